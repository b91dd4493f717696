"""What the realism audit costs, and what it finds, on the short run of each scenario.

Each scenario's short run (the seed and length of its scenario test) runs once; the
RealismAudit's updates are timed inside the same run, so the audit's share of the run's CPU
time is a ratio taken in one process. Printed per scenario: the real-time factor (simulated
seconds per CPU second, the whole diagram), the audit's share, the tasks done in the run and
the audit's worst values against their limits (docs/realism.md).

    .venv/bin/python benchmarks/realism_cost.py [coexistence cooperation collaboration]
"""

import argparse
import time
from collections import Counter

from pydrake.systems.analysis import Simulator

from hrc_drake.builder import build_diagram
from hrc_drake.evaluation.realism import LIMITS, PELVIS_SPEED_SWING, realism_metrics
from hrc_drake.scenario import load_scenario
from hrc_drake.systems.realism_audit import RealismAudit

SHORT_RUNS = {"coexistence": (2, 45.0), "cooperation": (0, 50.0), "collaboration": (15, 80.0)}
"""(seed, seconds) of each scenario test's short run."""
TASKS = {
    "coexistence": ("part_finished", "part_added"),
    "cooperation": ("part_good", "part_scrapped"),
    "collaboration": ("box_unloaded", "box_by_person", "handover", "regrip"),
}
"""The task events that count as work done."""


class AuditClock:
    """CPU time spent in the audit's updates (wraps RealismAudit._update while in use)."""

    def __init__(self):
        self.seconds = 0.0
        self._update = RealismAudit._update

    def __enter__(self):
        update = self._update

        def timed(audit, context, state):
            start = time.process_time()
            update(audit, context, state)
            self.seconds += time.process_time() - start

        RealismAudit._update = timed
        return self

    def __exit__(self, *exc):
        RealismAudit._update = self._update


def short_run(name: str):
    """CPU seconds of the whole run and of the audit, task events, realism section."""
    seed, duration = SHORT_RUNS[name]
    with AuditClock() as clock:  # the audit binds its update when it is built
        diagram = build_diagram(load_scenario(name, [("seed", seed)]))
        simulator = Simulator(diagram)
        context = simulator.get_context()
        simulator.Initialize()
        start = time.process_time()
        simulator.AdvanceTo(duration)
        total = time.process_time() - start
    events = Counter(
        event.name
        for agent in ("robot", "human")
        for event in diagram.GetOutputPort(f"{agent}_task_events").Eval(context)
    )
    realism = realism_metrics(diagram.GetOutputPort("realism").Eval(context))
    return duration, total, clock.seconds, events, realism


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("scenarios", nargs="*", default=list(SHORT_RUNS))
    args = parser.parse_args()
    for name in args.scenarios:
        duration, total, audit, events, realism = short_run(name)
        tasks = ", ".join(f"{task} {events[task]}" for task in TASKS[name])
        print(f"{name}: {duration:.0f} s, RTF {duration / total:.2f}, audit {audit / total:.1%}")
        print(f"  tasks: {tasks}")
        for measure, limit in LIMITS.items():
            worst = realism[measure]
            where = worst.get("where") or worst.get("object") or worst.get("point")
            value, when = worst["max"], worst["time"]
            print(f"  {measure:20s} {value:8.3f} (limit {limit:g}) {where} at {when:.1f} s")
        pelvis = realism["pelvis_speed"]
        print(
            f"  {'pelvis_speed':20s} {pelvis['variation_max']:8.3f} (limit {PELVIS_SPEED_SWING:g})"
            f" median {pelvis['variation_median']:.3f} over {pelvis['strides']} strides"
        )


if __name__ == "__main__":
    main()
