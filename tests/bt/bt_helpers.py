"""Test nodes and helpers shared by the behavior tree tests (like BT.CPP's test nodes)."""

from __future__ import annotations

from hrc_drake.bt import (
    ConditionNode,
    InputPort,
    StatefulActionNode,
    Status,
    SyncActionNode,
    default_registry,
    load_tree,
)

S, F, R, K = Status.SUCCESS, Status.FAILURE, Status.RUNNING, Status.SKIPPED
IDLE = Status.IDLE


class SettableResult:
    """Returns ``result`` (settable from the test) and counts its ticks."""

    def __init__(self, config):
        super().__init__(config)
        self.result = S
        self.ticks = 0

    def tick(self):
        self.ticks += 1
        return self.result


class Mock(SettableResult, SyncActionNode):
    """A synchronous action with a settable result."""


class MockCondition(SettableResult, ConditionNode):
    """A condition with a settable result."""


class AsyncMock(StatefulActionNode):
    """RUNNING for ``duration`` ticks after the start, then ``result``; counts halts."""

    ports = (InputPort("duration", int, 2), InputPort("result", Status, Status.SUCCESS))

    def __init__(self, config):
        super().__init__(config)
        self.starts = self.halts = self.elapsed = 0

    def on_start(self):
        self.starts += 1
        self.elapsed = 0
        return R

    def on_running(self):
        self.elapsed += 1
        return self.get_input("result") if self.elapsed >= self.get_input("duration") else R

    def on_halted(self):
        self.halts += 1


class RandomResult(SyncActionNode):
    """SUCCESS or FAILURE drawn from the tree's Generator."""

    def tick(self):
        return S if self.rng.random() < 0.5 else F


def registry():
    reg = default_registry()
    for cls in (Mock, MockCondition, AsyncMock, RandomResult):
        reg.register(cls)
    return reg


def tree_of(body: str, reg=None, **kwargs):
    """A tree whose main BehaviorTree is ``body``; extra trees go in ``kwargs['extra']``."""
    extra = kwargs.pop("extra", "")
    xml = (
        f'<root BTCPP_format="4" main_tree_to_execute="Main">'
        f'<BehaviorTree ID="Main">{body}</BehaviorTree>{extra}</root>'
    )
    return load_tree(xml, reg or registry(), **kwargs)


class Recorder:
    """Observer keeping (time, path, previous, new) of every transition."""

    def __init__(self):
        self.transitions = []

    def on_transition(self, time, node, previous, new):
        self.transitions.append((time, node.uid, node.path, previous, new))


def ticks(tree, count, start=0.0, step=0.1):
    """Statuses of ``count`` ticks at start, start+step, ..."""
    return [tree.tick(start + index * step) for index in range(count)]


def statuses(tree):
    return {node.name: node.status for _, _, node in tree.nodes()}


def all_idle(tree):
    return all(node.status is IDLE for _, _, node in tree.nodes())
