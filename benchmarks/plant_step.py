"""What a longer plant step would buy: each scenario's full run and its bare robot at the
scenario's own step and at a longer one, in the same process.

The full runs and the bare replays (as in `benchmarks/scenarios.py`: the bare plant and
controller replaying the desired state of a full run) advance in turns, timed by this
process's CPU time. Printed per scenario: the full run's time at the longer step over its
time at its own step, and the bare robot's. The robot's controller stays as it is (outside
the plant), so this measures the cost only, not whether tracking holds at the longer step.

    .venv/bin/python benchmarks/plant_step.py [--duration 20] [--step 0.004] [scenario ...]
"""

import argparse
import sys
import time
from pathlib import Path

from pydrake.systems.analysis import Simulator
from pydrake.systems.primitives import TrajectorySource

from hrc_drake.scenario import load_scenario, overridden

sys.path.insert(0, str(Path(__file__).resolve().parent))
from base_scenario import bare_diagram  # noqa: E402

from scenarios import SCENARIOS, desired_motion, full_simulator, timed_in_turns  # noqa: E402


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("scenarios", nargs="*", default=SCENARIOS)
    parser.add_argument("--duration", type=float, default=20.0)
    parser.add_argument("--step", type=float, default=0.004, help="the longer step (s)")
    args = parser.parse_args()
    columns = ("full longer/own", "bare longer/own")
    print(
        f"{'scenario':14s} {'step ms':>7s} {'longer':>7s} " + " ".join(f"{c:>16s}" for c in columns)
    )
    for name in args.scenarios:
        scenario = load_scenario(name)
        desired = desired_motion(scenario, args.duration)
        steps = (scenario.plant.time_step, args.step)
        variants = [overridden(scenario, [("plant.time_step", step)]) for step in steps]
        simulators = [full_simulator(variant)[0] for variant in variants]
        for variant in variants:
            simulator = Simulator(bare_diagram(variant, TrajectorySource(desired), False))
            simulator.Initialize()
            simulators.append(simulator)
        full, full_longer, bare, bare_longer = timed_in_turns(
            simulators, args.duration, time.process_time
        )
        print(
            f"{name:14s} {1e3 * steps[0]:7.1f} {1e3 * steps[1]:7.1f} "
            f"{full_longer / full:16.3f} {bare_longer / bare:16.3f}"
        )


if __name__ == "__main__":
    main()
