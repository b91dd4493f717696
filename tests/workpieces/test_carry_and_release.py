"""The robot's vacuum cup carries an object and releases it onto a table, a stack, the floor."""

import numpy as np
import pytest
from pydrake.common.eigen_geometry import AngleAxis
from pydrake.common.schema import Transform

from hrc_drake.messages import FAILED, SUCCEEDED
from hrc_drake.workpieces.config import GridLayout, WorkpiecesConfig
from hrc_drake.workpieces.messages import ROBOT_HOLDER, Attach
from tests.workpieces.workpieces_rig import (
    PART_HEIGHT,
    PART_TOP,
    TABLE_TOP,
    TOOL_DOWN,
    X,
    Y,
    build_rig,
    carry_to,
    config_with,
    part_on_table,
    path,
)

PERIOD = WorkpiecesConfig().period


def test_gripped_object_follows_the_tool_and_rests_on_the_table_when_released():
    tool, commands = carry_to((X + 0.4, Y - 0.2, PART_TOP + 0.03))
    rig = build_rig(config_with(objects=[part_on_table()]), commands, tool)
    X_TO = tool(0.0).inverse() @ rig.status().object(1).pose
    geometry_id = rig.status().object(1).geometry_id
    position_errors, angle_errors = [], []
    for t in np.arange(0.5, 3.1, 0.0173):  # between the 10 ms updates too
        status = rig.advance(t)
        assert status.object(1).holder == ROBOT_HOLDER
        expected = tool(t) @ X_TO
        for pose in (status.object(1).pose, rig.query().GetPoseInWorld(geometry_id)):
            error = expected.inverse() @ pose
            position_errors.append(np.linalg.norm(error.translation()))
            angle_errors.append(AngleAxis(error.rotation().matrix()).angle())
    assert max(position_errors) < 1e-3
    assert max(angle_errors) < 1e-2
    resting = rig.advance(4.0).object(1)
    assert resting.holder is None and resting.support == "work_table"
    assert abs(resting.pose.translation()[2] - (TABLE_TOP + PART_HEIGHT / 2)) < 1e-3
    np.testing.assert_allclose(resting.pose.translation()[:2], [X + 0.4, Y - 0.2], atol=1e-9)
    assert resting.velocity.get_coeffs() == pytest.approx(np.zeros(6))


def test_released_over_a_stack_rests_on_the_top_object():
    stack = GridLayout(type="part", origin=Transform(translation=[X + 0.4, Y, TABLE_TOP]), layers=3)
    stack_top = TABLE_TOP + 3 * PART_HEIGHT
    tool, commands = carry_to((X + 0.41, Y + 0.01, stack_top + PART_HEIGHT + 0.05))
    config = config_with(objects=[part_on_table()], grids=[stack])
    rig = build_rig(config, commands, tool)
    status = rig.advance(4.0)
    carried = status.object(1)
    assert status.results_of("robot_gripper").last.outcome == SUCCEEDED
    assert carried.support == "object:4"
    assert abs(carried.pose.translation()[2] - (stack_top + PART_HEIGHT / 2)) < 1e-3
    assert [status.object(i).support for i in (2, 3, 4)] == ["work_table", "object:2", "object:3"]


def test_released_over_the_floor_rests_on_the_floor():
    tool, commands = carry_to((X + 0.2, Y - 0.9, 0.6))
    rig = build_rig(config_with(objects=[part_on_table()]), commands, tool)
    carried = rig.advance(4.0).object(1)
    assert carried.support == "floor"
    assert abs(carried.pose.translation()[2] - PART_HEIGHT / 2) < 1e-3


def test_a_grip_after_a_pause_takes_the_object_at_the_tools_speed_now():
    """Everything rests while the tool comes down onto the part (the workpieces leave their
    updates out); gripped by a tool at rest, the part is at rest, not moving at the tool's
    average speed since the world's last update (a failed grip far above it)."""
    tool = path([(0.2, (X, Y, PART_TOP + 0.4), TOOL_DOWN), (1.0, (X, Y, PART_TOP), TOOL_DOWN)])
    too_far = Attach(seq=1, holder=ROBOT_HOLDER, max_mass=3.0)
    grip = Attach(seq=2, holder=ROBOT_HOLDER, max_mass=3.0)
    commands = {"robot_gripper": [(0.3, too_far), (1.5, grip)]}
    rig = build_rig(config_with(objects=[part_on_table()]), commands, tool)
    assert rig.advance(0.4).results_of("robot_gripper").outcome_of(1) == FAILED
    gripped = rig.advance(1.5 + PERIOD / 2)
    assert gripped.results_of("robot_gripper").outcome_of(2) == SUCCEEDED
    assert gripped.object(1).velocity.get_coeffs() == pytest.approx(np.zeros(6))
    np.testing.assert_allclose(gripped.object(1).pose.translation()[:2], [X, Y], atol=1e-9)
