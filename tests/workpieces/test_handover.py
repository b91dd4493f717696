"""Hand-over between the robot's vacuum cup and the person's hands, refused when far apart."""

import numpy as np
import pytest
from pydrake.math import RollPitchYaw

from hrc_drake.messages import FAILED, SUCCEEDED
from hrc_drake.workpieces.messages import BOTH_HANDS, ROBOT_HOLDER, Attach, Transfer
from tests.workpieces.workpieces_rig import (
    PART_HEIGHT,
    TABLE_TOP,
    TOOL_DOWN,
    build_rig,
    config_with,
    hands_path,
    part_on_table,
    path,
)

LEVEL = RollPitchYaw(0.0, 0.0, 0.0)
HANDOVER = np.array([0.0, 0.6, 1.2])
"""Where the robot presents the part: the cup on its top face."""
TAKEN = np.array([0.0, 0.4, 1.1])
"""Where the person then holds the part's top face centre."""
HALF_HEIGHT = PART_HEIGHT / 2
SIDE = 0.07
"""Hands 1 cm outside the part's ends (it is 0.12 m long)."""


def hand(side: float):
    """One hand's path: far, then at the part's end at the hand-over point, then moving it."""
    far = (side * 0.4, 0.0, 1.0)

    def at(point):
        return tuple(point + [side * SIDE, 0.0, -HALF_HEIGHT])

    return path(
        [
            (1.8, far, LEVEL),
            (2.3, at(HANDOVER), LEVEL),
            (3.5, at(HANDOVER), LEVEL),
            (4.0, at(TAKEN), LEVEL),
            (5.0, at(TAKEN), LEVEL),
            (5.5, far, LEVEL),
        ]
    )


TOOL = path(
    [
        (0.0, (0.0, 0.9, TABLE_TOP + PART_HEIGHT), TOOL_DOWN),
        (0.3, (0.0, 0.9, TABLE_TOP + PART_HEIGHT), TOOL_DOWN),
        (1.0, tuple(HANDOVER), TOOL_DOWN),
        (3.0, tuple(HANDOVER), TOOL_DOWN),
        (3.5, tuple(HANDOVER + [0.0, 0.0, 0.3]), TOOL_DOWN),
        (4.0, tuple(HANDOVER + [0.0, 0.0, 0.3]), TOOL_DOWN),
        (4.5, tuple(TAKEN), TOOL_DOWN),
    ]
)
COMMANDS = {
    "robot_gripper": [(0.2, Attach(seq=1, holder=ROBOT_HOLDER, max_mass=3.0))],
    "human_tree": [
        (1.5, Transfer(seq=1, object_id=1, to_holder=BOTH_HANDS)),
        (2.6, Transfer(seq=2, object_id=1, to_holder=BOTH_HANDS)),
    ],
    "robot_tree": [
        (3.8, Transfer(seq=1, object_id=1, to_holder=ROBOT_HOLDER, max_mass=3.0)),
        (4.7, Transfer(seq=2, object_id=1, to_holder=ROBOT_HOLDER, max_mass=3.0)),
    ],
}


@pytest.fixture(scope="module")
def run():
    rig = build_rig(
        config_with(objects=[part_on_table()]), COMMANDS, TOOL, hands_path(hand(-1), hand(1))
    )
    return {t: rig.advance(t) for t in (1.6, 2.7, 3.75, 3.9, 4.2, 4.8, 5.8)}


def centre(status) -> np.ndarray:
    return status.object(1).pose.translation()


def test_robot_to_person_is_refused_while_the_hands_are_far(run):
    result = run[1.6].results_of("human_tree").last
    assert (result.seq, result.outcome) == (1, FAILED)
    assert result.reason.startswith("hand-over refused: both_hands is 0.58")  # their midpoint
    assert run[1.6].object(1).holder == ROBOT_HOLDER


def test_robot_to_person_works_when_close_and_the_part_follows_the_hands(run):
    assert run[2.7].results_of("human_tree").outcome_of(2) == SUCCEEDED
    assert run[2.7].object(1).holder == BOTH_HANDS
    np.testing.assert_allclose(centre(run[4.2]), TAKEN - [0, 0, HALF_HEIGHT], atol=1e-6)


def test_the_part_follows_hands_sampled_at_60_hz_between_their_samples(run):
    between = (hand(-1)(3.75).translation() + hand(1)(3.75).translation()) / 2
    assert np.linalg.norm(centre(run[3.75]) - between) < 1e-3


def test_person_to_robot_is_refused_when_far_and_works_when_close(run):
    refused = run[3.9].results_of("robot_tree").last
    assert (refused.seq, refused.outcome) == (1, FAILED)
    assert refused.reason.startswith("hand-over refused: robot is")
    assert run[4.8].results_of("robot_tree").outcome_of(2) == SUCCEEDED
    assert run[5.8].object(1).holder == ROBOT_HOLDER
    np.testing.assert_allclose(centre(run[5.8]), TAKEN - [0, 0, HALF_HEIGHT], atol=1e-6)
