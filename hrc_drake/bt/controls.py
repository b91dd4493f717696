"""Built-in control nodes, following BehaviorTree.CPP 4.x (src/controls).

A tick here is BehaviorTree.CPP's ``tickExactlyOnce``: where BT.CPP emits a wake-up
signal (AsyncSequence, SequenceWithMemory after a child completed synchronously), the
node returns RUNNING and continues at the next tick.
"""

from __future__ import annotations

from typing import Any

from .errors import BTError
from .node import NodeConfig
from .node_kinds import ControlNode, halt_and_reset
from .ports import InputPort, value_to_text
from .script import EPSILON
from .status import FAILURE, IDLE, RUNNING, SKIPPED, SUCCESS, Status


def _opposite(status: Status) -> Status:
    return SUCCESS if status is FAILURE else FAILURE


class SequentialControl(ControlNode):
    """Sequence (``stops_on=FAILURE``) and Fallback (``stops_on=SUCCESS``): tick the
    children in order, resuming at the RUNNING one, until one returns ``stops_on``.

    ``yields``: return RUNNING after a child completed synchronously (Async variants).
    ``memory``: on ``stops_on`` keep the position (SequenceWithMemory), also when halted.
    """

    def __init__(self, config: NodeConfig, stops_on: Status, yields=False, memory=False):
        super().__init__(config)
        self.stops_on = stops_on
        self.passes_on = _opposite(stops_on)
        self.yields = yields
        self.memory = memory
        self.current = 0
        self.skipped = 0

    def tick(self) -> Status:
        children = self.children
        count = len(children)
        if self.status is IDLE:
            self.skipped = 0
        self.set_status(RUNNING)
        while self.current < count:
            child = children[self.current]
            previous = child.status
            status = child.execute_tick()
            if status is RUNNING:
                return RUNNING
            if status is self.stops_on:
                self._stop()
                return status
            self.current += 1
            if status is SKIPPED:
                self.skipped += 1
            elif self.yields and previous is IDLE and self.current < count:
                return RUNNING
        all_skipped = self.skipped == count
        self.reset_children()
        self.current = self.skipped = 0
        return SKIPPED if all_skipped else self.passes_on

    def _stop(self) -> None:
        if self.memory:
            for index in range(self.current, len(self.children)):
                self.halt_child(index)
        else:
            self.reset_children()
            self.current = 0

    def halt(self) -> None:
        if not self.memory:
            self.current = 0
        self.skipped = 0
        super().halt()

    def on_tree_reset(self) -> None:
        self.current = self.skipped = 0


class ReactiveControl(ControlNode):
    """ReactiveSequence (``stops_on=FAILURE``) and ReactiveFallback (``SUCCESS``): tick
    from the first child at every tick; when one is RUNNING, halt all the others."""

    def __init__(self, config: NodeConfig, stops_on: Status):
        super().__init__(config)
        self.stops_on = stops_on
        self.passes_on = _opposite(stops_on)

    def tick(self) -> Status:
        all_skipped = True
        self.set_status(RUNNING)
        children = self.children
        for index, child in enumerate(children):
            status = child.execute_tick()
            if status is RUNNING:
                for other in children:
                    if other is not child and other.status is not IDLE:
                        halt_and_reset(other)
                return RUNNING
            if status is self.stops_on:
                self.reset_children()
                return status
            if status is SKIPPED:
                self.halt_child(index)
            else:
                all_skipped = False
        self.reset_children()
        return SKIPPED if all_skipped else self.passes_on


def _threshold(value: int, count: int) -> int:
    """Negative thresholds count from the number of children: -1 means all of them."""
    return max(count + value + 1, 0) if value < 0 else value


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
        failure_threshold = _threshold(self.get_input("failure_count"), count)
        if count < required_successes or count < failure_threshold:
            raise self.error(
                f"{count} children are fewer than a threshold: can never "
                f"{'succeed' if count < required_successes else 'fail'}"
            )
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


def _skipped_condition(node: ControlNode) -> BTError:
    """BT.CPP has no branch for a skipped condition and throws; so do we, naming it."""
    condition = node.children[0]
    return node.error(
        f"its condition '{condition.path}' returned SKIPPED: a condition must succeed or fail"
    )


class IfThenElse(ControlNode):
    """Tick the condition (first child) once, then the second child if it succeeded or
    the third (if any) if it failed, until that branch completes."""

    children_range = (2, 3)

    def __init__(self, config: NodeConfig):
        super().__init__(config)
        self.branch = 0

    def tick(self) -> Status:
        self.set_status(RUNNING)
        if self.branch == 0:
            condition = self.children[0].execute_tick()
            if condition is RUNNING:
                return RUNNING
            if condition is SUCCESS:
                self.branch = 1
            elif condition is SKIPPED:
                raise _skipped_condition(self)
            elif len(self.children) == 3:
                self.branch = 2
            else:
                return FAILURE  # as BT.CPP: the condition keeps its FAILURE status
        status = self.children[self.branch].execute_tick()
        if status is RUNNING:
            return RUNNING
        self.reset_children()
        self.branch = 0
        return status

    def halt(self) -> None:
        self.branch = 0
        super().halt()


