"""HumanActor in a Diagram: protocol, movement accuracy, progress, transitions, add_human."""

import itertools

import numpy as np
import pytest

from hrc_drake.human.body import human_body
from hrc_drake.human.clip import load_clips
from hrc_drake.human.messages import (
    AnimateCommand,
    CancelCommand,
    Grasp,
    MoveCommand,
    SetCalledCommand,
)
from hrc_drake.human.performer import Performer
from hrc_drake.human.protocol import ActorState, advance, pose_at
from hrc_drake.human.segments import TurnSegment
from hrc_drake.human.skeleton import REGIONS
from hrc_drake.safety.geometry import human_parts
from hrc_drake.wiring import HUMAN_MODEL
from tests.human.scene import COLLISION_SHAPES, FLOOR, SAMPLE, Run, furniture


def test_setup_then_idle_at_the_start_pose():
    run = Run([], start_pose=(1.0, 2.0, 0.5))
    status = run.advance(0.1)
    assert status.state == "IDLE"
    assert status.base_pose == pytest.approx((1.0, 2.0, 0.5), abs=0.03)
    assert len(status.right_hand) == 7


def test_command_while_busy_is_rejected_and_cancel_returns_to_idle():
    run = Run(
        [
            (0.1, AnimateCommand(1, "inspect")),
            (0.5, AnimateCommand(2, "wave")),
            (1.0, CancelCommand(3)),
        ]
    )
    status = run.advance(0.7)
    assert status.state == "ANIMATION"
    assert (status.results.last.seq, status.results.last.outcome) == (2, "rejected")
    assert status.results.outcome_of(1) == "running"
    status = run.advance(1.2)
    assert status.state == "IDLE"
    assert status.results.outcome_of(1) == "cancelled"
    assert status.results.outcome_of(3) == "succeeded"


def test_unknown_animation_fails_with_a_reason():
    status = Run([(0.1, AnimateCommand(1, "moonwalk"))]).advance(0.3)
    assert status.results.last.outcome == "failed" and "moonwalk" in status.results.last.reason


def test_set_called_does_not_disturb_a_running_animation():
    run = Run([(0.1, AnimateCommand(1, "wave")), (0.4, SetCalledCommand(2, True))])
    status = run.advance(0.6)
    assert status.called and status.state == "ANIMATION"
    assert status.results.outcome_of(1) == "running" and status.results.outcome_of(2) == "succeeded"


def _yaw(quaternion_yaw):
    return (np.cos(quaternion_yaw / 2), 0.0, 0.0, np.sin(quaternion_yaw / 2))


def test_movement_reaches_target_pose():
    target_yaw = np.radians(120)
    run = Run([(0.1, MoveCommand(1, (3.0, -1.5, 0.0), _yaw(target_yaw)))])
    status = run.advance(10.0)
    assert status.results.outcome_of(1) == "succeeded" and status.state == "IDLE"
    x, y, yaw = status.base_pose
    assert np.hypot(x - 3.0, y + 1.5) < 0.02
    assert abs(np.angle(np.exp(1j * (yaw - target_yaw)))) < np.radians(3)


def test_null_quaternion_ends_facing_the_walking_direction_via_waypoints():
    run = Run([(0.1, MoveCommand(1, (2.0, 2.0, 0.0), waypoints=((2.0, 0.0),)))])
    status = run.advance(10.0)
    x, y, yaw = status.base_pose
    assert status.results.outcome_of(1) == "succeeded"
    assert np.hypot(x - 2.0, y - 2.0) < 0.02
    assert abs(np.angle(np.exp(1j * (yaw - np.pi / 2)))) < np.radians(3)


GAIT_CYCLE = 1.1
"""s: one gait cycle at the preferred pace (docs/human-body.md)."""
PELVIS_SPEED_SWING = 0.15
"""Published swing of the forward speed within a stride at a normal pace, as a fraction of
its mean (about ±10-15 %; Cavagna et al. 1977, docs/realism.md)."""
STANCE_SLIP = 0.01
"""m: how far a sole point standing on the floor may slide (docs/realism.md)."""
ON_FLOOR = 0.003
"""m: a sole point this close to the floor stands on it (the realism audit's)."""


