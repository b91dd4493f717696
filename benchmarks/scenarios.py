"""Real-time factor of each bundled scenario, and its cost against the bare robot.

For each scenario: a full run (trees, person, workpieces, safety monitor, RobotMotion), with
the robot's desired state recorded; then the bare plant + inverse-dynamics controller
replaying that same desired state, in the same process. The ratio full / bare is what the
behaviour, the person and the measurements cost on top of simulating the robot itself.
`cell/bare` is the same replay with the scenario's static cell and its contact geometry in
the plant, against the bare one (the station's dynamic plant had them until it dropped its
geometry: `benchmarks/plant_contact.py`).
Where the scenario's plant steps longer than 1 ms, the bare replay also runs at 1 ms
(`bare 1ms`, `full/bare1ms`): what the full run costs against the robot simulated as finely
as before.

The machine is shared, so the simulations are timed in turns: after a first full run that
records the desired state, a second full run, the bare replay and the cell replay advance
`SLICE` simulated seconds each in turn, each timed by this process's CPU time (`--wall`:
wall-clock time), so a burst of load from other processes falls on all three alike.
`--repeats` runs the turns again and keeps each one's fastest; `spread` is the slowest full
run's time over the fastest's.

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
from hrc_drake.scenario import load_scenario, overridden

sys.path.insert(0, str(Path(__file__).resolve().parent))
from base_scenario import bare_diagram  # noqa: E402

SCENARIOS = ("coexistence", "cooperation", "collaboration")
LOG_PERIOD = 0.005
FINE_STEP = 0.001
SLICE = 0.5
"""Simulated seconds each simulation advances in its turn."""


def full_simulator(scenario):
    """The whole scenario, logging the robot's desired state."""
    builder = DiagramBuilder()
    station = builder.AddSystem(build_diagram(scenario))
    log = LogVectorOutput(station.GetOutputPort("robot_desired_state"), builder, LOG_PERIOD)
    simulator = Simulator(builder.Build())
    simulator.Initialize()
    return simulator, log


def desired_motion(scenario, duration: float) -> PiecewisePolynomial:
    """The desired robot state of a full run, to replay on the bare robot."""
    simulator, log = full_simulator(scenario)
    simulator.AdvanceTo(duration)
    data = log.FindLog(simulator.get_context())
    return PiecewisePolynomial.FirstOrderHold(data.sample_times(), data.data())


def timed_in_turns(simulators: list, duration: float, clock) -> list[float]:
    """Each simulator's time to reach `duration`, advancing `SLICE` each in turn."""
    spent = [0.0] * len(simulators)
    t = 0.0
    while t < duration:
        t = min(duration, t + SLICE)
        for k, simulator in enumerate(simulators):
            start = clock()
            simulator.AdvanceTo(t)
            spent[k] += clock() - start
    return spent


def measure(scenario, duration: float, desired, clock) -> list[float]:
    """Times of the full run, the bare replay, the cell replay and, where the scenario's
    step is longer, the bare replay at FINE_STEP, timed in turns."""
    simulators = [full_simulator(scenario)[0]]
    replays = [(scenario, False), (scenario, True)]
    if scenario.plant.time_step > FINE_STEP:
        replays.append((overridden(scenario, [("plant.time_step", FINE_STEP)]), False))
    for replayed, cell in replays:
        simulator = Simulator(bare_diagram(replayed, TrajectorySource(desired), cell))
        simulator.Initialize()
        simulators.append(simulator)
    return timed_in_turns(simulators, duration, clock)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("scenarios", nargs="*", default=SCENARIOS)
    parser.add_argument("--duration", type=float, default=60.0)
    parser.add_argument("--repeats", type=int, default=1)
    parser.add_argument("--wall", action="store_true", help="wall-clock instead of CPU time")
    args = parser.parse_args()
    clock = time.perf_counter if args.wall else time.process_time
    print(
        f"{'scenario':14s} {'step ms':>7s} {'RTF':>6s} {'bare RTF':>9s} {'full/bare':>10s} "
        f"{'cell/bare':>10s} {'bare 1ms':>9s} {'full/bare1ms':>13s} {'spread':>7s}"
    )
    for name in args.scenarios:
        scenario = load_scenario(name)
        desired = desired_motion(scenario, args.duration)
        runs = [measure(scenario, args.duration, desired, clock) for _ in range(args.repeats)]
        full, bare, cell, *fine = (min(times) for times in zip(*runs, strict=True))
        spread = max(run[0] for run in runs) / full
        fine_columns = (
            f"{args.duration / fine[0]:9.2f} {full / fine[0]:13.2f}" if fine else f"{'':23s}"
        )
        print(
            f"{name:14s} {1e3 * scenario.plant.time_step:7.1f} {args.duration / full:6.2f} "
            f"{args.duration / bare:9.2f} {full / bare:10.2f} {cell / bare:10.2f} "
            f"{fine_columns} {spread:7.2f}"
        )


if __name__ == "__main__":
    main()
