"""Move: a free object set down elsewhere (a box squared up in its place, or knocked askew)."""

import math

import numpy as np
import pytest
from pydrake.math import RigidTransform, RotationMatrix

from hrc_drake.messages import FAILED, SUCCEEDED
from hrc_drake.workpieces.geometry import yaw_of
from hrc_drake.workpieces.messages import ROBOT_HOLDER, Move
from tests.workpieces.workpieces_rig import (
    PART_HEIGHT,
    TABLE_TOP,
    WORK_TABLE_XY,
    build_rig,
    carry_to,
    config_with,
    part_on_table,
)


def test_a_moved_object_stands_turned_where_it_was_set_down():
    turned = RigidTransform(
        RotationMatrix.MakeZRotation(math.radians(5.0)), [0.05, WORK_TABLE_XY[1], 1.2]
    )
    rig = build_rig(
        config_with(objects=[part_on_table()]), {"robot_tree": [(0.1, Move(1, 1, turned))]}
    )
    status = rig.advance(1.0)
    moved = status.object(1)
    assert status.results_of("robot_tree").outcome_of(1) == SUCCEEDED
    assert math.degrees(yaw_of(moved.pose.rotation())) == pytest.approx(5.0, abs=1e-6)
    np.testing.assert_allclose(
        moved.pose.translation(), [0.05, WORK_TABLE_XY[1], TABLE_TOP + PART_HEIGHT / 2], atol=1e-3
    )
    assert moved.support == "work_table"


def test_a_held_object_is_not_moved():
    tool, commands = carry_to((0.3, WORK_TABLE_XY[1], 1.2))
    commands["robot_tree"] = [(1.0, Move(1, 1, RigidTransform([0.3, WORK_TABLE_XY[1], 1.0])))]
    status = build_rig(config_with(objects=[part_on_table()]), commands, tool).advance(1.2)
    assert status.object(1).holder == ROBOT_HOLDER
    assert status.results_of("robot_tree").outcome_of(1) == FAILED
