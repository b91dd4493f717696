"""Belts move what rests on them at their speed, queue it at a stopped end, remove it at a
removing end."""

import itertools

import numpy as np
import pytest
from pydrake.common.schema import Transform
from pydrake.math import RollPitchYaw

from hrc_drake.messages import SUCCEEDED
from hrc_drake.workpieces.config import REMOVE, ConveyorConfig, PlacedObject, WorkpiecesConfig
from hrc_drake.workpieces.messages import ROBOT_HOLDER, Attach, Despawn, Detach
from tests.workpieces.workpieces_rig import (
    BELT_TOP,
    CONVEYOR_Y,
    PART_HEIGHT,
    TOOL_DOWN,
    build_rig,
    carry_to,
    config_with,
    hands_path,
    part_on_table,
    path,
)

SPEED = 0.2
PART_LENGTH = 0.12
PART_WIDTH = 0.08
REMOVING_Y = -2.5
QUEUED = (1, 2, 3)
PERIOD = WorkpiecesConfig().period
REMOVED = (4, 5)


def on_belt(x: float, y: float, layer: int = 0) -> PlacedObject:
    z = BELT_TOP + (layer + 0.5) * PART_HEIGHT
    return PlacedObject(type="part", pose=Transform(translation=[x, y, z]))


@pytest.fixture(scope="module")
def run():
    """Three parts on the queueing belt, two on a removing one (and one more on top of the
    first of those); statuses every 50 ms."""
    removing = ConveyorConfig(
        start=[-1.0, REMOVING_Y, BELT_TOP], end=[1.0, REMOVING_Y, BELT_TOP], at_end=REMOVE
    )
    belt = ConveyorConfig(start=[-1.0, CONVEYOR_Y, BELT_TOP], end=[1.0, CONVEYOR_Y, BELT_TOP])
    objects = [on_belt(x, CONVEYOR_Y) for x in (-0.2, 0.1, 0.4)]
    objects += [on_belt(x, REMOVING_Y) for x in (0.5, 0.7)] + [on_belt(0.5, REMOVING_Y, 1)]
    config = config_with(objects=objects, conveyors={"belt": belt, "removing": removing})
    rig = build_rig(config)
    return {round(t, 3): rig.advance(t) for t in np.arange(0.0, 6.0001, 0.05)}


def x_of(status, object_id: int) -> float:
    return status.object(object_id).pose.translation()[0]


def test_objects_move_at_the_belt_speed(run):
    travelled = x_of(run[2.5], 3) - x_of(run[0.5], 3)
    assert travelled / 2.0 == pytest.approx(SPEED, rel=0.01)
    assert run[1.0].object(3).velocity.translational() == pytest.approx([SPEED, 0.0, 0.0])
    assert run[1.0].object(3).support == "belt"


def test_objects_queue_at_a_stopped_end_without_overlapping(run):
    for status in run.values():
        for a, b in itertools.combinations(QUEUED, 2):
            assert abs(x_of(status, a) - x_of(status, b)) >= PART_LENGTH - 1e-9
    end = run[6.0]
    fronts = [x_of(end, i) + PART_LENGTH / 2 for i in (3, 2, 1)]
    assert fronts == pytest.approx([1.0, 1.0 - PART_LENGTH, 1.0 - 2 * PART_LENGTH])
    assert all(not end.object(i).velocity.get_coeffs().any() for i in QUEUED)
    heights = [end.object(i).pose.translation()[2] for i in QUEUED]
    assert heights == pytest.approx([BELT_TOP + PART_HEIGHT / 2] * 3, abs=1e-9)


def test_a_moving_object_says_where_the_queue_brings_it_to_rest(run):
    """What the person's arms keep out of: where each part still riding up will stand."""
    riding = run[1.0]
    assert [riding.object(i).rests_at.translation()[0] + PART_LENGTH / 2 for i in (3, 2, 1)] == (
        pytest.approx([1.0, 1.0 - PART_LENGTH, 1.0 - 2 * PART_LENGTH])
    )
    assert riding.object(4).rests_at is None  # a removing belt carries it off
    assert all(run[6.0].object(i).rests_at is None for i in QUEUED)


