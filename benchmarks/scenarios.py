"""Real-time factor of each bundled scenario, and its cost against the bare robot.

For each scenario: a full run (trees, person, workpieces, safety monitor, RobotMotion), with
the robot's desired state recorded; then the bare plant + inverse-dynamics controller
replaying that same desired state, in the same process. The ratio full / bare is what the
behaviour, the person and the measurements cost on top of simulating the robot itself.

    .venv/bin/python benchmarks/scenarios.py [--duration 60] [coexistence cooperation ...]
"""

import argparse
import sys
import time
from pathlib import Path

from pydrake.systems.analysis import Simulator
from pydrake.systems.framework import DiagramBuilder
from pydrake.systems.primitives import LogVectorOutput, TrajectorySource
from pydrake.trajectories import PiecewisePolynomial

from hrc_drake.builder import build_diagram
from hrc_drake.scenario import load_scenario

sys.path.insert(0, str(Path(__file__).resolve().parent))
from base_scenario import time_bare  # noqa: E402

SCENARIOS = ("coexistence", "cooperation", "collaboration")
LOG_PERIOD = 0.005


def full_run(scenario, duration: float):
    """Wall time of the whole scenario and the desired robot state it produced."""
    builder = DiagramBuilder()
    station = builder.AddSystem(build_diagram(scenario))
    log = LogVectorOutput(station.GetOutputPort("robot_desired_state"), builder, LOG_PERIOD)
    simulator = Simulator(builder.Build())
    simulator.Initialize()
    start = time.perf_counter()
    simulator.AdvanceTo(duration)
    wall = time.perf_counter() - start
    data = log.FindLog(simulator.get_context())
    return wall, PiecewisePolynomial.FirstOrderHold(data.sample_times(), data.data())


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("scenarios", nargs="*", default=SCENARIOS)
    parser.add_argument("--duration", type=float, default=60.0)
    args = parser.parse_args()
    print(f"{'scenario':14s} {'RTF':>6s} {'bare RTF':>9s} {'full/bare':>10s}")
    for name in args.scenarios:
        scenario = load_scenario(name)
        wall, desired = full_run(scenario, args.duration)
        bare = time_bare(scenario, args.duration, TrajectorySource(desired))
        print(
            f"{name:14s} {args.duration / wall:6.2f} {args.duration / bare:9.2f} "
            f"{wall / bare:10.2f}"
        )


if __name__ == "__main__":
    main()
