"""Aim pick, place, reach and hand-over: IK on the human body along the clip.

The clip's pose at its key event (grasp, release, reached, extended) is corrected by IK so
each aiming hand's grasp frame is at its target (hrc_drake.human.grasp: palms on an
object's faces), with the feet where they stand; arms, trunk bend and pelvis height (a
squat) are free. The hands come to it from outside: first to a point a little above it
and, for palms on an object's faces, a little wider apart (APPROACH), so that they close
on the object rather than sweeping through it or through what it stands on. A clip that
takes an object then carries it into the carry posture: the palms stay on its faces while
the object moves from where it was taken to where it is carried (the hands turn about
their palms' normal, IK at a few points of the way). A clip that puts an object down
starts from the carry posture, carries it above the target, sets it down, and opens the
hands outwards before they go back. The corrections are joint offsets at key times of
the clip, blended smoothly in between (`AimedMotion`).
"""

from dataclasses import dataclass

import numpy as np
from pydrake.math import RigidTransform, RotationMatrix

from hrc_drake.human.body import FrameTask, HumanBody
from hrc_drake.human.clip import Clip
from hrc_drake.human.grasp import CarryArms, arm_indices, hand_tasks, outward
from hrc_drake.human.keyed_clips import minimum_jerk
from hrc_drake.human.skeleton import SIDES

TARGETED = {
    "pick_floor": "grasp",
    "pick_table": "grasp",
    "place_floor": "release",
    "place_table": "release",
    "reach": "reached",
    "hand_over": "extended",
}
"""Clips that accept a target, and the event at which the hands arrive."""

HAND_TOLERANCE = 0.02
FOOT_TOLERANCE = 0.01
FEET_WEIGHT = (4.0, 4.0, 4.0)
"""Feet outrank hands in the IK: the person bends rather than sliding a foot."""
HOLD_AFTER_EVENT = 0.3
MAX_HORIZONTAL_REACH = 1.2
TRUNK = (
    "pelvis_height",
    "pelvis_tilt",
    "lumbar_flexion",
    "lumbar_bending",
    "thorax_flexion",
    "thorax_rotation",
)
APPROACH = (0.06, 0.06)
"""m: where the hands come to before they close on the target: this far outwards (palms
on an object's faces; a reaching hand: back towards the body) and this far above it."""
APPROACH_AT = 0.7
"""Fraction of the time to the event at which the hands are at the approach point."""
CARRY_SAMPLES = 8
"""Points of the way between the grasp and the carry posture at which the palms are put on
the object's faces by IK."""
CHEST = "chest"
"""The body the hands' way with a held object is laid out in."""


PALM_ORIENTATION = 1.0
"""Weight of a palm's orientation reaching for a target."""
HOLDING_ORIENTATION = 1.0
"""Weight of the hands' orientation while they hold an object on its way: a palm that
tilts pokes its fingers into the object."""


class Unreachable(ValueError):
    """The person cannot put a hand on the target without stepping."""


@dataclass(frozen=True, eq=False)
class AimedMotion:
    """Joint offsets that aim a clip: at each key time an offset added to the clip's pose;
    in between they ease from key to key (minimum jerk), or run straight through the evenly
    spaced keys of a carried object's way (`paths`; the way itself eases the object)."""

    times: tuple[float, ...]
    offsets: tuple[np.ndarray, ...]
    paths: tuple[tuple[int, int], ...] = ()
    """(first key, last key) of each stretch that is one smooth movement."""

    def offset(self, clip_time: float) -> np.ndarray:
        times = self.times
        if clip_time <= times[0]:
            return self.offsets[0]
        if clip_time >= times[-1]:
            return self.offsets[-1]
        for first, last in self.paths:
            if times[first] <= clip_time <= times[last]:
                return self._along(first, last, clip_time)
        k = int(np.searchsorted(times, clip_time, side="right")) - 1
        s = minimum_jerk((clip_time - times[k]) / (times[k + 1] - times[k]))
        return self.offsets[k] + s * (self.offsets[k + 1] - self.offsets[k])

    def _along(self, first: int, last: int, clip_time: float) -> np.ndarray:
        span = self.times[last] - self.times[first]
        u = (clip_time - self.times[first]) / span * (last - first)
        k = min(int(u), last - first - 1)
        a, b = self.offsets[first + k], self.offsets[first + k + 1]
        return a + (u - k) * (b - a)

    def pose(self, placed: np.ndarray, clip_time: float) -> np.ndarray:
        return placed + self.offset(clip_time)


def _hold_end(clip: Clip, event: str) -> float:
    later = sorted(t for t in clip.events.values() if t > clip.events[event])
    return later[0] if later else min(clip.events[event] + HOLD_AFTER_EVENT, clip.duration)