def test_objects_leave_at_a_removing_end(run):
    # Centres start 0.3 m and 0.5 m before the end: they pass it after 1.5 s and 2.5 s.
    assert run[1.45].object(5) is not None
    assert run[1.55].object(5) is None
    assert run[2.45].object(4) is not None
    assert run[2.55].object(4) is None
    assert run[6.0].free_slots["part"] == 6 - len(QUEUED)


def test_an_object_on_a_conveyed_object_rides_along_and_leaves_with_it(run):
    rider, below = run[1.0].object(6), run[1.0].object(4)
    assert rider.support == "object:4"
    np.testing.assert_allclose(rider.pose.translation()[:2], below.pose.translation()[:2])
    assert rider.pose.translation()[2] == pytest.approx(BELT_TOP + 1.5 * PART_HEIGHT)
    assert rider.velocity.translational() == pytest.approx([SPEED, 0.0, 0.0])
    assert run[3.0].object(6) is None


@pytest.fixture(scope="module")
def queue():
    """The three parts queued at the belt's stopped end by 4.5 s; the front one is taken
    away at 5.5 s (a command while the workpieces' updates are left out)."""
    config = config_with(objects=[on_belt(x, CONVEYOR_Y) for x in (-0.2, 0.1, 0.4)])
    return build_rig(config, commands={"robot_tree": [(5.5, Despawn(seq=1, object_id=3))]})


def world_time(rig) -> float:
    """When the workpieces' world last changed (the time of its last update)."""
    context = rig.workpieces.GetMyContextFromRoot(rig.simulator.get_context())
    return rig.workpieces.world(context).time


def test_a_queue_at_rest_costs_no_updates_and_moves_up_when_its_front_leaves(queue):
    queue.advance(5.0)
    queued_since = world_time(queue)
    assert queued_since <= 4.6
    queue.advance(5.4)
    assert world_time(queue) == queued_since  # nothing moved since, nothing was updated
    taken = queue.advance(5.5 + PERIOD)
    assert taken.results_of("robot_tree").outcome_of(1) == SUCCEEDED
    assert taken.object(3) is None
    assert taken.object(2).velocity.translational()[0] == pytest.approx(SPEED)
    moved_up = queue.advance(7.0)
    assert x_of(moved_up, 2) + PART_LENGTH / 2 == pytest.approx(1.0)
    assert x_of(moved_up, 1) + PART_LENGTH / 2 == pytest.approx(1.0 - PART_LENGTH)


def test_a_part_dropped_behind_a_standing_queue_rides_up_to_it():
    """The queue stands still while the robot carries a part (the workpieces update for the
    carried part, not for the queue); the part released above the belt lands on it and
    queues behind the last one, its narrow side along the belt (the tool turned it)."""
    queued = [on_belt(x, CONVEYOR_Y) for x in (0.2, 0.5)]
    config = config_with(objects=[part_on_table(), *queued])
    tool, commands = carry_to((0.4, CONVEYOR_Y, BELT_TOP + PART_HEIGHT + 0.1), release_at=4.0)
    rig = build_rig(config, commands=commands, tool=tool)
    standing = rig.advance(3.9)
    assert standing.object(1).holder == ROBOT_HOLDER
    assert [x_of(standing, i) + PART_LENGTH / 2 for i in (3, 2)] == pytest.approx(
        [1.0, 1.0 - PART_LENGTH]
    )
    end = rig.advance(7.0)
    dropped = end.object(1)
    assert dropped.support == "belt"
    assert not dropped.velocity.get_coeffs().any()
    assert x_of(end, 1) + PART_WIDTH / 2 == pytest.approx(1.0 - 2 * PART_LENGTH)


