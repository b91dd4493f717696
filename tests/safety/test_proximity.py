"""The meter's exactness while it reuses capsule gaps across updates: every reading names
the pair a brute-force query of all pairs finds closest, and every touching pair; and its
readings do not depend on the order the person and the robot were registered in."""

import itertools
import math

import numpy as np
import pytest
from pydrake.geometry import SceneGraph
from pydrake.systems.framework import DiagramBuilder
from pydrake.trajectories import PiecewisePolynomial

from hrc_drake.human.body import human_body, parse_human
from hrc_drake.safety.geometry import body_parts, human_parts
from hrc_drake.safety.proximity import ProximityMeter
from hrc_drake.scenario import load_scenario
from hrc_drake.station import add_robot, model_parser
from tests.safety.approach_cell import kinematic, walk

PERIOD = 0.01
PERSON = walk(stand=0.3, arrive=1.0, leave=5.0, bearing=math.radians(55), start=1.0)


class Cell:
    """The person and the arm in one SceneGraph, posed by hand; the robot's geometry is
    registered first unless `human_first`."""

    def __init__(self, human_first: bool = False):
        scenario = load_scenario("base")
        builder = DiagramBuilder()
        scene_graph = builder.AddSystem(SceneGraph())

        def add_robot_plant():
            return kinematic(
                builder, scene_graph, lambda p: add_robot(p, model_parser(p), scenario.station)
            )

        def add_human_plant():
            return kinematic(builder, scene_graph, lambda p: parse_human(p, 1.75, 75.0))

        if human_first:
            human_plant, human, self.human_pose = add_human_plant()
            robot_plant, arm, self.robot_pose = add_robot_plant()
        else:
            robot_plant, arm, self.robot_pose = add_robot_plant()
            human_plant, human, self.human_pose = add_human_plant()
        self.q_home = scenario.station.configuration("home")
        self.diagram = builder.Build()
        self.context = self.diagram.CreateDefaultContext()
        self.query_port = scene_graph.get_query_output_port()
        self.scene_graph = scene_graph
        inspector = scene_graph.model_inspector()
        self.human = human_parts(human_plant, inspector, human)
        self.robot = body_parts(robot_plant, [arm])
        self.meter = ProximityMeter(inspector, self.human, self.robot)

    def query_at(self, time: float, person=PERSON, person_time: float | None = None):
        """The QueryObject with A1 swinging at `time` and the person walking as `person` at
        `person_time` (default: `time`)."""
        q = self.q_home.copy()
        q[0] += math.radians(60) * math.sin(1.2 * time)
        person_q = person.value(time if person_time is None else person_time)
        for pose, positions in ((self.robot_pose, q), (self.human_pose, person_q)):
            pose.get_input_port().FixValue(pose.GetMyContextFromRoot(self.context), positions)
        return self.query_port.Eval(self.scene_graph.GetMyContextFromRoot(self.context))

    def all_distances(self, query) -> list[tuple[float, str, str]]:
        return [
            (
                query.ComputeSignedDistancePairClosestPoints(h.geometry, r.geometry).distance,
                h.name,
                r.name,
            )
            for h in self.human
            for r in self.robot
        ]


def test_reused_gaps_find_the_exact_closest_pair_and_every_contact():
    cell = Cell()
    robot = cell.meter.active(np.arange(len(cell.robot)))
    memory, touched = None, 0
    for time in np.arange(0.0, 5.0, PERIOD):
        query = cell.query_at(time)
        reading = cell.meter.measure(query, memory, time, robot)
        memory = reading.memory
        distances = cell.all_distances(query)
        closest = min(distances)
        assert reading.closest.distance == pytest.approx(closest[0], abs=1e-12)
        assert (reading.closest.region, reading.closest.part) == closest[1:]
        contacts = sorted((d, h, r) for d, h, r in distances if d <= 0.0)
        measured = sorted((c.distance, c.region, c.part) for c in reading.contacts)
        assert [c[1:] for c in measured] == [c[1:] for c in contacts]
        touched += bool(contacts)
    assert touched > 10  # the walk reaches into the swing


