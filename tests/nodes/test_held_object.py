"""HeldObject: the person's tree finds the box the robot holds out at a hand-over."""

import pytest
from pydrake.math import RigidTransform
from pydrake.multibody.math import SpatialVelocity

from hrc_drake.bt import BTError, Status, load_tree
from hrc_drake.nodes import hrc_registry
from hrc_drake.nodes.agent import Agent, Places
from hrc_drake.workpieces import messages as wp


def objects_status(*held: tuple[int, str | None]) -> wp.WorkpiecesStatus:
    """One box per (id, holder) pair, at x = id."""
    objects = tuple(
        wp.ObjectStatus(
            id=object_id,
            type="box",
            pose=RigidTransform([float(object_id), 0.0, 1.0]),
            velocity=SpatialVelocity.Zero(),
            holder=holder,
            support=None,
            attributes={},
        )
        for object_id, holder in held
    )
    return wp.WorkpiecesStatus(time=0.0, objects=objects, results={}, free_slots={})


def tick_held_object(status, holder="robot"):
    xml = (
        '<root BTCPP_format="4"><BehaviorTree ID="Main">'
        f'<HeldObject holder="{holder}" object_id="{{id}}" pose="{{pose}}"/>'
        "</BehaviorTree></root>"
    )
    agent = Agent("human", Places())
    agent.statuses["workpieces"] = status
    tree = load_tree(xml, hrc_registry(), agent=agent)
    return tree.tick(0.0), tree.root_blackboard


def test_held_object_names_what_the_robot_holds():
    status, blackboard = tick_held_object(objects_status((1, None), (2, wp.ROBOT_HOLDER)))
    assert status is Status.SUCCESS
    assert blackboard.get("id") == 2
    assert blackboard.get("pose").position == (2.0, 0.0, 1.0)


def test_held_object_fails_when_the_holder_holds_nothing():
    status, _ = tick_held_object(objects_status((1, None), (2, wp.BOTH_HANDS)))
    assert status is Status.FAILURE
    assert tick_held_object(None)[0] is Status.FAILURE


def test_held_object_rejects_an_unknown_holder():
    with pytest.raises(BTError, match="port 'holder': unknown value 'gripper'; known: robot, "):
        tick_held_object(objects_status((1, wp.ROBOT_HOLDER)), holder="gripper")