def _stance_slip(body, poses) -> float:
    """Largest horizontal travel of a sole point during one spell on the floor."""
    tracks = {}
    for q in poses:
        for name, point in body.sole_points(q).items():
            tracks.setdefault(name, []).append(point)
    worst = 0.0
    for track in map(np.array, tracks.values()):
        start = None
        for k, on_floor in enumerate(np.append(track[:, 2] < ON_FLOOR, False)):
            if on_floor and start is None:
                start = k
            elif not on_floor and start is not None:
                spell = track[start:k, :2]
                worst = max(worst, float(np.max(np.linalg.norm(spell - spell[0], axis=1))))
                start = None
    return worst


def test_walk_speed_and_planted_feet_in_the_actor():
    run = Run([(0.1, MoveCommand(1, (8.0, 0.0, 0.0)))])
    statuses, poses = run.record(9.0)
    arrived = next(s.time for s in statuses if s.base_pose[0] >= 8.0 - 0.005)
    assert 1.2 <= 8.0 / (arrived - 0.1 - 0.6) <= 1.4  # cruising speed; ramps cost 0.6 s
    done = next(s.time for s in statuses if s.results.outcome_of(1) == "succeeded")
    assert arrived <= done <= arrived + GAIT_CYCLE  # the last step closes the feet
    assert _stance_slip(run.body, poses) < STANCE_SLIP


def test_feet_set_down_without_sliding_round_a_corner_from_a_standstill():
    """The first steps lag behind the clip's (the body still speeds up) and the path turns:
    each foot still comes down onto its step, not gliding along the floor."""
    run = Run(
        [(0.1, MoveCommand(1, (1.2, 3.0, 0.0), waypoints=((-0.06, 0.61),)))],
        start_pose=(0.0, 0.0, 1.67),
    )
    _, poses = run.record(6.0)
    assert _stance_slip(run.body, poses) < STANCE_SLIP


def test_a_walk_turns_to_face_its_place_over_its_last_steps():
    """Arriving at a place to stand that faces 40 degrees off the way there, the person
    turns while walking in, without a turn on the spot and without sliding a foot."""
    run = Run([(0.1, MoveCommand(1, (3.0, 0.0, 0.0), _yaw(np.radians(40))))])
    statuses, poses = run.record(5.5)
    segments = run.context.get_abstract_state(0).get_value().activity.segments
    assert not any(isinstance(s, TurnSegment) and s.cycles for s in segments)
    assert statuses[-1].results.outcome_of(1) == "succeeded"
    assert abs(statuses[-1].base_pose[2] - np.radians(40)) < np.radians(3)
    assert _stance_slip(run.body, poses) < STANCE_SLIP


PELVIS_EXCURSION = 0.05
"""m: the pelvis (the body's centre of mass) rises and falls about 5 cm peak to peak in a
step of normal walking (Saunders, Inman and Eberhart 1953; docs/human-body.md): it never
comes lower than that below its standing height."""
INTO_FLOOR = 0.01
"""m: how far the body may go into the floor (the realism audit's penetration limit)."""


@pytest.mark.parametrize(
    ("goal", "start_yaw"),
    [((0.77, 0.0), 0.0), ((1.5, 0.0), 0.0), ((0.75, -0.15), 1.77)],
    ids=["short walk", "a stride and a half", "after a turn on the spot"],
)
def test_the_first_steps_keep_the_pelvis_up_and_the_feet_above_the_floor(goal, start_yaw):
    """Walks from a standstill whose first steps close the feet at the goal: the body does
    not sag to put a foot down far ahead of it, nor does a foot sink into the floor."""
    run = Run([(0.1, MoveCommand(1, (*goal, 0.0)))], start_pose=(0.0, 0.0, start_yaw), cell=[FLOOR])
    run.advance(0.05)
    standing = run.body.frame_pose("pelvis", run.positions()[run.body.plant_index]).translation()
    statuses, poses = run.record(4.0)
    assert statuses[-1].results.outcome_of(1) == "succeeded"
    lowest = min(run.body.frame_pose("pelvis", q).translation()[2] for q in poses)
    assert lowest >= standing[2] - PELVIS_EXCURSION, f"pelvis down to {lowest:.3f} m"
    assert run.overlap[0] <= INTO_FLOOR, run.overlap
    assert _stance_slip(run.body, poses) < STANCE_SLIP


