"""The walk-in cell: the station's robot (dynamic plant, inverse-dynamics controller,
RobotMotion) sweeping A1 back and forth at full speed, a scripted person who walks straight
at it at 1.6 m/s and reaches in with the right hand at 2.0 m/s, and the SafetyMonitor in
the loop. The person is kinematic (a position trajectory posing the human model); the
plant does not see their geometry, only the monitor does.

`simulate(case)` returns everything a test checks: the monitor's final status and logged
signals, the robot's joint positions and the person's positions at every monitor update.

A case may watch the person through a safety sensor instead (`Case.sensor`): a laser
scanner 2 m to the side of the approach from +y (bearing 90°), 0.3 m above the floor
(`SEEN`; `OCCLUDED` adds a wall of fence panels between it and the whole approach), or a
light curtain across that approach (`CURTAIN`). Every reading it takes is kept
(`Outcome.readings`).
"""

import functools
import math
from dataclasses import dataclass

import numpy as np
from pydrake.common.value import AbstractValue
from pydrake.common.yaml import yaml_load_typed
from pydrake.multibody.plant import AddMultibodyPlant
from pydrake.systems.analysis import Simulator
from pydrake.systems.framework import DiagramBuilder, EventStatus, LeafSystem
from pydrake.systems.primitives import LogVectorOutput, TrajectorySource
from pydrake.trajectories import PiecewisePolynomial

from hrc_drake.human.body import FrameTask, human_body, parse_human
from hrc_drake.messages import FINISHED
from hrc_drake.motion.messages import MoveJoints
from hrc_drake.ports import message_value
from hrc_drake.safety.config import SafetyConfig
from hrc_drake.safety.geometry import human_parts
from hrc_drake.safety.messages import SIGNALS
from hrc_drake.safety.sensors import LaserScanner, LightCurtain, SensorsConfig
from hrc_drake.safety.sensors_reading import SensorReading
from hrc_drake.scenario import Scenario
from hrc_drake.seeding import stream
from hrc_drake.station import add_station_models, model_parser
from hrc_drake.systems.robot_controller import add_robot_controller
from hrc_drake.systems.robot_motion import add_robot_motion
from hrc_drake.systems.safety_monitor import add_safety_monitor
from hrc_drake.systems.safety_sensors import add_safety_sensors
from hrc_drake.wiring import ROBOT_MOTION
from tests.safety.approach_cell import keep_person_out_of_contact, kinematic

WALK_SPEED = 1.6
"""m/s: ISO 13855's walking approach speed"""
HAND_SPEED = 2.0
"""m/s: ISO 13855's hand approach speed (the peak speed of the reach)"""
STAND = 0.65
"""m from the robot's base axis where the person stops walking and reaches in (by default:
inside the sweep)"""
HOLD = 1.0
"""s the hand stays reached in"""
SWEEP_TIME = 5.5
"""s: one sweep of A1 at full speed, about; a hand held in this long meets the arm head-on"""
AFTER = 2.5
"""s after the person walked back out, for the robot to resume"""
ROBOT_SPEED = 1.3
"""m/s the monitor takes as the robot's top point speed (the tool is limited to 1 m/s)"""
SWEEP_DEG = (0.0, -45.0, 60.0, 0.0, 60.0, 0.0)
"""The arm's pose while A1 sweeps: reaching out and down, tool at about waist height."""
SWEEP_A1 = 175.0

