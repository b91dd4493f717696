"""The kinds of node an author subclasses, with BehaviorTree.CPP's rules for each: actions
that complete within their tick, conditions, stateful (asynchronous) actions, and the
parents, controls and decorators, which halt and reset their children.
"""

from __future__ import annotations

from abc import abstractmethod
from typing import ClassVar

from .node import NodeConfig, TreeNode
from .status import FAILURE, IDLE, RUNNING, SUCCESS, Status


def halt_and_reset(node: TreeNode) -> None:
    """Halt ``node`` if it is RUNNING, then make it IDLE (BT.CPP's haltChild)."""
    if node.status is RUNNING:
        node.halt_node()
    if node.status is not IDLE:
        node.set_status(IDLE)


class SyncActionNode(TreeNode):
    """An action that completes within its tick: ``tick`` returns SUCCESS or FAILURE."""

    synchronous: ClassVar[bool] = True


class ConditionNode(SyncActionNode):
    """A check without side effects: ``tick`` returns SUCCESS or FAILURE."""

    kind: ClassVar[str] = "Condition"


class StatefulActionNode(TreeNode):
    """An asynchronous action: ``on_start`` when first ticked, ``on_running`` on later
    ticks while RUNNING, ``on_halted`` if it is interrupted while RUNNING."""

    @abstractmethod
    def on_start(self) -> Status:
        """First tick: start the action; RUNNING, or its result at once."""

    @abstractmethod
    def on_running(self) -> Status:
        """Later ticks while RUNNING: RUNNING until the action has its result."""

    def on_halted(self) -> None:
        """Cancel whatever the action started (default: nothing)."""

    def tick(self) -> Status:
        if self.status is IDLE:
            status = self.on_start()
        elif self.status is RUNNING:
            status = self.on_running()
        else:
            return self.status
        if status is IDLE:
            raise self.error(f"{type(self).__name__} must not return IDLE")
        return status

    def halt(self) -> None:
        if self.status is RUNNING:
            self.on_halted()
        self.reset_status()


class ControlNode(TreeNode):
    """A node with one or more children, ticked in an order the subclass decides."""

    kind: ClassVar[str] = "Control"
    children_range: ClassVar[tuple[int, int | None]] = (1, None)

    def __init__(self, config: NodeConfig):
        super().__init__(config)
        self.children: list[TreeNode] = []

    def children_nodes(self) -> list[TreeNode]:
        return self.children

    def halt_child(self, index: int) -> None:
        halt_and_reset(self.children[index])

    def reset_children(self) -> None:
        for child in self.children:
            if child.status is not IDLE:
                halt_and_reset(child)

    def halt(self) -> None:
        self.reset_children()
        self.reset_status()


class DecoratorNode(TreeNode):
    """A node with exactly one child, whose result it transforms."""

    kind: ClassVar[str] = "Decorator"
    children_range: ClassVar[tuple[int, int | None]] = (1, 1)

    def __init__(self, config: NodeConfig):
        super().__init__(config)
        self.child: TreeNode | None = None

    def children_nodes(self) -> list[TreeNode]:
        return [self.child] if self.child is not None else []

    def reset_child(self) -> None:
        halt_and_reset(self.child)

    def halt(self) -> None:
        self.reset_child()
        self.reset_status()

    def execute_tick(self) -> Status:
        status = TreeNode.execute_tick(self)
        child_status = self.child.status
        if child_status is SUCCESS or child_status is FAILURE:
            self.child.reset_status()
        return status