class WhileDoElse(ControlNode):
    """Re-check the condition at every tick; run the second child while it holds, the
    third (if any) otherwise, halting the branch that is no longer selected."""

    children_range = (2, 3)

    def tick(self) -> Status:
        self.set_status(RUNNING)
        children = self.children
        condition = children[0].execute_tick()
        if condition is RUNNING:
            return RUNNING
        if condition is SKIPPED:
            raise _skipped_condition(self)
        if condition is SUCCESS:
            if len(children) == 3:
                self.halt_child(2)
            status = children[1].execute_tick()
        elif len(children) == 3:
            self.halt_child(1)
            status = children[2].execute_tick()
        else:
            status = FAILURE
        if status is RUNNING:
            return RUNNING
        self.reset_children()
        return status


def _as_number(text: str, enums: dict[str, int]) -> float | None:
    if text in enums:
        return enums[text]
    try:
        return float(text)
    except ValueError:
        return None


def cases_match(variable: Any, case: Any, enums: dict[str, int]) -> bool:
    """Equal as strings, or as numbers (enum names count as their values)."""
    variable_text, case_text = value_to_text(variable), value_to_text(case)
    if variable_text == case_text:
        return True
    variable_number, case_number = _as_number(variable_text, enums), _as_number(case_text, enums)
    return (
        variable_number is not None
        and case_number is not None
        and abs(variable_number - case_number) <= EPSILON
    )


class Switch(ControlNode):
    """SwitchN: tick the child whose ``case_i`` equals ``variable``; the last child is
    the default. A change of case halts the child that was running."""

    def __init__(self, config: NodeConfig, cases: int):
        super().__init__(config)
        self.case_ports = [f"case_{index}" for index in range(1, cases + 1)]
        self.running_child = -1

    @classmethod
    def provided_ports(cls, cases: int) -> tuple:
        return (
            InputPort("variable", default=None, description="value to compare"),
            *(
                InputPort(f"case_{i}", description=f"value of case {i}")
                for i in range(1, cases + 1)
            ),
        )

    @classmethod
    def allowed_children(cls, cases: int) -> tuple[int, int]:
        return cases + 1, cases + 1

    def tick(self) -> Status:
        selected = self._selected_child()
        if self.running_child not in (-1, selected):
            self.halt_child(self.running_child)
        status = self.children[selected].execute_tick()
        if status is SKIPPED:
            self.running_child = -1
        elif status is RUNNING:
            self.running_child = selected
        else:
            self.reset_children()
            self.running_child = -1
        return status

    def _selected_child(self) -> int:
        variable = self.get_input("variable")
        if variable is not None:
            enums = self.tree.enums
            for index, port in enumerate(self.case_ports):
                if cases_match(variable, self.get_input(port, None), enums):
                    return index
        return len(self.case_ports)

    def halt(self) -> None:
        self.running_child = -1
        super().halt()


class TryCatch(ControlNode):
    """Tick the first children as a Sequence; if one fails, tick the last child (the
    catch branch) to completion and return FAILURE."""

    ports = (InputPort("catch_on_halt", bool, False, "run the catch branch when halted"),)
    children_range = (2, None)

    def __init__(self, config: NodeConfig):
        super().__init__(config)
        self.current = 0
        self.skipped = 0
        self.in_catch = False

    def tick(self) -> Status:
        if self.status is IDLE:
            self.skipped = 0
            self.in_catch = False
        self.set_status(RUNNING)
        if self.in_catch:
            return self._tick_catch()
        attempts = len(self.children) - 1
        while self.current < attempts:
            status = self.children[self.current].execute_tick()
            if status is RUNNING:
                return RUNNING
            if status is FAILURE:
                self.reset_children()
                self.current = 0
                self.in_catch = True
                return self._tick_catch()
            self.current += 1
            self.skipped += status is SKIPPED
        all_skipped = self.skipped == attempts
        self.reset_children()
        self.current = self.skipped = 0
        return SKIPPED if all_skipped else SUCCESS

    def _tick_catch(self) -> Status:
        if self.children[-1].execute_tick() is RUNNING:
            return RUNNING
        self.reset_children()
        self.current = 0
        self.in_catch = False
        return FAILURE

    def halt(self) -> None:
        if self.get_input("catch_on_halt") and not self.in_catch and self.status is RUNNING:
            last = len(self.children) - 1
            for index in range(last):
                self.halt_child(index)
            if self.children[last].execute_tick() is RUNNING:
                self.halt_child(last)
        self.current = self.skipped = 0
        self.in_catch = False
        super().halt()
