"""Stopping data of each iisy variant, measured on RobotMotion (ISO 10218-1 Annex B style).

RobotMotion brakes on its path with the full joint acceleration limits whenever it slows
down (`hrc_drake.motion.execution.next_progress`). This module measures that stop as Annex B
tabulates it: for each main axis (A1, A2, A3) moved on its own, at 33, 66 and 100 % of full
speed (the SetSpeed override) and at 33, 66 and 100 % extension (the tool's horizontal
distance from the A1 axis over its largest), the robot is stopped at the peak of its speed
and the stop is measured:

- time: from the update that receives the stop to rest (the monitor's period and the command
  latency come on top: they are part of T_r);
- distance: how far the fastest point of the robot travels meanwhile (the ends of the
  capsules that bound its geometry, the points the safety monitor measures), and that point's
  speed when the stop was commanded; the axis angle travelled.

Payload: the executor brakes within the joint acceleration limits whatever it carries, and
the simulated arm does not carry the workpieces' mass (they follow the tool kinematically),
so the stop does not depend on the payload: the data hold for any payload up to the rated
one. They are written to models/iisy/stopping/<variant>.yaml:

    .venv/bin/python -m hrc_drake.modelgen stopping    # re-measure and rewrite the files

The measurement executes the commanded motion with ideal tracking (RobotMotion's desired
state, as the controller at a plant step of SAMPLE reads it, fed back as the robot state;
evaluated at any time, as the measurement samples between those steps too); tests/motion
check the station's stop (plant and controller) against it. The safety monitor reads the data with
`hrc_drake.safety.stopping.load_stops(variant)`.
"""

import functools
import itertools
import math
from dataclasses import asdict
from pathlib import Path

import numpy as np
import yaml
from pydrake.systems.analysis import Simulator
from pydrake.systems.framework import BasicVector, DiagramBuilder, LeafSystem

from hrc_drake.iisy import VARIANTS
from hrc_drake.messages import FINISHED, SUCCEEDED
from hrc_drake.motion.execution import step_samples
from hrc_drake.motion.messages import MoveJoints, SetSpeed
from hrc_drake.motion.model import PlanningModel
from hrc_drake.motion.options import MotionOptions
from hrc_drake.safety.geometry import body_parts, bounding_segment
from hrc_drake.safety.stopping import Stop, stopping_file
from hrc_drake.seeding import stream
from hrc_drake.station import StationSpec
from hrc_drake.systems.robot_motion import RobotMotion, desired_differences
from hrc_drake.wiring import (
    ROBOT,
    ROBOT_MODEL,
    ROBOT_MOTION,
    TOOL_MODEL,
    command_input,
    tree_issuer,
)

AXES = ("A1", "A2", "A3")
SPEEDS = (0.33, 0.66, 1.0)
EXTENSIONS = (0.33, 0.66, 1.0)
SWING_DEG = {"A1": 240.0, "A2": 90.0, "A3": 110.0}
"""How far each axis turns in its measured motion (about the configuration of the
extension)."""

SAMPLE = 1e-3
"""s between samples of the desired motion."""
HALF_SAMPLE = SAMPLE / 2
AT_REST = 1e-6
"""rad/s: desired joint speeds below this are rest (braking leaves rounding residues)."""


class _DesiredState(LeafSystem):
    """The desired state (q, v) at the context's time from RobotMotion's `desired_segment`:
    its samples around that time (`step_samples`) differenced as a plant stepping every
    SAMPLE reads them (`desired_differences`)."""

    def __init__(self, segment_size: int, joints: int):
        super().__init__()
        self._joints = joints
        self._segment = self.DeclareVectorInputPort("desired_segment", segment_size)
        self._differences = desired_differences(joints, SAMPLE)[: 2 * joints]
        self.DeclareVectorOutputPort("desired_state", 2 * joints, self._calc)

    def _calc(self, context, output: BasicVector) -> None:
        segment = self._segment.Eval(context)
        coefficients = segment[1:].reshape(self._joints, -1)
        samples = step_samples(segment[0], coefficients, SAMPLE, [context.get_time()])
        output.SetFromVector(self._differences @ samples[0])


