"""What a tree that retries a pick the person cannot make costs, with the refusal planned
anew at every ask (as before the person remembered it) and remembered, in the same process.

A user's packing cell (#26), cut down (tests/human/cells/top_board): a box on a shelf's
1.6 m board that the person cannot take from where they stand; the pick is refused and the
tree asks it again at its next tick. Each ask was planned to the same refusal: 6.5 s each,
a 10 s run took 372 s. The scenario is run once each way, the memory off first (the
protocol's `_refused_again` forgetting every refusal), wall-clock timed; printed: each
run's wall time and real-time factor, the ratio, the picks planned and refused, and
whether the two runs' reports agree.

    .venv/bin/python benchmarks/refused_again.py [--duration 10] [cell.yaml]
"""

import argparse
import json
import time
from pathlib import Path

from hrc_drake.human import protocol
from hrc_drake.runner import run
from hrc_drake.scenario import load_scenario

TOP_BOARD = Path(__file__).resolve().parents[1] / "tests/human/cells/top_board/cell.yaml"


def timed_run(path: Path, duration: float, remembered: bool):
    """Wall seconds of a run of the scenario at `path`, the animations it planned and its
    report's metrics; `remembered` False: every refusal forgotten."""
    plan, forget, planned = protocol.plan_animation, protocol._refused_again, [0]

    def counted(*args):
        planned[0] += 1
        return plan(*args)

    protocol.plan_animation = counted
    if not remembered:
        protocol._refused_again = lambda state, asked: ""
    try:
        start = time.perf_counter()
        report = run(load_scenario(path), duration=duration)
        wall = time.perf_counter() - start
    finally:
        protocol.plan_animation, protocol._refused_again = plan, forget
    return wall, planned[0], json.dumps(report.metrics, sort_keys=True, default=str)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("scenario", nargs="?", type=Path, default=TOP_BOARD)
    parser.add_argument("--duration", type=float, default=10.0)
    args = parser.parse_args()
    before, planned_before, metrics_before = timed_run(args.scenario, args.duration, False)
    after, planned_after, metrics_after = timed_run(args.scenario, args.duration, True)
    nodes = json.loads(metrics_after)["bt"]["human"].items()
    picks = sum(node["failures"] for name, node in nodes if name.startswith("ActorPick"))
    print(
        f"{args.scenario}, {args.duration:.1f} s: {picks} picks refused; "
        f"planned every ask {before:.1f} s wall (real-time factor "
        f"{args.duration / before:.2f}, {planned_before} planned), remembered {after:.1f} s "
        f"({args.duration / after:.2f}, {planned_after} planned): ratio {before / after:.1f}; "
        f"reports {'agree' if metrics_before == metrics_after else 'DIFFER'}"
    )


if __name__ == "__main__":
    main()