def _free_joints(body: HumanBody, sides, squat: bool) -> np.ndarray:
    """Arms of the aiming hands and the trunk; with `squat` also pelvis height and legs."""
    names = [n for n in body.joint_names if n in TRUNK and (squat or n != "pelvis_height")]
    parts = [(side, ("shoulder", "elbow", "wrist")) for side in sides]
    if squat:
        parts += [(side, ("hip", "knee", "ankle")) for side in SIDES]
    for side, joints in parts:
        names += [n for n in body.joint_names if n.startswith(side) and any(j in n for j in joints)]
    return np.array([body.index(n) for n in names])


def _feet_tasks(body: HumanBody, q: np.ndarray) -> list[FrameTask]:
    tasks = []
    for side in SIDES:
        X: RigidTransform = body.frame_pose(f"{side}_sole", q)
        tasks.append(
            FrameTask(
                f"{side}_sole",
                X.translation(),
                X.rotation(),
                FEET_WEIGHT,
                rotation_weights=(1.0, 1.0, 1.0),
            )
        )
    return tasks


def _reach(body: HumanBody, q: np.ndarray, hands: dict) -> np.ndarray:
    """q with the aiming hands' grasp frames on their targets, the feet where they stand
    (a squat if the hands cannot reach otherwise). Two palms on an object's faces may turn
    in them (fingers down or forward, as the arms reach best). Raises Unreachable."""
    feet = _feet_tasks(body, q)
    both = len(hands) == 2
    for squat, oriented in ((False, True), (True, True), (True, False)):
        aimed = hands if oriented else {s: (p, None) for s, (p, _) in hands.items()}
        tasks = hand_tasks(aimed, PALM_ORIENTATION, turn_in_palm=both)
        solved = body.solve(
            q,
            tasks + feet,
            _free_joints(body, tuple(hands), squat),
            iterations=150,
            posture_weight=1e-3,
        )
        hand_error = body.task_error(solved, tasks)
        feet_error = body.task_error(solved, feet) / FEET_WEIGHT[0]
        if hand_error <= HAND_TOLERANCE and feet_error <= FOOT_TOLERANCE:
            return solved
    if hand_error <= HAND_TOLERANCE:
        raise Unreachable("only reachable by stepping")
    raise Unreachable(f"hand stays {hand_error:.2f} m from the target")


def approached(hands: dict, heading: float, reaching: bool, opening: bool = True) -> dict:
    """The hands' targets moved to where they come before closing on them: above, and
    (`opening`) outwards from an object's faces (a reaching hand: back towards the body);
    hands that hold what they put down stay on it."""
    out, up = APPROACH
    back = -np.array([np.cos(heading), np.sin(heading), 0.0])
    moved = {}
    for side, (position, R) in hands.items():
        away = back if reaching or R is None else outward(side, R)
        moved[side] = (np.asarray(position) + opening * out * away + [0.0, 0.0, up], R)
    return moved


def aim_clip(
    body: HumanBody,
    clip: Clip,
    placed_pose,
    hands: dict,
    heading: float,
    carry: CarryArms | None = None,
    takes: bool = False,
) -> AimedMotion:
    """The joint offsets that make `clip` (placed in the world by `placed_pose`) put each
    hand's grasp frame at its target: `hands` maps a side to (position, orientation or
    None). `carry`: the carry posture of what the hands take (`takes`) or put down.

    `placed_pose(q)` maps a clip pose to the world. Raises Unreachable with a reason.
    """
    event_name = TARGETED[clip.name]
    event = clip.events[event_name]
    hold_end = _hold_end(clip, event_name)
    at_event = placed_pose(clip.sample(event))
    middle = np.mean([position for position, _ in hands.values()], axis=0)
    base = at_event[[body.index("base_x"), body.index("base_y")]]
    distance = float(np.linalg.norm(middle[:2] - base))
    if distance > MAX_HORIZONTAL_REACH:
        raise Unreachable(f"target {distance:.2f} m away, out of reach without walking")
    on_target = _reach(body, at_event, hands) - at_event
    approach_time = APPROACH_AT * event
    at_approach = placed_pose(clip.sample(approach_time))
    reaching = clip.name == "reach"
    near = approached(hands, heading, reaching, opening=carry is None or takes)
    try:
        near_offset = _reach(body, at_approach + on_target, near) - at_approach
    except Unreachable:
        near_offset = on_target
    marks = (approach_time, event, hold_end)
    if carry is not None and takes:
        return _taking(body, clip, placed_pose, hands, carry, near_offset, on_target, marks)
    if carry is not None:
        return _putting_down(
            body, clip, placed_pose, hands, heading, carry, near_offset, on_target, marks
        )
    zero = np.zeros_like(on_target)
    times = (0.0, approach_time, event, hold_end, clip.duration)
    return AimedMotion(times, (zero, near_offset, on_target, on_target, zero))