CELL = """
name: walk_in
robot:
  variant: {variant}
  base_pose: {{translation: [0.0, 0.0, 0.8]}}
  initial_configuration: sweep_start
  configurations_deg:
    sweep_start: {start}
cell:
  - add_model: {{name: floor, file: package://hrc_drake_models/cell/floor.sdf}}
  - add_weld: {{parent: world, child: floor::body}}
  - add_model: {{name: robot_pedestal, file: package://hrc_drake_models/cell/robot_pedestal.sdf}}
  - add_weld: {{parent: world, child: robot_pedestal::body}}
"""
WALL = """
  - add_model: {{name: wall_{k}, file: package://hrc_drake_models/cell/fence.sdf}}
  - add_weld:
      parent: world
      child: wall_{k}::body
      X_PC: {{translation: [-1.0, {y}, 0.0], rotation: !Rpy {{deg: [0, 0, 90]}}}}
"""
SEEN, OCCLUDED, CURTAIN = "scanner", "occluded-scanner", "curtain"
SCANNER = LaserScanner(pose=[-2.0, 1.0, 0.0], response_time=0.12)
"""Beside the approach from +y, looking along +x; its response (three 40 ms scans) is
slower than the monitor's default sensing time, so S_p shows which it uses."""
LIGHT_CURTAIN = LightCurtain(ends=[[-1.0, 2.6], [1.0, 2.6]], heights=[0.3, 1.5])
"""Across the approach from +y, 2.6 m out: ISO 13855's S for its 30 mm resolution and the
R760's stop from full speed (1.55 m) beyond the reach"""
WALL_PANELS = (1.4, 3.4)
"""y of the fence panels (2 m long, along y at x = -1, beyond the robot's reach) that hide
the approach from it"""
START_SCANNED = 4.5
"""m from the base axis where a scanned person starts (beyond the scanner's S_p)"""


@dataclass(frozen=True)
class Case:
    """One walk-in: the robot variant, where the person comes from (bearing from +x,
    degrees; start distance from the base axis, m), when they set off (s), and whether
    SSM may slow the robot down; how long the hand stays reached in (s)."""

    variant: str
    bearing: float
    start: float
    delay: float
    ssm: bool = True
    stand: float = STAND
    hold: float = HOLD
    sensor: str = ""
    """"": the monitor knows the body; SEEN or OCCLUDED: it sees the person through
    SCANNER, CURTAIN through LIGHT_CURTAIN"""
    far_period: float = SafetyConfig.far_period
    """the monitor's `far_period` (0: it measures every period)"""

    @property
    def id(self) -> str:
        name = self.variant.split("_")[2]
        ssm = "ssm" if self.ssm else "no-ssm"
        where = f"{self.start:.1f}-{self.stand:.2f}m"
        held = "" if self.hold == HOLD else f"-hold{self.hold:.1f}s"
        scanned = f"-{self.sensor}" if self.sensor else ""
        far = "" if self.far_period == SafetyConfig.far_period else f"-far{self.far_period:g}s"
        return f"{name}-{self.bearing:.0f}deg-{where}-{self.delay:.1f}s{held}-{ssm}{scanned}{far}"

    @property
    def person(self) -> PiecewisePolynomial:
        return person_path(self.bearing, self.start, self.delay, self.stand, self.hold)


@dataclass
class Outcome:
    case: Case
    status: object
    """the monitor's final SafetyStatus"""
    times: np.ndarray
    signals: np.ndarray
    """SIGNALS × times"""
    robot_q: np.ndarray
    """joint positions × times (the plant's)"""
    robot_every_period: np.ndarray
    """joint positions at every monitor period, measured or not (the plant's)"""
    person_q: np.ndarray
    """the person's plant positions × times"""
    config: SafetyConfig
    part_names: tuple
    scenario: Scenario
    readings: list[SensorReading]
    """every reading the sensor took (none without one)"""

    def signals_named(self, name: str) -> np.ndarray:
        return self.signals[SIGNALS.index(name)]


def scenario(variant: str, occluded: bool = False) -> Scenario:
    start = [-SWEEP_A1, *SWEEP_DEG[1:]]
    text = CELL.format(variant=variant, start=start)
    if occluded:
        text += "".join(WALL.format(k=k, y=y) for k, y in enumerate(WALL_PANELS))
    return yaml_load_typed(schema=Scenario, data=text)


class Shuttle(LeafSystem):
    """Sends MoveJoints to the two ends of the sweep in turn: the next as soon as the last
    finished (a monitored stop only delays it)."""

    def __init__(self, goals: list[np.ndarray], period: float = 0.05):
        super().__init__()
        self._goals = goals
        self._status = self.DeclareAbstractInputPort("robot_status", message_value())
        self._command = self.DeclareAbstractState(AbstractValue.Make(self._move(1)))
        self.DeclareStateOutputPort("robot_command", self._command)
        self.DeclarePeriodicUnrestrictedUpdateEvent(period, 0.0, self._update)

    def _move(self, seq: int) -> MoveJoints:
        return MoveJoints(seq=seq, q=tuple(self._goals[seq % 2]))

    def _update(self, context, state) -> EventStatus:
        command = context.get_abstract_state(self._command).get_value()
        status = self._status.Eval(context)
        if status is not None and status.results.outcome_of(command.seq) in FINISHED:
            state.get_mutable_abstract_state(self._command).set_value(self._move(command.seq + 1))
        return EventStatus.Succeeded()


