"""The falsifier against Monte Carlo at the same budget: the lowest safety margin each has
reached after 1, 2, 4, ... runs, and the run at which each first found a violation.

Monte Carlo runs the scenario as written over seeds 0..N-1 (`hrc-drake sweep`); the
falsifier runs N trials of its `falsify:` parameters with seed 0 (`hrc-drake falsify`),
both on the same local workers. Each scenario is tried with the monitor as ISO 13855 has it
and with a weakened one that takes the person for 0.8 m/s. Prints, per scenario and monitor,
the margins (m) side by side and the falsifier's margin minus Monte Carlo's (negative: the
falsifier found a worse case). In the guarded cell even the correct monitor has a blind
spot: it sees the person through one laser scanner, which a shelf of cartons shadows.

    .venv/bin/python benchmarks/falsify.py [--budget 12] [--workers 2]
        [--scenarios walk_up:14,coexistence:40,guarded_cell:12] [--monitors correct,weak]
"""

import argparse
import tempfile
from pathlib import Path

import numpy as np

from hrc_drake.falsify import falsify, prepare
from hrc_drake.sweep import parse_seeds, plan, sweep

MONITORS = {
    "correct": (),
    "weak": (("safety.v_h_rule", "constant"), ("safety.v_h", 0.8)),
}
NO_MARGIN = float("inf")


def monte_carlo(name: str, sets, budget: int, workers: int, out: Path) -> list[float]:
    """The margin of each seed's run, in seed order."""
    search = prepare(name)
    texts = [f"{path}={value}" for path, value in sets]
    rows = sweep(plan(search.scenario_path, parse_seeds(f"0:{budget}"), texts), out, workers).rows
    return [_margin(row) for row in rows]


def falsifier(name: str, sets, budget: int, workers: int, out: Path) -> list[float]:
    """The margin of each trial's run, in trial order."""
    result = falsify(prepare(name, 0, tuple(sets) + (("falsify.worst", 0),)), budget, out, workers)
    return [_margin(trial.row) for trial in result.trials]


def _margin(row: dict) -> float:
    value = row["metrics"].get("margin", {}).get("value") if row["status"] == "ok" else None
    return NO_MARGIN if value is None else value


def lowest_after(margins: list[float], runs: list[int]) -> list[float]:
    lowest = np.minimum.accumulate(margins)
    return [float(lowest[n - 1]) for n in runs]


def first_violation(margins: list[float]) -> str:
    return next((str(k + 1) for k, m in enumerate(margins) if m < 0), "none")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--budget", type=int, default=12)
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--scenarios", default="walk_up:14,coexistence:40,guarded_cell:12")
    parser.add_argument("--monitors", default="correct,weak")
    args = parser.parse_args()
    runs = sorted({n for n in (1, 2, 4, 8, 16, 32, 64, args.budget) if n <= args.budget})
    for item in args.scenarios.split(","):
        name, duration = item.split(":")
        for monitor in args.monitors.split(","):
            sets = (*MONITORS[monitor], ("duration", float(duration)))
            with tempfile.TemporaryDirectory() as out:
                mc = monte_carlo(name, sets, args.budget, args.workers, Path(out) / "mc")
                found = falsifier(name, sets, args.budget, args.workers, Path(out) / "f")
            print(f"\n{name} ({duration} s runs), {monitor} monitor, budget {args.budget}")
            print(f"{'runs':>6} {'Monte Carlo':>12} {'falsifier':>10} {'difference':>11}")
            for n, a, b in zip(
                runs, lowest_after(mc, runs), lowest_after(found, runs), strict=True
            ):
                print(f"{n:>6} {a:>12.3f} {b:>10.3f} {b - a:>11.3f}")
            print(
                f"first violation at run: Monte Carlo {first_violation(mc)}, "
                f"falsifier {first_violation(found)}"
            )


if __name__ == "__main__":
    main()
