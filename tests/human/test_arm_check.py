"""The arms' check of a walk (hrc_drake.human.clearance) poses the walk without placing the
feet: placing a foot moves only its leg's joints and no arm hangs from a leg, so the arms
stand exactly where the played walk has them and the check finds the same, for less work."""

import numpy as np
import shapely

from hrc_drake.human.arm_shapes import Prisms, arms_in_world, check_arm
from hrc_drake.human.body import human_body
from hrc_drake.human.clearance import _held_check, _Keep, _tolerance, push_out
from hrc_drake.human.clip import load_clips
from hrc_drake.human.furniture import Furniture
from hrc_drake.human.grasp import arm_indices
from hrc_drake.human.legs import LEG_JOINTS
from hrc_drake.human.messages import MoveCommand
from hrc_drake.human.navigation import Obstacle
from hrc_drake.human.performer import Performer
from hrc_drake.human.planning import plan_movement
from hrc_drake.human.skeleton import SIDES
from hrc_drake.human.walking import WalkSegment


def _walk(performer: Performer) -> WalkSegment:
    command = MoveCommand(1, (2.5, 1.0, 0.0))
    activity = plan_movement(performer, command, (0.0, 0.0, 0.0), 0.0)
    return next(s for s in activity.segments if isinstance(s, WalkSegment))


def test_a_walks_arms_stand_as_in_the_walk_with_its_feet_placed():
    performer = Performer(human_body(), load_clips())
    walk = _walk(performer)
    legs = [performer.index(f"{side}_{joint}") for side in SIDES for joint in LEG_JOINTS]
    rest = np.setdiff1d(np.arange(len(performer.standing)), legs)
    legs_moved = 0
    for t in np.linspace(walk.start, walk.end(performer), 30):
        played, for_the_arms = walk.pose(performer, t), walk.arms_pose(performer, t)
        assert np.array_equal(played[rest], for_the_arms[rest])
        played_arms = arms_in_world(performer.body, played, SIDES)
        checked_arms = arms_in_world(performer.body, for_the_arms, SIDES)
        assert all(np.array_equal(played_arms[s], checked_arms[s]) for s in SIDES)
        legs_moved += not np.array_equal(played[legs], for_the_arms[legs])
    assert legs_moved > 20  # the played walk places its feet; the arms' pose leaves them


def test_the_arms_checked_all_at_once_are_clear_where_each_arm_checked_alone_is():
    """The arm check screens the poses of a pass all at once (`_Keep.clear`); the pushes
    measure one arm at one pose (`check_arm`). Round a table and a box beside it, with the
    arms thrown about, hands held or free and the pelvis near and far, both answer alike."""
    body = human_body()
    rng = np.random.default_rng(7)
    table = Obstacle("table", shapely.box(0.3, -0.6, 1.2, 0.6), 0.0, 1.05)
    box = Obstacle("box", shapely.box(0.5, 0.7, 0.8, 1.0), 0.0, 1.3)
    keep = _Keep.of(Furniture((table,)), 0.0, (Furniture((table, box)), 1.0))
    arms = np.concatenate([arm_indices(body, (side,)) for side in SIDES])
    times, poses, holdings = [], [], []
    for k in range(300):
        q = body.standing_pose().copy()
        q[:3] = rng.uniform(-0.2, 1.0), rng.uniform(-1.0, 1.3), rng.uniform(-np.pi, np.pi)
        q[arms] += rng.normal(0.0, 0.8, len(arms))
        times.append(k / 150.0)
        poses.append(q)
        holdings.append(tuple(s for s in SIDES if rng.random() < 0.3))
    together = keep.clear(body, times, poses, holdings)
    alone = [
        all(
            check_arm(body, keep.near(t, q), q, s).depth <= _tolerance(s, holding)
            for s in SIDES
            if len(keep.near(t, q).axes)
        )
        for t, q, holding in zip(times, poses, holdings, strict=True)
    ]
    assert list(together) == alone
    assert 30 < sum(alone) < 270  # arms both in and out of the furniture


def test_a_holding_hand_stays_where_it_holds_while_its_forearm_is_pushed_down_off_a_board():
    """A forearm reaching under a shelf's board goes 2 cm into it: the arm is pushed down out
    of it with the holding hand kept on what it holds. Free to slide along the way out, the
    hand went 4 cm down with it (into what the held tote was being lowered onto; in a user's
    cell, hands pushed so rose 2.3 cm and the tote went 5 cm into the board)."""
    body = human_body()
    q = body.standing_pose().copy()
    q[body.index("right_shoulder_flexion")] = np.radians(60)
    q[body.index("right_elbow_flexion")] = np.radians(30)
    hand = body.frame_pose("right_hand_grasp", q).translation()
    elbow = body.frame_pose("right_forearm", q).translation()
    underside = elbow[2] + 0.02
    outline = shapely.box(hand[0] - 0.3, elbow[1] - 0.3, hand[0] + 0.3, elbow[1] + 0.6)
    near = Prisms.of(Furniture((Obstacle("board", outline, underside, underside + 0.04),)))
    check = _held_check(body, near, q, "right")
    assert check.depth > 0.02 and check.out[2] == -1.0
    pushed = push_out(body, q, "right", check, keep_hand=True)
    moved = body.frame_pose("right_hand_grasp", pushed).translation() - hand
    assert np.linalg.norm(moved) <= 0.01, moved
