"""What the realism audit costs, and what it finds, on a short run of each scenario.

Each scenario's short run is simulated twice in this process, with the audit and without it
(the station built with no RealismAudit), the two advancing `SLICE` simulated seconds each in
turn and timed by this process's CPU time, so that load from other processes falls on both
alike. The audit's cost is then the run's extra time with it (its recording during the run)
and the time its `realism` output takes to read after the run (the audit proper), both as a
share of the run without it. Printed per scenario: the real-time factor without the audit,
the two shares, and the audit's worst values against their limits (docs/realism.md).

    .venv/bin/python benchmarks/realism_cost.py [--duration 30] [coexistence cooperation ...]
"""

import argparse
import sys
import time
from pathlib import Path

from pydrake.systems.analysis import Simulator

from hrc_drake import builder
from hrc_drake.evaluation.realism import LIMITS, PELVIS_SPEED_SWING, realism_metrics
from hrc_drake.scenario import load_scenario

sys.path.insert(0, str(Path(__file__).resolve().parent))
from scenarios import timed_in_turns  # noqa: E402

SHORT_RUNS = {"coexistence": 0, "cooperation": 0, "collaboration": 15}
"""The seed of each scenario's short run."""


def simulator(name: str, with_audit: bool):
    """The scenario's run, initialized; without the audit its station has none."""
    add_audit = builder._add_audit
    if not with_audit:
        builder._add_audit = lambda *args: None
    try:
        diagram = builder.build_diagram(load_scenario(name, [("seed", SHORT_RUNS[name])]))
    finally:
        builder._add_audit = add_audit
    simulator = Simulator(diagram)
    simulator.Initialize()
    return simulator


def audit_cost(name: str, duration: float):
    """CPU seconds of the run without the audit and with it, of reading the audit after the
    run, and the audit's realism section."""
    audited, bare = simulator(name, True), simulator(name, False)
    with_audit, without = timed_in_turns([audited, bare], duration, time.process_time)
    start = time.process_time()
    realism = audited.get_system().GetOutputPort("realism").Eval(audited.get_context())
    read = time.process_time() - start
    return without, with_audit, read, realism_metrics(realism)


def short_runs_asked(doc: str) -> argparse.Namespace:
    """The scenarios (of SHORT_RUNS) and the duration a short-run benchmark is asked for."""
    return short_runs_parser(doc).parse_args()


def short_runs_parser(doc: str) -> argparse.ArgumentParser:
    """`short_runs_asked`'s parser, for a benchmark that asks more."""
    parser = argparse.ArgumentParser(description=doc.splitlines()[0])
    parser.add_argument("scenarios", nargs="*", default=list(SHORT_RUNS))
    parser.add_argument("--duration", type=float, default=30.0)
    return parser


def main() -> None:
    args = short_runs_asked(__doc__)
    for name in args.scenarios:
        without, with_audit, read, realism = audit_cost(name, args.duration)
        print(
            f"{name} seed {SHORT_RUNS[name]}, {args.duration:.0f} s: RTF without the audit "
            f"{args.duration / without:.2f}; the audit adds {with_audit / without - 1:+.1%} "
            f"during the run and {read / without:.1%} to read it after"
        )
        for measure, limit in LIMITS.items():
            worst = realism[measure]
            where = worst.get("where") or worst.get("object") or worst.get("point")
            value, when = worst["max"], worst["time"]
            print(f"  {measure:20s} {value:8.4f} (limit {limit:g}) {where} at {when:.2f} s")
        pelvis = realism["pelvis_speed"]
        print(
            f"  {'pelvis_speed':20s} {pelvis['variation_max']:8.4f} (limit {PELVIS_SPEED_SWING:g})"
            f" median {pelvis['variation_median']:.4f} over {pelvis['strides']} strides"
        )


if __name__ == "__main__":
    main()
