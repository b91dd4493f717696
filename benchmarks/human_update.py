"""What the person's update costs in a scenario's short run, and what the arms' check costs
with and without the feet placed.

The run is simulated once, the HumanActor's updates timed by this process's CPU time; at
every change of activity the arms' check of the new activity (`clearance.arm_correction`,
the largest single cost of an update that takes a command) is worked out twice in turn:
from the arms' poses, as the person does (the feet left unplaced: they move no arm), and
from the full poses (feet placed, as before). The two must give the same correction, bit
for bit; their CPU times are compared in the same process.

    .venv/bin/python benchmarks/human_update.py [--duration 30] [coexistence collaboration ...]
"""

import sys
import time
from pathlib import Path

import numpy as np
from pydrake.systems.analysis import Simulator

from hrc_drake.builder import build_diagram
from hrc_drake.human.activity import Activity
from hrc_drake.scenario import load_scenario
from hrc_drake.systems.human_actor import HumanActor

sys.path.insert(0, str(Path(__file__).resolve().parent))
from realism_cost import SHORT_RUNS, short_runs_asked  # noqa: E402


class Clocks:
    """CPU seconds of the person's updates and of the arms' checks both ways, while in use."""

    def __init__(self):
        self.update = 0.0
        self.arms = 0.0
        self.full = 0.0
        self.checks = 0
        self.differing = 0
        self._originals = (HumanActor._update, Activity._arms_clear, Activity._blended_pose)

    def __enter__(self):
        update, arms_clear, blended = self._originals

        def timed_update(actor, context, state):
            start = time.process_time()
            update(actor, context, state)
            self.update += time.process_time() - start

        def both_ways(activity, performer, t):
            start = time.process_time()
            correction = arms_clear(activity, performer, t)
            self.arms += time.process_time() - start
            Activity._blended_pose = lambda a, p, u, arms_only=False: blended(a, p, u)
            start = time.process_time()
            full = arms_clear(activity, performer, t)
            self.full += time.process_time() - start
            Activity._blended_pose = blended
            self.checks += 1
            self.differing += not _same(correction, full)
            return correction

        HumanActor._update, Activity._arms_clear = timed_update, both_ways
        return self

    def __exit__(self, *exc):
        HumanActor._update, Activity._arms_clear, Activity._blended_pose = self._originals


def _same(a, b) -> bool:
    """Whether two activities' corrections (head, then arms) are the same, key for key."""
    return len(a) == len(b) and all(
        x.times == y.times
        and all(np.array_equal(u, v) for u, v in zip(x.offsets, y.offsets, strict=True))
        for x, y in zip(a, b, strict=True)
    )


def _ratio(numerator: float, denominator: float) -> str:
    return f"ratio {numerator / denominator:.2f}" if denominator > 0 else "no ratio"


def main() -> None:
    args = short_runs_asked(__doc__)
    for name in args.scenarios:
        with Clocks() as clocks:
            simulator = Simulator(build_diagram(load_scenario(name, [("seed", SHORT_RUNS[name])])))
            simulator.Initialize()
            start = time.process_time()
            simulator.AdvanceTo(args.duration)
            total = time.process_time() - start - clocks.full  # the run as the person runs it
        print(
            f"{name} seed {SHORT_RUNS[name]}, {args.duration:.0f} s: the person's updates "
            f"{clocks.update - clocks.full:.2f} s of {total:.2f} s CPU "
            f"({(clocks.update - clocks.full) / total:.1%}); arms' checks at "
            f"{clocks.checks} changes of activity: {clocks.arms:.2f} s from the arms' poses, "
            f"{clocks.full:.2f} s from the full poses ({_ratio(clocks.arms, clocks.full)}), "
            f"{clocks.differing} corrections differing"
        )


if __name__ == "__main__":
    main()