def sweep_goals() -> list[np.ndarray]:
    return [np.radians([sign * SWEEP_A1, *SWEEP_DEG[1:]]) for sign in (-1.0, 1.0)]


@functools.cache
def person_path(
    bearing: float, start: float, delay: float, stand: float, hold: float
) -> PiecewisePolynomial:
    """The person's plant positions over time: stand at `start` m from the base axis along
    `bearing` (degrees) facing the robot, set off after `delay` s, walk in to `stand` at
    WALK_SPEED, reach the right hand in at HAND_SPEED, hold it there `hold` s, take it back,
    walk back out."""
    body = human_body()
    direction = np.array([math.cos(math.radians(bearing)), math.sin(math.radians(bearing))])

    def standing_at(radius: float) -> np.ndarray:
        q = body.standing_pose()
        q[body.index("base_x")], q[body.index("base_y")] = radius * direction
        q[body.index("base_yaw")] = math.radians(bearing) + math.pi
        return q

    standing = standing_at(stand)
    reach = _reached_in(body, standing, direction)
    reach_steps = np.linspace(0.0, 1.0, 9)
    reach_poses = [(1 - a) * standing + a * reach for a in reach_steps]
    hand = np.array([body.frame_pose("right_hand_grasp", q).translation() for q in reach_poses])
    step_time = np.linalg.norm(np.diff(hand, axis=0), axis=1).max() / HAND_SPEED
    walk = (start - stand) / WALK_SPEED
    times, poses = [0.0, delay], [standing_at(start), standing_at(start)]
    t = delay + walk
    for pose in reach_poses:
        times.append(t)
        poses.append(pose)
        t += step_time
    t += hold - step_time
    for pose in reversed(reach_poses):
        times.append(t)
        poses.append(pose)
        t += step_time
    times += [t - step_time + walk, t - step_time + walk + AFTER]
    poses += [standing_at(start), standing_at(start)]
    columns = np.array([body.plant_positions(q) for q in poses]).T
    return PiecewisePolynomial.FirstOrderHold(times, columns)


def _reached_in(body, standing: np.ndarray, direction: np.ndarray) -> np.ndarray:
    """The right arm stretched out towards the robot's base axis at 1.1 m height."""
    target = np.array([*(0.05 * direction), 1.1])
    free = np.array(
        [
            body.index(joint)
            for joint in (
                "right_shoulder_flexion",
                "right_shoulder_abduction",
                "right_shoulder_rotation",
                "right_elbow_flexion",
            )
        ]
    )
    return body.solve(standing, [FrameTask("right_hand_grasp", target)], free, iterations=60)


def duration(case: Case) -> float:
    return case.person.end_time()


def build(case: Case):
    scene = scenario(case.variant, case.sensor == OCCLUDED)
    sensors = sensors_of(case.sensor)
    config = SafetyConfig(
        ssm=case.ssm, robot_speed=ROBOT_SPEED, sensors=sensors, far_period=case.far_period
    )
    builder = DiagramBuilder()
    plant, scene_graph = AddMultibodyPlant(scene.plant, builder)
    arm, _ = add_station_models(plant, model_parser(plant), scene.station)
    plant.Finalize()
    plant.SetDefaultPositions(arm, scene.station.initial_positions)
    controller = add_robot_controller(builder, scene.station, plant, arm)
    seed = stream(scene.seed, ROBOT_MOTION)
    motion, _ = add_robot_motion(builder, scene.station, seed, plant, arm, controller)
    shuttle = builder.AddSystem(Shuttle(sweep_goals()))
    builder.Connect(motion.GetOutputPort("robot_status"), shuttle.get_input_port())
    builder.Connect(shuttle.get_output_port(), motion.GetInputPort("robot_tree_command"))

    human_plant, human = _kinematic_person(builder, scene_graph, case)
    monitor = add_safety_monitor(
        builder, scene_graph, plant, human_plant, human, config, case.variant
    )
    builder.Connect(monitor.GetOutputPort("speed_scale"), motion.GetInputPort("speed_scale"))
    builder.Connect(motion.GetOutputPort("path_rate"), monitor.GetInputPort("robot_path_rate"))
    logs = {
        "signals": LogVectorOutput(monitor.GetOutputPort("safety_signals"), builder, config.period),
        "robot": LogVectorOutput(plant.get_state_output_port(arm), builder, config.period),
    }
    if case.sensor:
        sensor, logs["readings"] = _add_sensor(
            builder, scene_graph, plant, human_plant, human, sensors
        )
        builder.Connect(
            sensor.GetOutputPort("sensor_readings"), monitor.GetInputPort("sensor_readings")
        )
    return builder.Build(), monitor, logs, config, scene


