"""An instantiated tree: ticked with the simulation time, observed, halted, reset."""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass
from typing import Any, Protocol

import numpy as np

from .blackboard import Blackboard
from .node import TreeNode
from .registry import NodeRegistry
from .status import FAILURE, IDLE, SUCCESS, Status


class TransitionObserver(Protocol):
    """Receives every status change. Optional ``attach(tree)`` is called when added."""

    def on_transition(self, time: float, node: TreeNode, previous: Status, new: Status) -> None: ...


class TickMonitor(Protocol):
    """Called at the boundaries of every tick (e.g. a Groot2 server taking snapshots):
    the only moments at which the tree is consistent and may be changed from outside."""

    def before_tick(self, tree: Tree) -> None: ...

    def after_tick(self, tree: Tree) -> None: ...


@dataclass(frozen=True)
class SubtreeInstance:
    """One instance of a <BehaviorTree> in the tree (the main tree has path "")."""

    tree_id: str
    path: str
    root: TreeNode
    blackboard: Blackboard


class Tree:
    """Nodes built by a TreeFactory. Deterministic: time comes only from ``tick(now)``,
    randomness only from ``rng``; ``agent`` is the application's handle for nodes (the agent
    the tree drives)."""

    def __init__(
        self, tree_id: str, registry: NodeRegistry, rng: np.random.Generator, agent: Any = None
    ):
        self.id = tree_id
        self.registry = registry
        self.enums = registry.enums
        self.rng = rng
        self.agent = agent
        self.now = 0.0
        self.observers: list[TransitionObserver] = []
        self.monitors: list[TickMonitor] = []
        self.subtrees: list[SubtreeInstance] = []
        self.node_list: list[TreeNode] = []

    @property
    def root(self) -> TreeNode:
        return self.subtrees[0].root

    @property
    def root_blackboard(self) -> Blackboard:
        return self.subtrees[0].blackboard

    @property
    def status(self) -> Status:
        return self.root.status

    def tick(self, now: float) -> Status:
        """Tick the root once at simulation time ``now`` (seconds); a completed root is
        reset to IDLE afterwards, so the next tick starts a new run."""
        self.now = now
        for monitor in self.monitors:
            monitor.before_tick(self)
        status = self.root.execute_tick()
        if status is SUCCESS or status is FAILURE:
            self.root.reset_status()
        for monitor in self.monitors:
            monitor.after_tick(self)
        return status

    def halt(self) -> None:
        """Halt every running node (each once); all nodes end IDLE."""
        root = self.root
        if root.status is not IDLE:
            root.halt_node()
        for node in self.node_list:  # completed children that no parent reset (as BT.CPP)
            node.reset_status()

    def reset(self, rng: np.random.Generator | None = None) -> None:
        """Back to the state after construction: halted, node memory and blackboards
        restored; optionally with a new random generator for the next run."""
        self.halt()
        for node in self.node_list:
            node.on_tree_reset()
        for instance in self.subtrees:
            instance.blackboard.restore_initial_state()
        if rng is not None:
            self.rng = rng

    def nodes(self) -> Iterator[tuple[int, str, TreeNode]]:
        """(uid, path, node) in depth-first pre-order, SubTrees expanded."""
        for node in self.node_list:
            yield node.uid, node.path, node

    def instance_nodes(self) -> Iterator[tuple[SubtreeInstance, list[TreeNode]]]:
        """Each SubTree instance with its own nodes in pre-order (a SubTree node belongs
        to the instance that contains it): BehaviorTree.CPP's ``tree.subtrees[i]->nodes``."""
        for instance in self.subtrees:
            nodes: list[TreeNode] = []
            pending = [instance.root]
            while pending:
                node = pending.pop()
                nodes.append(node)
                if node.kind != "SubTree":
                    pending.extend(reversed(node.children_nodes()))
            yield instance, nodes

    def node(self, path_or_name: str) -> TreeNode:
        """The node with this path, or else the first with this name."""
        for node in self.node_list:
            if node.path == path_or_name:
                return node
        for node in self.node_list:
            if node.name == path_or_name:
                return node
        raise KeyError(path_or_name)

    def add_observer(self, observer: TransitionObserver) -> None:
        self.observers.append(observer)
        attach = getattr(observer, "attach", None)
        if attach is not None:
            attach(self)

    def remove_observer(self, observer: TransitionObserver) -> None:
        self.observers.remove(observer)

    def add_monitor(self, monitor: TickMonitor) -> None:
        self.monitors.append(monitor)

    def remove_monitor(self, monitor: TickMonitor) -> None:
        self.monitors.remove(monitor)

    def notify(self, node: TreeNode, previous: Status, new: Status) -> None:
        for observer in self.observers:
            observer.on_transition(self.now, node, previous, new)
