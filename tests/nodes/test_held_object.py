"""The boxes the person handles: HeldObject finds the box the robot holds out at a hand-over,
NextObject which free box is taken next, ActorPlace where a box put down goes."""

from dataclasses import replace

import numpy as np
import pytest
from pydrake.math import RigidTransform
from pydrake.multibody.math import SpatialVelocity

from hrc_drake.bt import BTError, Status, load_tree
from hrc_drake.human import messages as human
from hrc_drake.nodes import hrc_registry
from hrc_drake.nodes.agent import Agent, Places
from hrc_drake.nodes.stacks import on_top_of_what_lies_there
from hrc_drake.safety.messages import SafetyStatus
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


@pytest.mark.parametrize(
    ("second_x", "taken"),
    [(1.02, 2), (1.17, 1)],
    ids=["on the first", "beside it, touching"],
)
def test_next_object_offers_the_box_on_top_before_the_one_under_it(second_x, taken):
    """Box 1, the oldest, has box 2 lying on it: the person takes box 2 first (pulling box 1
    out from under it put their hand into box 2). A box that only touches box 1's edge
    (settling may name it as its support) does not keep box 1 back."""
    objects = (
        _material(1, (1.0, 0.0, 0.94)),
        _material(2, (second_x, 0.0, 1.02), support=wp.object_support(1)),
    )
    xml = (
        '<root BTCPP_format="4"><BehaviorTree ID="Main">'
        '<NextObject area="-9,-9;9,-9;9,9;-9,-9;9,9;-9,9" object_id="{id}"/>'
        "</BehaviorTree></root>"
    )
    agent = Agent("human", Places())
    agent.statuses["workpieces"] = wp.WorkpiecesStatus(0.0, objects, {}, {})
    tree = load_tree(xml, hrc_registry(), agent=agent)
    assert tree.tick(0.0) is Status.SUCCESS
    assert tree.root_blackboard.get("id") == taken


MATERIAL = (0.16, 0.12, 0.08)


def _material(object_id, position, holder=None, support=None) -> wp.ObjectStatus:
    return wp.ObjectStatus(
        id=object_id,
        type="material",
        pose=RigidTransform(position),
        velocity=SpatialVelocity.Zero(),
        holder=holder,
        support=support,
        attributes={},
        size=MATERIAL,
    )


def test_a_box_put_down_where_others_lie_goes_on_top_of_them():
    """The person puts a box onto the stack at the target, not into it (their hands went
    9 cm into the box already there); a box 0.3 m away is left alone."""
    held = _material(9, (0.0, 0.0, 1.2), holder=wp.BOTH_HANDS)
    target = (0.05, 0.0, 0.94)
    apart = [_material(1, (0.3, 0.0, 0.94))]
    assert on_top_of_what_lies_there(target, held, [held, *apart])[2] == pytest.approx(0.94)
    one = [*apart, _material(2, (0.0, 0.0, 0.94))]
    assert on_top_of_what_lies_there(target, held, [held, *one])[2] == pytest.approx(1.02)
    two = [*one, _material(3, (0.02, 0.0, 1.02))]
    assert on_top_of_what_lies_there(target, held, [held, *two])[2] == pytest.approx(1.10)


def test_an_animation_keeps_the_arms_out_of_the_objects_where_the_person_stands():
    """A kitting cell of our own: inspecting at a work table with three kits stacked on it,
    a hand went 14.1 cm into one; the animation was not told of them as a pick or a reach
    near them is. The objects within reach of where the person stands (not a far one, not
    one held) go with the animation."""
    objects = (
        _material(1, (0.3, 0.4, 0.95)),
        _material(2, (3.0, 0.0, 0.95)),
        _material(3, (0.0, 0.2, 1.0), holder=wp.BOTH_HANDS),
    )
    nearby = _nearby_told('<ActorAnimation animation_name="inspect"/>', objects, 1.57)
    assert nearby == ["material 1"]


def _nearby_told(node_xml: str, objects, heading: float, safety=None) -> list[str]:
    """The objects a tree of one person node tells the person to keep the arms out of,
    the person at the origin facing `heading`, with `objects` in the cell and the safety
    monitor's `safety` status."""
    return [box.name for box in _told(node_xml, objects, heading, safety).nearby]


def _told(node_xml: str, objects, heading: float, safety=None):
    """The command a tree of one person node sends (as `_nearby_told`)."""
    xml = f'<root BTCPP_format="4"><BehaviorTree ID="Main">{node_xml}</BehaviorTree></root>'
    agent = Agent("human", Places())
    agent.statuses["workpieces"] = wp.WorkpiecesStatus(
        time=0.0, objects=tuple(objects), results={}, free_slots={}
    )
    agent.statuses["human"] = human.HumanStatus(base_pose=(0.0, 0.0, heading))
    agent.statuses["safety"] = safety
    load_tree(xml, hrc_registry(), agent=agent).tick(0.0)
    (command,) = agent.take_outbox()["human"]
    return command


