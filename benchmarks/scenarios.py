"""Real-time factor of each bundled scenario, and its cost against the bare robot.

For each scenario: a full run (trees, person, workpieces, safety monitor, RobotMotion), with
the robot's desired state recorded; then the bare plant + inverse-dynamics controller
replaying that same desired state, in the same process. The ratio full / bare is what the
behaviour, the person and the measurements cost on top of simulating the robot itself.
`cell/bare` is the same replay with the scenario's static cell in the plant (as in the
station's dynamic plant: its contact geometry is part of every step), against the bare one.

Times are this process's CPU time (`--wall`: wall-clock time): on a shared machine the
wall clock also counts the turns of other processes. The runs alternate over `--repeats`
and each keeps its fastest, so load distorts the ratios less; `spread` is the slowest full
run's time over the fastest's (how noisy the machine was).

    .venv/bin/python benchmarks/scenarios.py [--duration 60] [--repeats 1] [--wall] [scenario ...]
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


def full_run(scenario, duration: float, clock=time.process_time):
    """Time of the whole scenario and the desired robot state it produced."""
    builder = DiagramBuilder()
    station = builder.AddSystem(build_diagram(scenario))
    log = LogVectorOutput(station.GetOutputPort("robot_desired_state"), builder, LOG_PERIOD)
    simulator = Simulator(builder.Build())
    simulator.Initialize()
    start = clock()
    simulator.AdvanceTo(duration)
    spent = clock() - start
    data = log.FindLog(simulator.get_context())
    return spent, PiecewisePolynomial.FirstOrderHold(data.sample_times(), data.data())


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("scenarios", nargs="*", default=SCENARIOS)
    parser.add_argument("--duration", type=float, default=60.0)
    parser.add_argument("--repeats", type=int, default=1)
    parser.add_argument("--wall", action="store_true", help="wall-clock instead of CPU time")
    args = parser.parse_args()
    clock = time.perf_counter if args.wall else time.process_time
    print(
        f"{'scenario':14s} {'RTF':>6s} {'bare RTF':>9s} {'full/bare':>10s} "
        f"{'cell/bare':>10s} {'spread':>7s}"
    )
    for name in args.scenarios:
        scenario = load_scenario(name)
        fulls, bares, cells = [], [], []
        for _ in range(args.repeats):
            spent, desired = full_run(scenario, args.duration, clock)
            fulls.append(spent)
            for cell, times in ((False, bares), (True, cells)):
                source = TrajectorySource(desired)
                times.append(time_bare(scenario, args.duration, source, cell, clock))
        full, bare, cell = min(fulls), min(bares), min(cells)
        print(
            f"{name:14s} {args.duration / full:6.2f} {args.duration / bare:9.2f} "
            f"{full / bare:10.2f} {cell / bare:10.2f} {max(fulls) / full:7.2f}"
        )


if __name__ == "__main__":
    main()
