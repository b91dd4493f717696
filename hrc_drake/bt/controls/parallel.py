"""Parallel and ParallelAll: every child ticked at each tick, following BehaviorTree.CPP 4.x."""

from __future__ import annotations

from ..node import NodeConfig
from ..node_kinds import ControlNode
from ..ports import InputPort
from ..status import FAILURE, RUNNING, SKIPPED, SUCCESS, Status


def _threshold(value: int, count: int) -> int:
    """Negative thresholds count from the number of children: -1 means all of them."""
    return max(count + value + 1, 0) if value < 0 else value


THRESHOLDS = {"success_count": "succeed", "failure_count": "fail"}
"""Parallel's thresholds, and what the node could never do when one exceeds its children."""


class Parallel(ControlNode):
    """Tick every child not yet completed; SUCCESS once ``success_count`` succeeded,
    FAILURE once ``failure_count`` failed or success became impossible."""

    ports = (
        InputPort("success_count", int, -1, "successes needed (-1 = all children)"),
        InputPort("failure_count", int, 1, "failures that make the node fail (-1 = all)"),
    )

    def __init__(self, config: NodeConfig):
        super().__init__(config)
        self.completed: set[int] = set()
        self.successes = self.failures = 0

    def tick(self) -> Status:
        count = len(self.children)
        success_value = self.get_input("success_count")
        required_successes = _threshold(success_value, count)
        failure_value = self.get_input("failure_count")
        failure_threshold = _threshold(failure_value, count)
        for port, value in (("success_count", success_value), ("failure_count", failure_value)):
            if problem := self.input_problem(port, value):
                raise self.error(problem, port=port)
        self.set_status(RUNNING)
        skipped = 0
        for index, child in enumerate(self.children):
            if index not in self.completed:
                status = child.execute_tick()
                if status is SKIPPED:
                    skipped += 1
                elif status is SUCCESS:
                    self.completed.add(index)
                    self.successes += 1
                elif status is FAILURE:
                    self.completed.add(index)
                    self.failures += 1
            if self.successes >= required_successes or (
                success_value < 0 and self.successes + skipped >= required_successes
            ):
                return self._decide(SUCCESS)
            if count - self.failures < required_successes or self.failures == failure_threshold:
                return self._decide(FAILURE)
        return SKIPPED if skipped == count else RUNNING

    def input_problem(self, port: str, value) -> str:
        """A threshold beyond the number of children: the node could never succeed (or
        fail) by it (the tree builder finds a literal, `validate` a parameter)."""
        problem = super().input_problem(port, value)
        count = len(self.children)
        if problem or port not in THRESHOLDS or _threshold(value, count) <= count:
            return problem
        return f"{count} children are fewer than {value}: it can never {THRESHOLDS[port]}"

    def _decide(self, status: Status) -> Status:
        self._clear()
        self.reset_children()
        return status

    def _clear(self) -> None:
        self.completed.clear()
        self.successes = self.failures = 0

    def halt(self) -> None:
        self._clear()
        super().halt()


class ParallelAll(ControlNode):
    """Tick every child until all completed; FAILURE if at least ``max_failures`` failed."""

    ports = (InputPort("max_failures", int, 1, "failures that make the node fail (-1 = all)"),)

    def __init__(self, config: NodeConfig):
        super().__init__(config)
        self.completed: set[int] = set()
        self.failures = 0

    def tick(self) -> Status:
        count = len(self.children)
        failure_threshold = _threshold(self.get_input("max_failures"), count)
        if count < failure_threshold:
            raise self.error(f"{count} children are fewer than max_failures: can never fail")
        self.set_status(RUNNING)
        skipped = 0
        for index, child in enumerate(self.children):
            if index in self.completed:
                continue
            status = child.execute_tick()
            if status is SKIPPED:
                skipped += 1
            elif status is not RUNNING:
                self.completed.add(index)
                self.failures += status is FAILURE
        if skipped == count:
            return SKIPPED
        if skipped + len(self.completed) < count:
            return RUNNING
        self.reset_children()
        result = FAILURE if self.failures >= failure_threshold else SUCCESS
        self.completed.clear()
        self.failures = 0
        return result

    def halt(self) -> None:
        self.completed.clear()
        self.failures = 0
        super().halt()
