"""The arms' check of a walk (hrc_drake.human.clearance) poses the walk without placing the
feet: placing a foot moves only its leg's joints and no arm hangs from a leg, so the arms
stand exactly where the played walk has them and the check finds the same, for less work."""

import numpy as np

from hrc_drake.human.arm_shapes import arms_in_world
from hrc_drake.human.body import human_body
from hrc_drake.human.clip import load_clips
from hrc_drake.human.legs import LEG_JOINTS
from hrc_drake.human.messages import MoveCommand
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
