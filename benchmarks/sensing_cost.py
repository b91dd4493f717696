"""Cost of the safety sensors per run: a scenario with its laser scanners and light curtains
against the same scenario without them (the monitor then knows the person's body), in the
same process.

The monitor runs with SSM off (`safety.ssm: false`), so the robot moves the same with and
without sensors whatever they see: its final state must agree, so both runs did the same
work, and the difference is the sensors' readings (the ray cast of every beam at every
scan) and the monitor's view of them. The person walks up to the cell and reaches in
(`parameters.visit_area=far_side` in the guarded cell), so the scanner sees them most of
the run. Variants alternate, best of the repeats; times are the process's CPU time.

    .venv/bin/python benchmarks/sensing_cost.py [--duration 20] [--repeats 2]
        [--scenario guarded_cell] [--set parameters.visit_area=far_side ...]
"""

import argparse
import dataclasses
import math
import sys
from pathlib import Path

import numpy as np

from hrc_drake.builder import build_diagram
from hrc_drake.safety.sensors import SensorsConfig
from hrc_drake.scenario import Scenario, load_scenario
from hrc_drake.scenario.overrides import parse_sets

sys.path.insert(0, str(Path(__file__).resolve().parent))
from safety_cost import simulated  # noqa: E402  (the same timing as the monitor's cost)


def scenario(name: str, sets: list[tuple[str, object]], with_sensors: bool):
    """The scenario measuring only (SSM off), with its sensors or without."""
    loaded = load_scenario(name, [("safety.ssm", False), *sets])
    if not with_sensors:
        loaded.safety = dataclasses.replace(loaded.safety, sensors=SensorsConfig())
    return loaded


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scenario", default="guarded_cell")
    parser.add_argument("--duration", type=float, default=20.0)
    parser.add_argument("--repeats", type=int, default=2)
    parser.add_argument("--set", action="append", default=["parameters.visit_area=far_side"])
    args = parser.parse_args()
    sets = [(path, values[0]) for path, values in parse_sets(args.set, Scenario)]
    best, final = {False: math.inf, True: math.inf}, {}
    for _ in range(args.repeats):
        for with_sensors in best:
            diagram = build_diagram(scenario(args.scenario, sets, with_sensors))
            cpu, final[with_sensors] = simulated(diagram, args.duration)
            best[with_sensors] = min(best[with_sensors], cpu)
    if not np.allclose(final[False], final[True], atol=1e-9):
        raise SystemExit(f"{args.scenario}: the robot moved differently with the sensors")
    sensors = ", ".join(scenario(args.scenario, sets, True).safety.sensors.all())
    print(
        f"{args.scenario} ({sensors}), {args.duration:g} s: RTF without sensors "
        f"{args.duration / best[False]:.2f}, with {args.duration / best[True]:.2f}; "
        f"sensing costs {100 * (best[True] / best[False] - 1):.1f} % of a run"
    )


if __name__ == "__main__":
    main()