class _IdealRobot:
    """RobotMotion whose desired state is fed back as the measured state."""

    def __init__(self, variant: str, options: MotionOptions):
        station = StationSpec(variant)
        builder = DiagramBuilder()
        self.motion = builder.AddSystem(
            RobotMotion(station, stream(0, ROBOT_MOTION), options, sample_step=SAMPLE)
        )
        segment = self.motion.GetOutputPort("desired_segment")
        joints = len(VARIANTS[variant].joint_names)
        desired = builder.AddSystem(_DesiredState(segment.size(), joints))
        builder.Connect(segment, desired.get_input_port())
        builder.Connect(desired.get_output_port(), self.motion.GetInputPort("robot_state"))
        builder.ExportOutput(desired.get_output_port(), "desired_state")
        command = command_input(tree_issuer(ROBOT))
        builder.ExportInput(self.motion.GetInputPort(command), command)
        builder.ExportInput(self.motion.GetInputPort("speed_scale"), "speed_scale")
        self.diagram = builder.Build()
        self.simulator = Simulator(self.diagram)
        self.context = self.simulator.get_mutable_context()
        self.motion_context = self.motion.GetMyContextFromRoot(self.context)
        self.model = self.motion.planner.model
        self.points = RobotPoints(self.model)
        self.period = options.period
        self.set_scale(1.0)

    def set_scale(self, scale: float) -> None:
        self.diagram.GetInputPort("speed_scale").FixValue(self.context, [scale])

    def command(self, command) -> None:
        self.diagram.GetInputPort(command_input(tree_issuer(ROBOT))).FixValue(self.context, command)

    def desired(self) -> np.ndarray:
        return self.diagram.GetOutputPort("desired_state").Eval(self.context)

    def outcome(self, seq: int) -> str | None:
        return (
            self.motion.GetOutputPort("robot_status")
            .Eval(self.motion_context)
            .results.outcome_of(seq)
        )

    def step(self) -> None:
        self.simulator.AdvanceTo(self.context.get_time() + SAMPLE)

    def run_move(self, seq: int, q) -> list[tuple[float, float]]:
        """Executes a move to the end; (time, fastest point speed) samples."""
        self.command(MoveJoints(seq=seq, q=tuple(q)))
        samples = []
        before = self.points.world(self.desired()[:6])
        while self.outcome(seq) not in FINISHED:
            self.step()
            now = self.points.world(self.desired()[:6])
            samples.append((self.context.get_time(), _fastest_step(before, now) / SAMPLE))
            before = now
        if self.outcome(seq) != SUCCEEDED:
            reason = (
                self.motion.GetOutputPort("robot_status")
                .Eval(self.motion_context)
                .results.last.reason
            )
            raise RuntimeError(f"stopping measurement move {seq} did not succeed: {reason}")
        return samples


class RobotPoints:
    """The ends of the capsules that bound the robot's geometry (arm and tool), in world
    coordinates: the points whose speeds the safety monitor measures."""

    def __init__(self, model):
        plant = model.plant
        inspector = model.checker.model().scene_graph().model_inspector()
        names = [n for n in (ROBOT_MODEL, TOOL_MODEL) if plant.HasModelInstanceNamed(n)]
        parts = body_parts(plant, [plant.GetModelInstanceByName(n) for n in names])
        self._plant, self._context = plant, model.plant_context
        self._bodies, ends = [], []
        for part in parts:
            start, end, _ = bounding_segment(inspector.GetShape(part.geometry))
            X_BG = inspector.GetPoseInFrame(part.geometry)
            body = plant.GetBodyFromFrameId(inspector.GetFrameId(part.geometry))
            self._bodies.append(body)
            ends.append(np.column_stack([X_BG @ start, X_BG @ end]))
        self._ends = ends

    def world(self, q) -> np.ndarray:
        """(points × 3) at the arm configuration q."""
        self._plant.SetPositions(self._context, q)
        return np.vstack(
            [
                (body.EvalPoseInWorld(self._context) @ ends).T
                for body, ends in zip(self._bodies, self._ends, strict=True)
            ]
        )


def _fastest_step(before: np.ndarray, after: np.ndarray) -> float:
    return float(np.linalg.norm(after - before, axis=1).max())


def measure_stop(variant: str, axis: str, speed: float, extension: float) -> Stop:
    """Moves `axis` through its swing at `speed` and stops it at its peak speed."""
    start, goal = swing(variant, axis, extension)
    peak = _peak_time(variant, start, goal, speed)
    robot = _started(variant, start, goal, speed)
    update = robot.period * math.floor(peak / robot.period + 1e-9)  # the update before the peak
    robot.simulator.AdvanceTo(update - 2 * HALF_SAMPLE)
    before = robot.points.world(robot.desired()[:6])
    robot.simulator.AdvanceTo(update - HALF_SAMPLE)
    now = robot.points.world(robot.desired()[:6])
    point_speed = _fastest_step(before, now) / HALF_SAMPLE
    q_stop = robot.desired()[:6].copy()
    robot.set_scale(0.0)  # received by the update at `update`, between two samples
    travelled = np.zeros(len(now))
    while np.abs(robot.desired()[6:]).max() > AT_REST:
        robot.step()
        after = robot.points.world(robot.desired()[:6])
        travelled += np.linalg.norm(after - now, axis=1)
        now = after
    joint = AXES.index(axis)
    return Stop(
        axis=axis,
        speed=speed,
        extension=extension,
        time=robot.context.get_time() - update,
        distance=float(travelled.max()),
        point_speed=point_speed,
        angle=math.degrees(abs(robot.desired()[joint] - q_stop[joint])),
    )


