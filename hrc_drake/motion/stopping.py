"""Stopping data of each iisy variant: T_s and S_s of the protective separation distance.

RobotMotion brakes on the planned path when the safety scale drops to 0, within the joint
acceleration limits (scaled like the speed, so the stopping time does not depend on the
scale and the stopping distance is proportional to it). This module measures, for each
variant, the stop from top speed (scale 1 → 0, applied just after an update so the update
period's latency is included) on standard motions that drive the tool at its collaborative
speed limit, and stores the worst case in models/iisy/stopping.yaml:

    .venv/bin/python -m hrc_drake.motion.stopping      # re-measure and rewrite the file

The measurement executes the commanded motion with ideal tracking (RobotMotion's desired
state fed back as the robot state); the simulated robot's tracking error under the
inverse-dynamics controller is well below a millimetre (tests/motion check the real stop).
Read the data with `stopping_data(variant)`.
"""

from dataclasses import asdict, dataclass
from pathlib import Path

import numpy as np
import yaml
from pydrake.systems.analysis import Simulator
from pydrake.systems.framework import DiagramBuilder

from hrc_drake.iisy import VARIANTS
from hrc_drake.messages import FINISHED, SUCCEEDED
from hrc_drake.motion.messages import MoveJoints
from hrc_drake.motion.options import MotionOptions
from hrc_drake.paths import resource_dir
from hrc_drake.scenario import RobotConfig, Scenario

STOPPING_FILE = "iisy/stopping.yaml"
"""Inside the model folder (models/ in a checkout)."""

STANDARD_MOTIONS_DEG = {
    "A1 sweep, arm reaching out": ((-120, -60, 60, 0, 60, 0), (120, -60, 60, 0, 60, 0)),
    "A2 swing forward and down": ((0, -115, 60, 0, 60, 0), (0, -20, 60, 0, 60, 0)),
    "A3 swing, elbow opening": ((0, -60, 100, 0, 60, 0), (0, -60, -10, 0, 60, 0)),
}
"""Start and goal (degrees) of the motions whose stops are measured."""

SAMPLE = 1e-3
"""s between samples of the desired motion."""


@dataclass(frozen=True)
class StoppingData:
    """time: T_s (s) from the scale command to rest; distance: S_s (m) travelled by the tool
    meanwhile; speed: the tool's speed (m/s) when the stop was commanded."""

    time: float
    distance: float
    speed: float


def stopping_data(variant: str) -> StoppingData:
    """The stored worst-case stop of `variant` from top speed."""
    entry = load_stopping_file()[variant]
    return StoppingData(entry["time"], entry["distance"], entry["speed"])


def load_stopping_file() -> dict:
    """The whole stopping data file: per variant the worst case and each measured motion."""
    return yaml.safe_load((resource_dir("models") / STOPPING_FILE).read_text())