def test_pelvis_speed_within_a_stride_swings_as_published():
    run = Run([(0.1, MoveCommand(1, (8.0, 0.0, 0.0)))])
    statuses, _ = run.record(7.0)
    times = np.array([s.time for s in statuses])
    x = np.array([s.base_pose[0] for s in statuses])
    speed = np.gradient(x, times)
    for start in np.arange(2.0, 5.0, GAIT_CYCLE / 2):  # cruising: strides after the ramp
        stride = speed[(times >= start) & (times < start + GAIT_CYCLE)]
        swing = (stride.max() - stride.min()) / 2 / stride.mean()
        assert swing <= PELVIS_SPEED_SWING, f"stride from {start:.2f} s: ±{swing:.0%}"


def test_a_turn_cancelled_halfway_finishes_its_step_without_sliding_a_foot():
    run = Run(
        [(0.1, MoveCommand(1, (0.0, 0.0, 0.0), _yaw(np.radians(170)))), (0.8, CancelCommand(2))]
    )
    statuses, poses = run.record(4.0)
    assert statuses[-1].results.outcome_of(1) == "cancelled" and statuses[-1].state == "IDLE"
    assert _stance_slip(run.body, poses) < STANCE_SLIP


@pytest.mark.parametrize("tell", [0.45, 1.05, 1.45], ids=["speeding up", "mid-swing", "cruising"])
def test_a_walk_cancelled_under_way_stops_on_its_feet_without_sliding_one(tell):
    """Stopped by a cancel (or by the robot coming to rest in its way), the foot in the air
    goes on to its new step and lands there, and no standing foot moves: a fade of the
    whole pose slid a landed foot 9.1 / 2.6 / 1.5 cm at these instants."""
    move = MoveCommand(1, (2.5, 0.0, 0.0))
    run = Run([(0.1, move), (tell, (move, CancelCommand(2)))], start_pose=(-1.5, 0.0, 0.0))
    statuses, poses = run.record(4.0)
    assert statuses[-1].results.outcome_of(1) == "cancelled" and statuses[-1].state == "IDLE"
    assert _stance_slip(run.body, poses) < STANCE_SLIP


@pytest.mark.parametrize("cut_at", [0.5, 0.9], ids=["reaching out", "at the grasp"])
def test_a_pick_cancelled_at_the_table_idles_where_its_feet_stand(cut_at):
    """A pick leans the pelvis 2 cm towards the table; cancelled part way (the part it was
    for is gone), the person idles where they stood, the lean fading out over still feet
    (idled from the leaning pelvis, both feet slid 2 cm: coexistence seed 5 at 84.8 s)."""
    grasp = Grasp("both", (0.1, 0.4, 0.94), np.pi / 2, (0.16, 0.12, 0.08))
    schedule = [
        (0.1, AnimateCommand(1, "pick_table", grasp=grasp)),
        (0.1 + cut_at, CancelCommand(2)),
    ]
    table = furniture("work_table", 0.0, 0.55)
    run = Run(schedule, start_pose=(0.0, 0.0, np.pi / 2), cell=[FLOOR, table])
    statuses, poses = run.record(cut_at + 3.0)
    assert statuses[-1].results.outcome_of(1) == "cancelled" and statuses[-1].state == "IDLE"
    assert _stance_slip(run.body, poses) < STANCE_SLIP


def test_animation_progress_rises_and_speed_two_halves_the_duration():
    durations = {}
    for speed in (1.0, 2.0):
        run = Run([(0.1, AnimateCommand(1, "reach", speed))])
        statuses, _ = run.record(3.0)
        running = [s for s in statuses if s.results.outcome_of(1) == "running"]
        progress = [s.progress for s in running]
        assert progress[0] < 0.05 and np.all(np.diff(progress) >= 0)
        done = next(s for s in statuses if s.results.outcome_of(1) == "succeeded")
        assert done.progress == 1.0
        durations[speed] = done.time - 0.1
    assert durations[2.0] == pytest.approx(durations[1.0] / 2, abs=2 * SAMPLE)


