"""IfThenElse, WhileDoElse and SwitchN: one child chosen by a condition or by a value,
following BehaviorTree.CPP 4.x."""

from __future__ import annotations

from typing import Any

from ..errors import BTError
from ..node import NodeConfig
from ..node_kinds import ControlNode
from ..ports import InputPort, value_to_text
from ..script import EPSILON
from ..status import FAILURE, RUNNING, SKIPPED, SUCCESS, Status


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