class _IdealRobot:
    """RobotMotion whose desired state is fed back as the measured state."""

    def __init__(self, variant: str, options: MotionOptions):
        from hrc_drake.systems.robot_motion import RobotMotion  # systems import this package

        scenario = Scenario(name=f"stopping_{variant}", robot=RobotConfig(variant=variant))
        builder = DiagramBuilder()
        self.motion = builder.AddSystem(RobotMotion(scenario, options))
        builder.Connect(
            self.motion.GetOutputPort("desired_state"), self.motion.GetInputPort("robot_state")
        )
        builder.ExportInput(self.motion.GetInputPort("robot_command"), "robot_command")
        builder.ExportInput(self.motion.GetInputPort("speed_scale"), "speed_scale")
        self.diagram = builder.Build()
        self.simulator = Simulator(self.diagram)
        self.context = self.simulator.get_mutable_context()
        self.motion_context = self.motion.GetMyContextFromRoot(self.context)
        self.model = self.motion.planner.model
        self.period = options.update_period
        self.set_scale(1.0)

    def set_scale(self, scale: float) -> None:
        self.diagram.GetInputPort("speed_scale").FixValue(self.context, [scale])

    def move(self, seq: int, q) -> None:
        command = MoveJoints(seq=seq, q=tuple(np.radians(q)))
        self.diagram.GetInputPort("robot_command").FixValue(self.context, command)

    def tool_speed(self) -> float:
        x = self.motion.GetOutputPort("desired_state").Eval(self.motion_context)
        return self.model.tool_speed(x[:6], x[6:])

    def at_rest(self) -> bool:
        x = self.motion.GetOutputPort("desired_state").Eval(self.motion_context)
        return bool(np.all(x[6:] == 0.0))

    def outcome(self, seq: int) -> str | None:
        return self.motion.GetOutputPort("robot_status").Eval(self.motion_context).outcome_of(seq)

    def step(self) -> None:
        self.simulator.AdvanceTo(self.context.get_time() + SAMPLE)

    def run_move(self, seq: int, q) -> list[tuple[float, float]]:
        """Executes a move to the end; (time, tool speed) samples."""
        self.move(seq, q)
        samples = []
        while self.outcome(seq) not in FINISHED:
            self.step()
            samples.append((self.context.get_time(), self.tool_speed()))
        if self.outcome(seq) != SUCCEEDED:
            reason = self.motion.GetOutputPort("robot_status").Eval(self.motion_context).reason
            raise RuntimeError(f"stopping measurement move {seq} did not succeed: {reason}")
        return samples


def measure_stop(variant: str, start_deg, goal_deg, options=None) -> StoppingData:
    """Stops the move start → goal at its peak tool speed (just after an update)."""
    options = options or MotionOptions()
    reference = _IdealRobot(variant, options)
    reference.run_move(1, start_deg)
    samples = reference.run_move(2, goal_deg)
    t_move = samples[0][0]
    t_peak = max(samples, key=lambda sample: sample[1])[0]
    robot = _IdealRobot(variant, options)
    robot.run_move(1, start_deg)
    robot.move(2, goal_deg)
    period = options.update_period
    update_before_peak = t_move + np.floor((t_peak - t_move) / period) * period
    robot.simulator.AdvanceTo(update_before_peak + SAMPLE)
    speed = robot.tool_speed()
    robot.set_scale(0.0)
    t_stop, distance = robot.context.get_time(), 0.0
    while not robot.at_rest():
        robot.step()
        distance += robot.tool_speed() * SAMPLE
    return StoppingData(robot.context.get_time() - t_stop, distance, speed)


def measure_variant(variant: str) -> dict[str, StoppingData]:
    return {
        name: measure_stop(variant, start, goal)
        for name, (start, goal) in STANDARD_MOTIONS_DEG.items()
    }


def write_stopping_file(path: Path | None = None) -> Path:
    """Measures every variant and writes the stopping data file."""
    path = path or resource_dir("models") / STOPPING_FILE
    entries = {}
    for variant in sorted(VARIANTS):
        stops = measure_variant(variant)
        worst = {
            "time": max(s.time for s in stops.values()),
            "distance": max(s.distance for s in stops.values()),
            "speed": max(s.speed for s in stops.values()),
        }
        motions = {name: _rounded(asdict(stop)) for name, stop in stops.items()}
        entries[variant] = {**_rounded(worst), "motions": motions}
    header = (
        "# Stopping time (s), stopping distance (m) and tool speed (m/s) at the stop of each\n"
        "# iisy variant from top speed, speed scale 1 -> 0: T_s and S_s of ISO/TS 15066.\n"
        "# Worst case of the motions below. Generated by `python -m hrc_drake.motion.stopping`.\n"
    )
    path.write_text(header + yaml.safe_dump(entries, sort_keys=True))
    return path


def _rounded(values: dict) -> dict:
    return {k: round(float(v), 4) for k, v in values.items()}


if __name__ == "__main__":
    print(f"wrote {write_stopping_file()}")