def _robot(speed: float) -> SafetyStatus:
    """The monitor's status of a robot whose forearm (0.6 m, radius 0.06) slants down from
    (0.3, 0, 1.3) to the gripper over (0.5, 0, 1.0), moving at `speed`."""
    starts = np.array([[0.3, 0.0, 1.3], [0.5, 0.0, 1.15]])
    spans = np.array([[0.2, 0.0, -0.15], [0.0, 0.0, -0.15]])
    return SafetyStatus(robot_speed=speed, robot_parts=(starts, spans, np.array([0.06, 0.03])))


@pytest.mark.parametrize("speed, kept", [(0.0, True), (0.3, False)], ids=["at rest", "moving"])
def test_a_pick_keeps_the_arms_out_of_the_robot_at_rest(speed, kept):
    """A user's machine-tending cell: the robot stopped with its wrist over the outfeed
    table, and the person's hand went 3.7 cm into the gripper picking a part beside it.
    The robot at rest is among what the arms keep out of, in boxes that hold each capsule
    the safety monitor bounds it by; moving, it will be elsewhere by then."""
    taken = _material(1, (0.5, 0.3, 0.95))
    command = _told('<ActorPick object_id="1"/>', (taken,), 0.0, _robot(speed))
    robot = [box for box in command.nearby if box.name == "the robot at rest"]
    assert bool(robot) == kept
    if kept:
        for point in ([0.3, 0.0, 1.3], [0.4, 0.059, 1.225], [0.5, 0.0, 1.0], [0.5, 0.029, 1.05]):
            assert any(_inside(point, box) for box in robot), point
        volume = sum(np.prod(box.size) for box in robot)
        assert volume < 3 * (np.pi * 0.06**2 * 0.25 + np.pi * 0.03**2 * 0.15)


def test_a_hand_over_reaches_into_the_robots_cup_at_rest():
    held = replace(_material(1, (0.5, 0.0, 0.95)), holder=wp.ROBOT_HOLDER)
    node = '<ActorHandOver object_id="1"/>'
    assert "the robot at rest" not in _nearby_told(node, (held,), 0.0, _robot(0.0))


def _inside(point, box: human.Box) -> bool:
    """Whether `point` lies in `box` (its centre, heading and extents)."""
    offset = np.subtract(point, box.center)
    c, s = np.cos(box.yaw), np.sin(box.yaw)
    local = (c * offset[0] + s * offset[1], -s * offset[0] + c * offset[1], offset[2])
    return all(abs(v) <= size / 2 + 1e-9 for v, size in zip(local, box.size, strict=True))


@pytest.mark.parametrize("speed, kept", [(0.0, True), (0.3, False)], ids=["still", "moving"])
def test_a_pick_keeps_the_arms_out_of_a_box_the_stopped_robot_holds_over_it(speed, kept):
    """A user's palletizing cell: the robot, stopped as the person came, held a carton just
    over the belt's end while the person took the next one off the belt: a forearm went
    14.9 cm through the hanging carton and the carton lifted went 16.4 cm into it. What the
    robot holds still is among what the pick's arms keep out of (a refusal names it); moving,
    it will be elsewhere by then."""
    taken = _material(1, (0.5, 0.0, 0.95))
    hanging = replace(
        _material(2, (0.5, 0.0, 1.1), holder=wp.ROBOT_HOLDER),
        velocity=SpatialVelocity([0.0, 0.0, 0.0], [speed, 0.0, 0.0]),
    )
    names = _nearby_told('<ActorPick object_id="1"/>', (taken, hanging), 0.0)
    assert names == (["material 2 the robot holds"] if kept else []), names


def test_next_object_says_why_it_offers_none_where_every_one_has_another_on_it():
    """A user's tray with parts lying on it: the NextObject for the tray failed every tick,
    and the run said nothing of why. Its failure now names what lies on what; a later
    failure for want of any tray says nothing (a tree polling an empty area is no mistake)."""
    tray = replace(_material(1, (1.0, 0.0, 0.94)), type="tray")
    part = _material(2, (1.02, 0.0, 1.02), support=wp.object_support(1))
    xml = (
        '<root BTCPP_format="4"><BehaviorTree ID="Main">'
        '<NextObject area="-9,-9;9,-9;9,9;-9,-9;9,9;-9,9" filter="type=tray" object_id="{id}"/>'
        "</BehaviorTree></root>"
    )
    agent = Agent("human", Places())
    agent.statuses["workpieces"] = wp.WorkpiecesStatus(0.0, (tray, part), {}, {})
    tree = load_tree(xml, hrc_registry(), agent=agent)
    (node,) = tree.node_list
    assert tree.tick(0.0) is Status.FAILURE
    assert node.failure_reason == (
        "every object here that the filter takes has another lying on it (object 2 on "
        "object 1): the one on top is taken first"
    )
    agent.statuses["workpieces"] = wp.WorkpiecesStatus(0.1, (part,), {}, {})
    assert tree.tick(0.1) is Status.FAILURE and node.failure_reason == ""
