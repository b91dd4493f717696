"""Sweep throughput (runs per minute) with 1 and 2 local workers on a scenario, and the
parallel efficiency: (runs/min with 2) / (2 × runs/min with 1).

Worker start-up (spawning, importing Drake) is part of a sweep's cost, so it is included.
The two settings alternate over the repeats and each keeps its best rate, so load from
other processes on the machine distorts the ratio less.

    .venv/bin/python benchmarks/sweep.py [--runs 16] [--duration 5] [--repeats 3]
"""

import argparse
import tempfile
import time
from pathlib import Path

from hrc_drake.scenario import load_scenario, resolve_scenario_path
from hrc_drake.sweep import plan, sweep


def runs_per_minute(scenario: str, runs: int, duration: float, workers: int) -> float:
    specs = plan(resolve_scenario_path(scenario), list(range(runs)), [f"duration={duration}"])
    with tempfile.TemporaryDirectory() as out:
        start = time.perf_counter()
        result = sweep(specs, Path(out), workers=workers)
        wall = time.perf_counter() - start
    assert not result.failed, result.failed[0]["error"]
    return 60.0 * runs / wall


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scenario", default="base")
    parser.add_argument("--runs", type=int, default=16)
    parser.add_argument("--duration", type=float, default=5.0)
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args()
    rates = {1: 0.0, 2: 0.0}
    for _ in range(args.repeats):
        for workers in rates:
            rate = runs_per_minute(args.scenario, args.runs, args.duration, workers)
            rates[workers] = max(rates[workers], rate)
    for workers, rate in rates.items():
        print(
            f"{args.scenario}: {workers} worker(s): {rate:7.1f} runs/min "
            f"({args.runs} runs of {args.duration} s)"
        )
    print(f"parallel efficiency: {100 * rates[2] / (2 * rates[1]):.0f} %")
    default = load_scenario(args.scenario).duration
    hours = 1000 / rates[2] * (default / args.duration) / 60
    print(f"1000 seeds of {default:g} s on 2 workers: at most {hours:.1f} h")


if __name__ == "__main__":
    main()