def test_a_part_held_just_over_the_queue_end_keeps_the_next_one_back_until_lifted():
    """The robot takes the front part of a standing queue and holds it 2 cm over the belt:
    the next part stays behind it (it moved up into the held part's place, 4.1 cm into a
    carton a person had just taken in a user's cell), and moves up once the part is lifted
    clear."""
    front = 1.0 - PART_LENGTH / 2
    top = BELT_TOP + PART_HEIGHT
    tool = path(
        [
            (0.0, (front, CONVEYOR_Y, top), TOOL_DOWN),
            (5.2, (front, CONVEYOR_Y, top), TOOL_DOWN),
            (5.6, (front, CONVEYOR_Y, top + 0.02), TOOL_DOWN),
            (7.0, (front, CONVEYOR_Y, top + 0.02), TOOL_DOWN),
            (7.5, (front, CONVEYOR_Y, top + 0.3), TOOL_DOWN),
        ]
    )
    grip = Attach(seq=1, holder=ROBOT_HOLDER, object_id=3, max_mass=3.0)
    config = config_with(objects=[on_belt(x, CONVEYOR_Y) for x in (-0.2, 0.1, 0.4)])
    rig = build_rig(config, commands={"robot_gripper": [(5.1, grip)]}, tool=tool)
    held = rig.advance(6.9)
    assert held.object(3).holder == ROBOT_HOLDER
    assert held.object(3).pose.translation()[2] == pytest.approx(BELT_TOP + 0.02 + PART_HEIGHT / 2)
    assert x_of(held, 2) + PART_LENGTH / 2 == pytest.approx(1.0 - PART_LENGTH)
    assert x_of(held, 1) + PART_LENGTH / 2 == pytest.approx(1.0 - 2 * PART_LENGTH)
    lifted = rig.advance(9.0)
    assert x_of(lifted, 2) + PART_LENGTH / 2 == pytest.approx(1.0)
    assert x_of(lifted, 1) + PART_LENGTH / 2 == pytest.approx(1.0 - PART_LENGTH)


LEVEL = RollPitchYaw(0.0, 0.0, 0.0)


def test_a_part_the_palms_set_down_on_the_belt_rides_once_they_are_out_of_its_way():
    """Both palms take the front part of the queue off the belt's end, set it down 0.6 m
    upstream and stay at its ends; then the palm ahead of it lifts away. The part stays
    where the palms left it while that palm is in its way (it rode into the palm ahead,
    5.2 cm into it, in a user's palletizing cell), then the belt takes it."""
    front, z = 1.0 - PART_LENGTH / 2, BELT_TOP + PART_HEIGHT / 2
    ends = PART_LENGTH / 2 + 0.005

    def palm(side: float, away: float = 0.0):
        knots = [(0.0, front, z), (0.5, front, z + 0.05), (1.5, 0.4, z + 0.05), (2.0, 0.4, z)]
        knots += [(3.0, 0.4, z), (3.5, 0.4, z + away)]
        return path([(t, (x + side * ends, CONVEYOR_Y, h), LEVEL) for t, x, h in knots])

    commands = [(0.2, Attach(seq=1, holder="both_hands", object_id=1, max_mass=3.0))]
    commands += [(2.1, Detach(seq=2, holder="both_hands"))]
    config = config_with(objects=[on_belt(front, CONVEYOR_Y)])
    hands = hands_path(palm(1.0, away=0.3), palm(-1.0))
    rig = build_rig(config, commands={"human_tree": commands}, hands=hands)
    waiting = rig.advance(3.0)
    assert waiting.results_of("human_tree").outcome_of(2) == SUCCEEDED
    assert (waiting.object(1).support, x_of(waiting, 1)) == ("belt", pytest.approx(0.4))
    assert x_of(rig.advance(3.1), 1) == pytest.approx(0.4)
    assert x_of(rig.advance(4.5), 1) > 0.4 + 0.1 * SPEED
