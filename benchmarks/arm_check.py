"""What the person's arm check (hrc_drake.human.clearance) costs in a run of each scenario.

Each scenario runs once (`hrc_drake.runner.run`, no run directory), noting every activity
whose arms are checked as it takes over (`Activity._arms_clear`); the checks are then done
again, `--repeats` times, outside the run. Printed per scenario: how many checks, the CPU
time of one (the fastest repeat's mean) and their share of the run's CPU time. Run it on two
versions of the code to compare them: the run's time includes the checks.

    .venv/bin/python benchmarks/arm_check.py [--duration 30] [--repeats 3] [scenario ...]
"""

import argparse
import time
from unittest import mock

from hrc_drake import runner
from hrc_drake.human.activity import Activity
from hrc_drake.scenario import load_scenario

SCENARIOS = ("coexistence", "cooperation", "collaboration")
CHECK = Activity._arms_clear


def checked_run(name: str, duration: float) -> tuple[float, list]:
    """The run's CPU time and the (activity, performer, time) of each arm check in it."""
    checks = []

    def noted(activity, performer, t):
        checks.append((activity, performer, t))
        return CHECK(activity, performer, t)

    start = time.process_time()
    with mock.patch.object(Activity, "_arms_clear", noted):
        runner.run(load_scenario(name), duration=duration)
    return time.process_time() - start, checks


def checks_time(checks: list) -> float:
    start = time.process_time()
    for activity, performer, t in checks:
        CHECK(activity, performer, t)
    return time.process_time() - start


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("scenarios", nargs="*", default=SCENARIOS)
    parser.add_argument("--duration", type=float, default=30.0)
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args()
    print(f"{'scenario':14s} {'checks':>7s} {'ms/check':>9s} {'share of run':>13s}")
    for name in args.scenarios:
        run_time, checks = checked_run(name, args.duration)
        spent = min(checks_time(checks) for _ in range(args.repeats))
        per_check = 1e3 * spent / max(len(checks), 1)
        print(f"{name:14s} {len(checks):7d} {per_check:9.1f} {spent / run_time:13.3f}")


if __name__ == "__main__":
    main()
