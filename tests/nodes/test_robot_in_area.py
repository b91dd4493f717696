"""RobotInArea and RobotAtRest: the person's tree sees whether the robot's tool works above
a tray and whether the robot holds still before they reach in."""

import pytest
from pydrake.math import RigidTransform

from hrc_drake.areas import Area
from hrc_drake.bt import Status, load_tree
from hrc_drake.motion.messages import RobotStatus
from hrc_drake.nodes import hrc_registry
from hrc_drake.nodes.agent import Agent, Places

TRAY = Area.from_polygon([[-0.6, -0.2], [-0.3, -0.2], [-0.3, 0.3], [-0.6, 0.3]])


def robot_status(tool_xyz=(0.0, 0.0, 0.9), mode="moving") -> RobotStatus:
    return RobotStatus(
        mode=mode,
        results=(),
        tool_pose=RigidTransform(list(tool_xyz)),
        tool_speed=0.0,
        speed_fraction=1.0,
        safety_scale=1.0,
        speed_scale=1.0,
    )


def tick_condition(node: str, status) -> Status:
    xml = f'<root BTCPP_format="4"><BehaviorTree ID="Main">{node}</BehaviorTree></root>'
    agent = Agent("human", Places(areas={"tray": TRAY}))
    agent.statuses["robot"] = status
    return load_tree(xml, hrc_registry(), agent=agent).tick(0.0)


def tick_robot_in_area(status) -> Status:
    return tick_condition('<RobotInArea area="tray"/>', status)


@pytest.mark.parametrize(
    ("tool", "expected"),
    [((-0.45, 0.0, 0.9), Status.SUCCESS), ((0.0, 0.5, 0.9), Status.FAILURE)],
    ids=["above the tray", "elsewhere"],
)
def test_robot_in_area_follows_the_tool_centre_point(tool, expected):
    assert tick_robot_in_area(robot_status(tool)) is expected


def test_robot_in_area_fails_without_robot_status():
    assert tick_robot_in_area(None) is Status.FAILURE


@pytest.mark.parametrize(
    ("mode", "expected"),
    [
        ("idle", Status.SUCCESS),
        ("moving", Status.FAILURE),
        ("stopping", Status.FAILURE),
        ("stopped", Status.FAILURE),
        ("planning", Status.FAILURE),
    ],
)
def test_robot_at_rest_only_without_a_motion_under_way(mode, expected):
    """A monitored stop (`stopped`) is a pause on the way, not rest."""
    assert tick_condition("<RobotAtRest/>", robot_status(mode=mode)) is expected


def test_robot_at_rest_fails_without_robot_status():
    assert tick_condition("<RobotAtRest/>", None) is Status.FAILURE