def test_events_fire_during_the_clip():
    run = Run([(0.1, AnimateCommand(1, "pick_table"))])
    statuses, _ = run.record(3.0)
    fired = [s for s in statuses if s.event == "grasp"]
    assert len(fired) == 1
    assert fired[0].time == pytest.approx(
        0.1 + load_clips()["pick_table"].events["grasp"], abs=0.03
    )


def test_targeted_pick_puts_the_hands_on_the_target():
    target = (0.5, 0.1, 0.75)
    run = Run([(0.1, AnimateCommand(1, "pick_table", target=target))])
    grasp = 0.1 + load_clips()["pick_table"].events["grasp"]
    run.advance(grasp)
    q = run.positions()[run.body.plant_index]
    hands = [run.body.frame_pose(f"{s}_hand_grasp", q).translation() for s in ("left", "right")]
    assert np.linalg.norm(np.mean(hands, axis=0) - target) < 0.02


def test_unreachable_target_fails_without_moving():
    run = Run([(0.1, AnimateCommand(1, "reach", target=(2.5, 0.0, 1.0)))])
    status = run.advance(0.5)
    assert status.results.last.outcome == "failed" and "reach" in status.results.last.reason
    assert status.state == "IDLE"


ANIMATIONS = [
    "idle",
    "pick_floor",
    "pick_table",
    "place_floor",
    "place_table",
    "inspect",
    "reach",
    "hand_over",
    "wave",
    "look_around",
    "turn_left",
]


def _max_speed(poses):
    """Largest joint speed between consecutive updates (rad/s)."""
    return np.abs(np.diff(poses[:, 3:], axis=0)).max() / SAMPLE


@pytest.mark.parametrize("first", ANIMATIONS)
def test_transition_speeds_stay_bounded(first):
    """Every clip, cancelled halfway, then every other clip: joint speeds under 10 rad/s."""
    schedule, t, seq = [], 0.1, itertools.count(1)
    for second in ANIMATIONS:
        half = load_clips()[first].duration / 2
        schedule += [
            (t, AnimateCommand(next(seq), first)),
            (t + half, CancelCommand(next(seq))),
            (t + half + 0.1, AnimateCommand(next(seq), second)),
        ]
        t += half + 0.1 + load_clips()[second].duration + 0.1
    _, poses = Run(schedule).record(t)
    assert _max_speed(poses) < 10.0


def _pose_jump(performer, state, t, command):
    """Joint jump (rad) when `command` is handled at time t, compared at the same instant."""
    before = pose_at(performer, state, t)
    state = advance(performer, state, t, {"human": command})
    return state, np.abs(pose_at(performer, state, t) - before)[3:].max()


def test_transitions_between_every_pair_of_clips_have_no_jump():
    performer = Performer(human_body(), load_clips())
    state, seq, worst = advance(performer, ActorState(), 0.0, {}), 0, 0.0
    t = 0.0
    for first, second in itertools.product(ANIMATIONS, ANIMATIONS):
        for command, wait in (
            (AnimateCommand(seq + 1, first), 0.37),
            (CancelCommand(seq + 2), 0.2),
            (AnimateCommand(seq + 3, second), 0.0),
        ):
            state, jump = _pose_jump(performer, state, t, command)
            worst = max(worst, jump)
            t += wait
        t += performer.clips[second].duration / 1.0 + 0.05
        state, jump = _pose_jump(performer, state, t, None)
        worst = max(worst, jump)
        seq += 3
    assert worst < np.radians(0.5)


def test_walk_transitions_are_continuous():
    run = Run(
        [
            (0.1, MoveCommand(1, (2.0, 1.0, 0.0), _yaw(-2.0))),
            (2.0, CancelCommand(2)),
            (2.6, MoveCommand(3, (0.0, 0.0, 0.0), _yaw(0.0), "carry")),
        ]
    )
    _, poses = run.record(9.0)
    assert _max_speed(poses) < 10.0


def test_regions_cover_every_collision_geometry():
    run = Run([])
    inspector = run.scene_graph.model_inspector()
    parts = human_parts(run.plant, inspector, run.plant.GetModelInstanceByName(HUMAN_MODEL))
    assert len(parts) == COLLISION_SHAPES and {part.name for part in parts} == set(REGIONS)