def _between(start: dict, end: dict, s: float) -> dict:
    """Targets of the holding hands a fraction s of the way from their grasp frames `start`
    to `end` (in one frame): each hand turns about its palm's normal as the object turns, two
    palms keep their spacing about their midpoint, which moves straight."""
    sides = tuple(start)
    turned = {side: _slerp(start[side].rotation(), end[side].rotation(), s) for side in sides}
    if len(sides) == 1:
        (side,) = sides
        a, b = start[side].translation(), end[side].translation()
        return {side: (a + s * (b - a), turned[side])}
    a, b = (np.mean([X[side].translation() for side in sides], axis=0) for X in (start, end))
    width = float(np.linalg.norm(start["left"].translation() - start["right"].translation()))
    middle = a + s * (b - a)
    return {side: (middle + outward(side, R) * width / 2, R) for side, R in turned.items()}


def _slerp(a: RotationMatrix, b: RotationMatrix, s: float) -> RotationMatrix:
    return RotationMatrix(a.ToQuaternion().slerp(s, b.ToQuaternion()))


def _way(body, clip, placed_pose, times, start, end, trunk_from, trunk_to, arms):
    """Offsets at `times` (evenly spaced) on the way of the holding hands from `start` to
    `end` (grasp frames in the chest's frame at the first and last time): the way runs in
    the chest's frame, which rises and turns with the trunk, so the arms can follow it; the
    arms are solved to hold the object, the rest of the body eases from the offset
    `trunk_from` to `trunk_to`."""
    offsets, solved = [], None
    for k, t in enumerate(times):
        s = k / (len(times) - 1)
        placed = placed_pose(clip.sample(t))
        q = placed + trunk_from + s * (trunk_to - trunk_from)
        if solved is not None:  # each point starts from the last: the arms follow the way
            q[arms] = solved[arms]
        chest = body.frame_pose(CHEST, q)
        local = _between(start, end, minimum_jerk(s))
        targets = {side: (chest @ p, chest.rotation() @ R) for side, (p, R) in local.items()}
        tasks = hand_tasks(targets, HOLDING_ORIENTATION)
        solved = body.solve(q, tasks, arms, iterations=60, posture_weight=1e-4)
        offsets.append(solved - placed)
    return offsets


def _in_chest(body: HumanBody, q: np.ndarray, sides) -> dict:
    """The hands' grasp frames in the chest's frame at q."""
    chest = body.frame_pose(CHEST, q).inverse()
    return {s: chest @ body.frame_pose(f"{s}_hand_grasp", q) for s in sides}


def _taking(body, clip, placed_pose, hands, carry, near_offset, on_target, marks):
    """Offsets of a clip that takes an object and carries it off in the carry posture."""
    approach_time, event, hold_end = marks
    sides = tuple(hands)
    grasped = placed_pose(clip.sample(hold_end)) + on_target
    end_pose = placed_pose(clip.sample(clip.duration))
    carried = carry.over(end_pose)
    start, end = _in_chest(body, grasped, sides), _in_chest(body, carried, sides)
    times = tuple(np.linspace(hold_end, clip.duration, CARRY_SAMPLES))
    zero = np.zeros_like(on_target)
    way = _way(
        body, clip, placed_pose, times, start, end, on_target, zero, arm_indices(body, sides)
    )
    way[0], way[-1] = on_target, carried - end_pose
    key_times = (0.0, approach_time, event, *times)
    offsets = (zero, near_offset, on_target, *way)
    return AimedMotion(key_times, offsets, ((3, len(key_times) - 1),))


def _putting_down(body, clip, placed_pose, hands, heading, carry, near_offset, on_target, marks):
    """Offsets of a clip that starts in the carry posture and puts the object down."""
    approach_time, event, hold_end = marks
    sides = tuple(hands)
    start_pose = placed_pose(clip.sample(0.0))
    held = carry.over(start_pose)
    above = placed_pose(clip.sample(approach_time)) + near_offset
    start, end = _in_chest(body, held, sides), _in_chest(body, above, sides)
    times = tuple(np.linspace(0.0, approach_time, CARRY_SAMPLES))
    zero = np.zeros_like(on_target)
    arms = arm_indices(body, sides)
    way = _way(body, clip, placed_pose, times, start, end, zero, near_offset, arms)
    way[0], way[-1] = held - start_pose, near_offset
    release_end = hold_end + 0.3 * (clip.duration - hold_end)
    at_open = placed_pose(clip.sample(release_end))
    try:
        open_offset = _reach(body, at_open + on_target, approached(hands, heading, False))
        open_offset = open_offset - at_open
    except Unreachable:
        open_offset = on_target
    key_times = (*times, event, hold_end, release_end, clip.duration)
    offsets = (*way, on_target, on_target, open_offset, zero)
    return AimedMotion(key_times, offsets, ((0, CARRY_SAMPLES - 1),))
