"""A test cell for the SafetyMonitor: a kinematic iisy swinging its arm at a speed scaled by
the monitor, and a person (kinematic human model) walking straight at it, waiting, and
walking away. Both are placed in one SceneGraph by MultibodyPositionToGeometryPose."""

import math

import numpy as np
from pydrake.geometry import SceneGraph
from pydrake.multibody.plant import MultibodyPlant
from pydrake.systems.analysis import Simulator
from pydrake.systems.framework import DiagramBuilder, LeafSystem
from pydrake.systems.primitives import LogVectorOutput, TrajectorySource
from pydrake.systems.rendering import MultibodyPositionToGeometryPose
from pydrake.trajectories import PiecewisePolynomial

from hrc_drake.human.body import human_body, parse_human
from hrc_drake.safety.config import SafetyConfig
from hrc_drake.scenario import load_scenario
from hrc_drake.station_models import add_robot, model_parser
from hrc_drake.systems.safety_monitor import add_safety_monitor

SWING_AMPLITUDE = math.radians(60)
SWING_RATE = 1.2
"""rad/s of the path parameter at scale 1 (A1 then turns at up to 1.2 · 60° ≈ 72°/s)."""
ACCELERATION = 4.0
"""rad/s² of the path parameter: how fast the arm follows a change of scale."""
STEP = 0.002


class ScriptedArm(LeafSystem):
    """Swings A1 back and forth along a fixed path; the path rate follows the speed scale
    with bounded acceleration, so slowing down and stopping take real time."""

    def __init__(self, q_home: np.ndarray):
        super().__init__()
        self.q_home = q_home
        self.scale = self.DeclareVectorInputPort("speed_scale", 1)
        state = self.DeclareDiscreteState(2)  # path parameter, its rate
        self.DeclarePeriodicDiscreteUpdateEvent(STEP, 0.0, self._advance)
        self.DeclareVectorOutputPort("q", len(q_home), self._positions, {self.xd_ticket()})
        self.state_index = state

    def _advance(self, context, discrete_state):
        sigma, rate = context.get_discrete_state(self.state_index).value()
        target = SWING_RATE * self.scale.Eval(context)[0]
        rate += np.clip(target - rate, -ACCELERATION * STEP, ACCELERATION * STEP)
        discrete_state.set_value(self.state_index, [sigma + rate * STEP, rate])

    def _positions(self, context, output):
        sigma = context.get_discrete_state(self.state_index).value()[0]
        q = self.q_home.copy()
        q[0] += SWING_AMPLITUDE * math.sin(sigma)
        output.SetFromVector(q)


def walk(
    stand: float,
    arrive: float,
    leave: float,
    bearing: float,
    speed=1.0,
    start: float = 3.0,
    away: float = 4.0,
):
    """Person positions: walk straight at the robot's base from `start` metres away along
    the `bearing` (rad from +x) to `stand` metres away, wait, walk back out to `away`."""
    body = human_body()
    q = body.standing_pose()
    q[body.index("base_yaw")] = bearing + math.pi  # face the robot's base
    travel = (start - stand) / speed
    back = (away - stand) / speed
    times = [0.0, arrive - travel, arrive, leave, leave + back, leave + back + 1.0]
    radii = [start, start, stand, stand, away, away]
    columns = []
    for radius in radii:
        q[body.index("base_x")] = radius * math.cos(bearing)
        q[body.index("base_y")] = radius * math.sin(bearing)
        columns.append(body.plant_positions(q))
    return PiecewisePolynomial.FirstOrderHold(times, np.array(columns).T)


def build(config: SafetyConfig, person: PiecewisePolynomial):
    scenario = load_scenario("base")
    builder = DiagramBuilder()
    scene_graph = builder.AddSystem(SceneGraph())
    robot = kinematic(builder, scene_graph, lambda p: add_robot(p, model_parser(p), scenario.robot))
    human_plant, human_instance, human_pose = kinematic(
        builder, scene_graph, lambda p: parse_human(p, 1.75, 75.0)
    )
    robot_plant, _, robot_pose = robot
    arm = builder.AddSystem(ScriptedArm(scenario.configuration("home")))
    builder.Connect(arm.get_output_port(), robot_pose.get_input_port())
    walker = builder.AddSystem(TrajectorySource(person))
    builder.Connect(walker.get_output_port(), human_pose.get_input_port())
    monitor = add_safety_monitor(
        builder, scene_graph, robot_plant, human_plant, human_instance, config, "lbr_iisy3_r760"
    )
    builder.Connect(monitor.GetOutputPort("speed_scale"), arm.get_input_port())
    logger = LogVectorOutput(monitor.GetOutputPort("safety_signals"), builder, config.period)
    return builder.Build(), monitor, logger


def simulate(config: SafetyConfig, person: PiecewisePolynomial, duration: float):
    """Runs the cell; returns the final status and the logged signals (time, values)."""
    diagram, monitor, logger = build(config, person)
    simulator = Simulator(diagram)
    simulator.AdvanceTo(duration)
    context = simulator.get_context()
    status = monitor.GetOutputPort("safety_status").Eval(monitor.GetMyContextFromRoot(context))
    log = logger.FindLog(context)
    return status, log.sample_times(), log.data()


def kinematic(builder, scene_graph, add_models):
    """A never-stepped plant whose geometry is posed from a position input."""
    plant = MultibodyPlant(0.0)
    plant.RegisterAsSourceForSceneGraph(scene_graph)
    instance = add_models(plant)
    plant.Finalize()
    to_pose = builder.AddSystem(MultibodyPositionToGeometryPose(plant))
    builder.Connect(
        to_pose.get_output_port(), scene_graph.get_source_pose_port(plant.get_source_id())
    )
    return plant, instance, to_pose