def test_parts_that_come_and_go_are_measured_exactly_and_without_speed_jumps():
    """A carried object is a robot part only while held: readings over the active parts stay
    exact, and a part that becomes active does not jump from a stale pose (which would read
    as a robot speed no part ever had)."""
    cell = Cell()
    every = cell.meter.active(np.arange(len(cell.robot)))
    fewer = cell.meter.active(np.arange(len(cell.robot) - 2))
    memory_all = memory_some = None
    for k, time in enumerate(np.arange(0.0, 3.0, PERIOD)):
        active = every if (k // 25) % 2 else fewer
        query = cell.query_at(time)
        full = cell.meter.measure(query, memory_all, time, every)
        some = cell.meter.measure(query, memory_some, time, active)
        memory_all, memory_some = full.memory, some.memory
        names = {cell.robot[j].name for j in active.robot}
        closest = min(d for d in cell.all_distances(query) if d[2] in names)
        assert (some.closest.distance, some.closest.region, some.closest.part) == pytest.approx(
            closest, abs=1e-12
        )
        assert some.robot_speed <= full.robot_speed + 1e-9


def test_person_speed_is_measured_between_their_pose_samples():
    """HumanActor holds each pose for 1/60 s; the meter at 100 Hz must read the person's
    walking speed, not 0 on a held pose and too fast just after a new one."""
    cell = Cell()
    speed = 1.2
    person = walk(stand=0.5, arrive=3.0, leave=10.0, bearing=math.radians(55), speed=speed)
    robot = cell.meter.active(np.arange(len(cell.robot)))
    memory, readings = None, []
    for time in np.arange(0.0, 2.9, PERIOD):
        sample = math.floor(time * 60.0 + 1e-9) / 60.0
        reading = cell.meter.measure(
            cell.query_at(time, person, sample), memory, time, robot, sample
        )
        memory = reading.memory
        if time > 1.0:  # walking in a straight line since 0.92 s
            readings.append(reading.walking_speed)
    np.testing.assert_allclose(readings, speed, rtol=1e-9)


def swinging_arm(bearing: float, distance: float, period: float = 1.0):
    """Person positions: standing `distance` metres from the robot's base facing it, the
    right arm swinging ±60° at the shoulder once per `period` (the hand about 4 m/s)."""
    body = human_body()
    q = body.standing_pose()
    q[body.index("base_yaw")] = bearing + math.pi
    q[body.index("base_x")] = distance * math.cos(bearing)
    q[body.index("base_y")] = distance * math.sin(bearing)
    times = np.arange(0.0, 3.0, 0.01)
    columns = []
    for t in times:
        q[body.index("right_shoulder_flexion")] = math.radians(60) * math.sin(2 * math.pi * t)
        columns.append(body.plant_positions(q))
    return PiecewisePolynomial.FirstOrderHold(times, np.array(columns).T)


def test_walking_speed_is_the_pelvis_not_a_swinging_arm():
    """A person who stands and swings an arm does not walk, however fast the hand moves; the
    hand, closest to the robot, approaches it by its own motion."""
    cell = Cell()
    person = swinging_arm(math.radians(55), 1.0)
    robot = cell.meter.active(np.arange(len(cell.robot)))
    memory, walking, hand_approach = None, [], []
    for time in np.arange(0.0, 2.0, PERIOD):
        sample = math.floor(time * 60.0 + 1e-9) / 60.0
        reading = cell.meter.measure(
            cell.query_at(time, person, sample), memory, time, robot, sample
        )
        memory = reading.memory
        walking.append(reading.walking_speed)
        if reading.closest.region == "hand":
            hand_approach.append(reading.closest.human_approach)
    assert max(walking) < 1e-9
    assert max(hand_approach) > 1.0


def readings_over_the_walk(cell: Cell, person, duration: float):
    robot = cell.meter.active(np.arange(len(cell.robot)))
    memory, readings = None, []
    for time in np.arange(0.0, duration, PERIOD):
        reading = cell.meter.measure(cell.query_at(time, person), memory, time, robot)
        memory = reading.memory
        readings.append(reading)
    return readings


def test_registration_order_gives_the_same_readings_and_the_right_signs():
    """SceneGraph orders a pair its own way: with the robot registered first it reports the
    robot as A. Either way the person walking in reads as approaching, at the same speed."""
    speed = 1.2
    person = walk(stand=0.3, arrive=2.5, leave=10.0, bearing=math.radians(55), speed=speed)
    robot_first = readings_over_the_walk(Cell(human_first=False), person, 2.5)
    human_first = readings_over_the_walk(Cell(human_first=True), person, 2.5)
    # Drake's distances agree to its solver's tolerance, the witness points' speeds to 1 mm/s
    tolerances = {"distance": 1e-5, "robot_approach": 1e-3, "human_approach": 1e-3}
    for a, b in zip(robot_first, human_first, strict=True):
        assert (a.closest.region, a.closest.part) == (b.closest.region, b.closest.part)
        for name, tolerance in tolerances.items():
            assert getattr(a.closest, name) == pytest.approx(
                getattr(b.closest, name), abs=tolerance
            )
        assert a.closest.normal @ b.closest.normal > 0.999  # within 2.6 degrees
        assert [c.pinned for c in a.contacts] == [c.pinned for c in b.contacts]
    walking_in = [r.closest for r in robot_first[100:190]]  # straight at the robot, apart
    assert all(c.distance > 0.05 for c in walking_in)
    # the closest body point walks in at up to the walking speed, never away
    approach = np.array([c.human_approach for c in walking_in])
    assert approach.min() > 0.2 * speed and approach.max() <= speed + 1e-6
    # the normal points from the robot out to the person, who comes in along the bearing
    bearing = np.array([math.cos(math.radians(55)), math.sin(math.radians(55)), 0.0])
    assert all(c.normal @ bearing > 0.5 and c.human_point @ bearing > 0.3 for c in walking_in)


def test_robot_swinging_at_the_person_reads_approaching():
    """The robot's closest point moving towards a person standing still reads positive,
    away negative, and at the rate the separation changes (whatever the registration)."""
    person = walk(
        stand=0.9, arrive=0.5, leave=10.0, bearing=math.radians(55), start=0.95, speed=0.2
    )
    for cell in (Cell(human_first=False), Cell(human_first=True)):
        readings = readings_over_the_walk(cell, person, 2.6)[60:]  # the person stands
        pairs = [(r.closest.region, r.closest.part) for r in readings]
        distances = np.array([r.closest.distance for r in readings])
        approach = np.array([r.closest.robot_approach for r in readings])
        closing = -np.diff(distances) / PERIOD
        same_pair = np.array([a == b for a, b in itertools.pairwise(pairs)])
        np.testing.assert_allclose(approach[1:][same_pair], closing[same_pair], atol=0.01)
        assert approach.max() > 0.4 and approach.min() < -0.05