def sensors_of(sensor: str) -> SensorsConfig:
    if sensor == CURTAIN:
        return SensorsConfig(light_curtains={sensor: LIGHT_CURTAIN})
    return SensorsConfig(scanners={sensor: SCANNER}) if sensor else SensorsConfig()


def _add_sensor(builder, scene_graph, plant, human_plant, human, sensors: SensorsConfig):
    """The sensor reading the scene, and a probe keeping every reading it takes."""
    inspector = scene_graph.model_inspector()
    person = [part.geometry for part in human_parts(human_plant, inspector, human)]
    fixed = [
        geometry
        for body in plant.GetBodiesWeldedTo(plant.world_body())
        for geometry in plant.GetCollisionGeometriesForBody(body)
    ]
    sensor = add_safety_sensors(builder, scene_graph, sensors, person, fixed, seed=0)
    ((name, config),) = sensors.all().items()
    probe = builder.AddSystem(ReadingsProbe(name, config.scan_time))
    builder.Connect(sensor.GetOutputPort("sensor_readings"), probe.get_input_port())
    return sensor, probe


class ReadingsProbe(LeafSystem):
    """Keeps the newest reading of the sensor `name` at every scan."""

    def __init__(self, name: str, period: float):
        super().__init__()
        self._name = name
        self.readings: list[SensorReading] = []
        self.DeclareAbstractInputPort("sensor_readings", message_value())
        self.DeclarePeriodicPublishEvent(period, period / 2, self._keep)

    def _keep(self, context) -> None:
        history = self.get_input_port().Eval(context).get(self._name, ())
        if history and (not self.readings or history[-1].time > self.readings[-1].time):
            self.readings.append(history[-1])


def _kinematic_person(builder, scene_graph, case: Case):
    """The person's model posed from their path, in the plant's SceneGraph but out of its
    contact computations."""
    human_plant, human, to_pose = kinematic(
        builder, scene_graph, lambda p: parse_human(p, 1.75, 75.0)
    )
    keep_person_out_of_contact(scene_graph)
    path = builder.AddSystem(TrajectorySource(case.person))
    builder.Connect(path.get_output_port(), to_pose.get_input_port())
    return human_plant, human


def simulate(case: Case) -> Outcome:
    diagram, monitor, logs, config, scene = build(case)
    simulator = Simulator(diagram)
    simulator.AdvanceTo(duration(case))
    context = simulator.get_context()
    status = monitor.GetOutputPort("safety_status").Eval(monitor.GetMyContextFromRoot(context))
    # A logger at time t records the monitor's last update, of t - period or (while the
    # person is far and the monitor measures every far_period) earlier: each update once,
    # with the robot state the other logger recorded at the update's time.
    logged = logs["signals"].FindLog(context).data()[:, 1:]
    measured = logged[SIGNALS.index("time")]
    updates = np.flatnonzero(np.diff(measured, append=np.inf) != 0.0)
    signals, times = logged[:, updates], measured[updates]
    robot_log = logs["robot"].FindLog(context)
    columns = np.searchsorted(robot_log.sample_times(), times)
    assert np.allclose(robot_log.sample_times()[columns], times)
    robot = robot_log.data()[:6, columns]
    path = case.person
    return Outcome(
        case=case,
        status=status,
        times=times,
        signals=signals,
        robot_q=robot,
        robot_every_period=robot_log.data()[:6],
        person_q=np.column_stack([path.value(t).ravel() for t in times]),
        config=config,
        part_names=monitor.part_names,
        scenario=scene,
        readings=logs["readings"].readings if "readings" in logs else [],
    )
