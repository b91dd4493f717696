"""Planning failures and the wall-clock budget of one plan."""

import time


class PlanningFailed(Exception):
    """A move cannot be planned; the message is the reason reported in the status."""


class Deadline:
    """The wall-clock budget of one plan: the only use of the wall clock in robot motion.

    It bounds how long a hopeless search runs; a plan that succeeds within the budget does
    not depend on it, so results stay deterministic.
    """

    def __init__(self, seconds: float):
        self._end = time.perf_counter() + seconds

    def expired(self) -> bool:
        return time.perf_counter() > self._end

    def check(self, what: str) -> None:
        if self.expired():
            raise PlanningFailed(f"planning time budget exceeded while {what}")
