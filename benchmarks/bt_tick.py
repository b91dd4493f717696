"""Ticks per second of hrc_drake.bt against py_trees 2.x on the same tree structures.

(a) an 11-node ReactiveSequence: 9 conditions and one asynchronous action;
(b) a 111-node tree: a Parallel of 10 SubTree instances, each a ReactiveSequence of
    conditions, a Fallback, an Inverter and an asynchronous action.
Prints microseconds per tick and the ratio (py_trees / ours). Target: ratio >= 5.
"""

from __future__ import annotations

import time
from collections.abc import Callable

import py_trees

from hrc_drake.bt import StatefulActionNode, Status, default_registry, load_tree

CONDITIONS_A = 9
WORKERS_B = 10


class Working(StatefulActionNode):
    """Asynchronous action that stays RUNNING."""

    def on_start(self):
        return Status.RUNNING

    def on_running(self):
        return Status.RUNNING


def _registry():
    registry = default_registry()
    registry.register_function("Ok", lambda node: Status.SUCCESS, kind="Condition")
    registry.register_function("NotOk", lambda node: Status.FAILURE, kind="Condition")
    registry.register(Working)
    return registry


WORKER_XML = (
    "<ReactiveSequence><Ok/><Ok/><Fallback><NotOk/><NotOk/><Ok/></Fallback>"
    "<Inverter><NotOk/></Inverter><Working/></ReactiveSequence>"
)


def ours_a():
    body = "<ReactiveSequence>" + "<Ok/>" * CONDITIONS_A + "<Working/></ReactiveSequence>"
    return load_tree(
        f'<root BTCPP_format="4"><BehaviorTree ID="A">{body}</BehaviorTree></root>', _registry()
    )


def ours_b():
    subtrees = '<SubTree ID="Worker"/>' * WORKERS_B
    xml = (
        f'<root BTCPP_format="4" main_tree_to_execute="B"><BehaviorTree ID="B">'
        f"<Parallel>{subtrees}</Parallel></BehaviorTree>"
        f'<BehaviorTree ID="Worker">{WORKER_XML}</BehaviorTree></root>'
    )
    return load_tree(xml, _registry())


class PtCondition(py_trees.behaviour.Behaviour):
    def __init__(self, name: str, result: py_trees.common.Status):
        super().__init__(name)
        self.result = result

    def update(self):
        return self.result


class PtWorking(py_trees.behaviour.Behaviour):
    def update(self):
        return py_trees.common.Status.RUNNING


def _ok(name="Ok"):
    return PtCondition(name, py_trees.common.Status.SUCCESS)


def _not_ok(name="NotOk"):
    return PtCondition(name, py_trees.common.Status.FAILURE)


def py_trees_a():
    root = py_trees.composites.Sequence("ReactiveSequence", memory=False)
    root.add_children([_ok(f"Ok{i}") for i in range(CONDITIONS_A)] + [PtWorking("Working")])
    return py_trees.trees.BehaviourTree(root)


def _py_trees_worker(index: int):
    fallback = py_trees.composites.Selector(f"Fallback{index}", memory=False)
    fallback.add_children([_not_ok(), _not_ok(), _ok()])
    inverter = py_trees.decorators.Inverter(f"Inverter{index}", _not_ok())
    worker = py_trees.composites.Sequence(f"Worker{index}", memory=False)
    worker.add_children([_ok(), _ok(), fallback, inverter, PtWorking("Working")])
    return worker


def py_trees_b():
    policy = py_trees.common.ParallelPolicy.SuccessOnAll(synchronise=False)
    root = py_trees.composites.Parallel("Parallel", policy=policy)
    root.add_children([_py_trees_worker(index) for index in range(WORKERS_B)])
    return py_trees.trees.BehaviourTree(root)


def microseconds_per_tick(tick: Callable[[int], object], ticks: int, repeats: int = 5) -> float:
    best = float("inf")
    for _ in range(repeats):
        start = time.perf_counter()
        for index in range(ticks):
            tick(index)
        best = min(best, time.perf_counter() - start)
    return best / ticks * 1e6


def node_count(tree) -> int:
    return sum(1 for _ in tree.nodes())


def compare(label: str, ours, theirs, ticks: int) -> float:
    ours_us = microseconds_per_tick(lambda index: ours.tick(index * 0.05), ticks)
    theirs_us = microseconds_per_tick(lambda index: theirs.tick(), ticks)
    theirs_nodes = sum(1 for _ in theirs.root.iterate())
    ratio = theirs_us / ours_us
    print(
        f"{label}: hrc_drake.bt {ours_us:7.2f} us/tick ({node_count(ours)} nodes) | "
        f"py_trees {theirs_us:7.2f} us/tick ({theirs_nodes} nodes) | ratio {ratio:5.1f}x"
    )
    return ratio


def main() -> None:
    ratios = [
        compare("(a) 11-node ReactiveSequence", ours_a(), py_trees_a(), 5000),
        compare("(b) 100+ node tree with SubTrees", ours_b(), py_trees_b(), 1000),
    ]
    print("target >= 5x on both:", "met" if min(ratios) >= 5 else "NOT met")


if __name__ == "__main__":
    main()
