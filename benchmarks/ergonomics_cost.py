"""What the ergonomic evaluation costs: the share of a run's CPU time spent sampling what the
person's hands hold (the only Python the recording adds: the joint positions are logged by
Drake's C++ logger), and the CPU time of scoring the recorded run afterwards (RULA, REBA,
lifts) against the simulation's. Both are ratios taken in one process.

    .venv/bin/python benchmarks/ergonomics_cost.py [--duration S] [scenario ...]
"""

import argparse
import time

from hrc_drake.evaluation.ergonomics import assessment_of
from hrc_drake.runner import simulate
from hrc_drake.scenario import load_scenario
from hrc_drake.systems.state_changes import StateChanges
from hrc_drake.wiring import HELD_OBJECTS


class SamplerClock:
    """CPU time in the held-objects sampler's publishes (wraps StateChanges._sample)."""

    def __init__(self):
        self.seconds = 0.0
        self._sample = StateChanges._sample

    def __enter__(self):
        sample = self._sample

        def timed(sampler, context):
            start = time.process_time()
            sample(sampler, context)
            if sampler.get_name() == HELD_OBJECTS:
                self.seconds += time.process_time() - start

        StateChanges._sample = timed
        return self

    def __exit__(self, *exc):
        StateChanges._sample = self._sample


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("scenarios", nargs="*", default=["cooperation"])
    parser.add_argument("--duration", type=float, default=20.0)
    args = parser.parse_args()
    for name in args.scenarios:
        scenario = load_scenario(name, [("duration", args.duration)])
        with SamplerClock() as clock:
            start = time.process_time()
            record = simulate(scenario)
            simulation = time.process_time() - start
        start = time.process_time()
        assessment = assessment_of(record)
        scoring = time.process_time() - start
        samples = len(assessment.times) if assessment is not None else 0
        print(
            f"{name}: {args.duration:g} s simulated in {simulation:.2f} CPU s; "
            f"held-objects sampling {clock.seconds / simulation:.2%} of it; "
            f"scoring {samples} samples afterwards {scoring / simulation:.2%} of it"
        )


if __name__ == "__main__":
    main()