def _started(variant: str, start, goal, speed: float) -> _IdealRobot:
    """A robot at `start`, its move to `goal` at `speed` just commanded."""
    robot = _IdealRobot(variant, MotionOptions())
    robot.run_move(1, start)
    robot.command((SetSpeed(seq=2, fraction=speed), MoveJoints(seq=3, q=tuple(goal))))
    return robot


def _peak_time(variant: str, start, goal, speed: float) -> float:
    """When the move start → goal at `speed` moves its fastest point fastest."""
    robot = _started(variant, start, goal, speed)
    samples = []
    before = robot.points.world(robot.desired()[:6])
    while robot.outcome(3) not in FINISHED:
        robot.step()
        now = robot.points.world(robot.desired()[:6])
        samples.append((robot.context.get_time(), _fastest_step(before, now) / SAMPLE))
        before = now
    return max(samples, key=lambda sample: sample[1])[0]


def swing(variant: str, axis: str, extension: float) -> tuple[np.ndarray, np.ndarray]:
    """Start and goal (rad) of the measured motion: `axis` turning through SWING_DEG (inside
    its limits) about the best fitting configuration of `extension` from which the whole
    swing is clear of the robot itself."""
    model = _planning_model(variant)
    joint = AXES.index(axis)
    limits = VARIANTS[variant]
    half = math.radians(SWING_DEG[axis]) / 2
    for q in _by_extension(variant, extension):
        low = max(q[joint] - half, limits.position_lower[joint] + 0.05)
        high = min(q[joint] + half, limits.position_upper[joint] - 0.05)
        start, goal = q.copy(), q.copy()
        start[joint], goal[joint] = low, high
        if model.edge_collision_free(start, goal):
            return start, goal
    raise RuntimeError(f"{variant}: no clear {axis} swing at extension {extension}")


@functools.cache
def _by_extension(variant: str, extension: float) -> list[np.ndarray]:
    """Arm configurations (A1 = 0, wrist straight), the closest to `extension` of the
    tool's largest horizontal distance from the A1 axis at the height of A2 first."""
    model = _planning_model(variant)
    height = model.tool_pose(np.zeros(6)).translation()[2]  # stretched along the upper arm
    candidates = []
    for a2, a3 in itertools.product(range(-90, 1, 3), range(-150, 151, 3)):
        q = np.radians([0.0, a2, a3, 0.0, 0.0, 0.0])
        p = model.tool_pose(q).translation()
        candidates.append((q, math.hypot(p[0], p[1]), p[2]))
    reach = max(r for _, r, _ in candidates)

    def misfit(candidate) -> float:
        _, r, z = candidate
        return abs(r / reach - extension) + 0.2 * abs(z - height)

    return [q for q, _, _ in sorted(candidates, key=misfit)]


@functools.cache
def _planning_model(variant: str):
    return PlanningModel(StationSpec(variant), 0.0)


def measure_variant(variant: str) -> list[Stop]:
    return [
        measure_stop(variant, axis, speed, extension)
        for axis, extension, speed in itertools.product(AXES, EXTENSIONS, SPEEDS)
    ]


def write_stopping(models_dir: Path) -> list[Path]:
    """Measures every variant and writes its stopping data file into `models_dir`."""
    return [write_stopping_file(variant, models_dir) for variant in sorted(VARIANTS)]


def write_stopping_file(variant: str, models_dir: Path) -> Path:
    """Measures `variant` and writes its stopping data file."""
    path = stopping_file(variant, models_dir)
    path.parent.mkdir(parents=True, exist_ok=True)
    rows = [
        {k: round(v, 4) if isinstance(v, float) else v for k, v in asdict(s).items()}
        for s in measure_variant(variant)
    ]
    header = (
        f"# Stopping data of the {variant} under RobotMotion (ISO 10218-1 Annex B style):\n"
        "# each main axis moved alone at 33/66/100 % speed and 33/66/100 % extension, stopped\n"
        "# at its peak speed. time: s from the stop command to rest; distance: m travelled\n"
        "# by the robot's fastest point meanwhile; point_speed: that point's speed (m/s) at\n"
        "# the command; angle: degrees the axis turned. Valid for any payload up to the\n"
        "# rated one. Generated by `python -m hrc_drake.modelgen stopping`.\n"
    )
    path.write_text(header + yaml.safe_dump({"variant": variant, "stops": rows}, sort_keys=False))
    return path
