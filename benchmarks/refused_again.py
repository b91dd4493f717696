"""What a tree that retries a command its actor cannot carry out costs, with the failure
planned anew at every ask and remembered, in the same process.

- `person` (default): a user's packing cell (#26), cut down (tests/human/cells/top_board):
  a box on a shelf's 1.6 m board that the person cannot take from where they stand; the
  pick is refused and the tree asks it again at its next tick. Each ask was planned to the
  same refusal: 6.5 s each, a 10 s run took 372 s.
- `robot`: a user's kitting cell, cut down (tests/motion/cells/shelf_out_of_reach): a part
  on a shelf's board the robot cannot reach; the tree asks the RobotMove again at every
  tick. Each was planned to the same failure: a 5 s run took 366 s.

The scenario is run once each way, the memory off first (the person's `_refused_again` or
the robot's `_failed_again` forgetting every failure), wall-clock timed; printed: each
run's wall time and real-time factor, the ratio, the plans made and the failures, and
whether the two runs' reports agree.

    .venv/bin/python benchmarks/refused_again.py [--actor robot] [--duration 10] [cell.yaml]
"""

import argparse
import json
import time
from dataclasses import dataclass
from pathlib import Path

from hrc_drake.human import protocol
from hrc_drake.motion import state_machine
from hrc_drake.motion.planner import MotionPlanner
from hrc_drake.runner import run
from hrc_drake.scenario import load_scenario

CELLS = Path(__file__).resolve().parents[1] / "tests"


@dataclass(frozen=True)
class Memory:
    """Where an actor remembers its last failure, what plans its commands, and the cell
    and tree node that show the retries."""

    module: object
    forget: str
    planner: object
    plan: str
    cell: Path
    tree: str
    node: str


MEMORIES = {
    "person": Memory(
        protocol,
        "_refused_again",
        protocol,
        "plan_animation",
        CELLS / "human/cells/top_board/cell.yaml",
        "human",
        "ActorPick",
    ),
    "robot": Memory(
        state_machine,
        "_failed_again",
        MotionPlanner,
        "plan",
        CELLS / "motion/cells/shelf_out_of_reach/cell.yaml",
        "robot",
        "RobotMove",
    ),
}


def timed_run(memory: Memory, path: Path, duration: float, remembered: bool):
    """Wall seconds of a run of the scenario at `path`, the plans it made and its report's
    metrics; `remembered` False: every failure forgotten."""
    plan, forget, planned = (
        getattr(memory.planner, memory.plan),
        getattr(memory.module, memory.forget),
        [0],
    )

    def counted(*args):
        planned[0] += 1
        return plan(*args)

    setattr(memory.planner, memory.plan, counted)
    if not remembered:
        setattr(memory.module, memory.forget, lambda *args: "")
    try:
        start = time.perf_counter()
        report = run(load_scenario(path), duration=duration)
        wall = time.perf_counter() - start
    finally:
        setattr(memory.planner, memory.plan, plan)
        setattr(memory.module, memory.forget, forget)
    return wall, planned[0], json.dumps(report.metrics, sort_keys=True, default=str)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("scenario", nargs="?", type=Path)
    parser.add_argument("--actor", choices=sorted(MEMORIES), default="person")
    parser.add_argument("--duration", type=float, default=10.0)
    args = parser.parse_args()
    memory = MEMORIES[args.actor]
    path = args.scenario or memory.cell
    before, planned_before, metrics_before = timed_run(memory, path, args.duration, False)
    after, planned_after, metrics_after = timed_run(memory, path, args.duration, True)
    nodes = json.loads(metrics_after)["bt"][memory.tree].items()
    failed = sum(node["failures"] for name, node in nodes if name.startswith(memory.node))
    print(
        f"{path}, {args.duration:.1f} s: {failed} {memory.node} failed; "
        f"planned every ask {before:.1f} s wall (real-time factor "
        f"{args.duration / before:.2f}, {planned_before} planned), remembered {after:.1f} s "
        f"({args.duration / after:.2f}, {planned_after} planned): ratio {before / after:.1f}; "
        f"reports {'agree' if metrics_before == metrics_after else 'DIFFER'}"
    )


if __name__ == "__main__":
    main()
