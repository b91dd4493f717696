"""Sweep throughput of each scenario: runs per minute on 1 and 2 local workers, the parallel
efficiency (runs/min with 2) / (2 × runs/min with 1), and the projected time of 1 000 seeds
on 2 workers.

By default 100 seeds of each bundled scenario at its own duration (what a user's safety
verdict sweeps). Worker start-up (spawning, importing Drake) is part of a sweep's cost, so
it is included. The two settings alternate over the repeats and each keeps its best rate,
so load from other processes on the machine distorts the ratio less. On a shared machine the
wall clock also counts other people's work: `--cpu` projects from the CPU time the sweep's
processes (this one and its workers) spent instead, as if each worker had a core of its own.

    .venv/bin/python benchmarks/sweep.py [--runs 100] [--duration 0] [--repeats 1] [--cpu]
        [scenario ...]
"""

import argparse
import os
import tempfile
import time
from pathlib import Path

from hrc_drake.scenario import load_scenario, resolve_scenario_path
from hrc_drake.sweep import plan, sweep

SCENARIOS = ("coexistence", "cooperation", "collaboration")
PROJECTED_SEEDS = 1000


def process_seconds() -> float:
    """CPU time of this process and of its finished children (the sweep's workers)."""
    t = os.times()
    return t.user + t.system + t.children_user + t.children_system


def runs_per_minute(scenario: str, runs: int, duration: float, workers: int, cpu: bool) -> float:
    """Runs per minute of wall time, or with `cpu` per minute of CPU time per worker."""
    sets = [f"duration={duration}"] if duration > 0 else []
    specs = plan(resolve_scenario_path(scenario), list(range(runs)), sets)
    with tempfile.TemporaryDirectory() as out:
        wall, spent = time.perf_counter(), process_seconds()
        result = sweep(specs, Path(out), workers=workers)
        wall, spent = time.perf_counter() - wall, process_seconds() - spent
    assert not result.failed, result.failed[0]["error"]
    return 60.0 * runs / (spent / workers if cpu else wall)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("scenarios", nargs="*", default=SCENARIOS)
    parser.add_argument("--runs", type=int, default=100)
    parser.add_argument("--duration", type=float, default=0.0, help="0: the scenario's own")
    parser.add_argument("--repeats", type=int, default=1)
    parser.add_argument("--cpu", action="store_true", help="per CPU second, not wall second")
    args = parser.parse_args()
    for name in args.scenarios:
        rates = {1: 0.0, 2: 0.0}
        for _ in range(args.repeats):
            for workers in rates:
                rate = runs_per_minute(name, args.runs, args.duration, workers, args.cpu)
                rates[workers] = max(rates[workers], rate)
        default = load_scenario(name).duration
        duration = args.duration if args.duration > 0 else default
        clock = "CPU" if args.cpu else "wall"
        for workers, rate in rates.items():
            print(
                f"{name}: {workers} worker(s): {rate:7.2f} runs/min ({clock}; "
                f"{args.runs} runs of {duration:g} s)"
            )
        print(f"{name}: parallel efficiency: {100 * rates[2] / (2 * rates[1]):.0f} %")
        hours = PROJECTED_SEEDS / rates[2] * (default / duration) / 60
        print(f"{name}: {PROJECTED_SEEDS} seeds of {default:g} s on 2 workers: {hours:.2f} h")


if __name__ == "__main__":
    main()
