"""Transition observers: Groot2 .btlog and JSON-lines writers, per-node counters."""

from __future__ import annotations

import json
import os
import struct
from dataclasses import dataclass

from .model_xml import tree_to_xml
from .node import TreeNode
from .status import IDLE, RUNNING, Status
from .tree import Tree

BTLOG_MAGIC = b"BTCPP4-FileLogger2"
BTLOG_PROTOCOL = 1


def _microseconds(seconds: float) -> int:
    return round(seconds * 1_000_000)


class BtlogWriter:
    """Writes Groot2's FileLogger2 format: header (magic, protocol, XML with uids,
    start time) then one 9-byte record per transition, times in simulation µs."""

    def __init__(self, path: str | os.PathLike):
        self.path = path
        self._file = None
        self._start_us = 0

    def attach(self, tree: Tree) -> None:
        xml = tree_to_xml(tree).encode()
        self._start_us = _microseconds(tree.now)
        self._file = open(self.path, "wb")  # noqa: SIM115 - closed by close()
        self._file.write(BTLOG_MAGIC + struct.pack("<Bi", BTLOG_PROTOCOL, len(xml)) + xml)
        self._file.write(struct.pack("<q", self._start_us))

    def on_transition(self, time: float, node: TreeNode, previous: Status, new: Status) -> None:
        offset = _microseconds(time) - self._start_us
        self._file.write(struct.pack("<Q", offset)[:6] + struct.pack("<HB", node.uid, new))

    def close(self) -> None:
        if self._file is not None:
            self._file.close()
            self._file = None


class JsonLinesWriter:
    """One JSON object per transition: time, uid, path, node name, from, to, and for a
    FAILURE the reason the node gave, when it gave one."""

    def __init__(self, path: str | os.PathLike):
        self._file = open(path, "w")  # noqa: SIM115 - closed by close()

    def on_transition(self, time: float, node: TreeNode, previous: Status, new: Status) -> None:
        record = {
            "t": time,
            "uid": node.uid,
            "path": node.path,
            "node": node.registration_id,
            "from": previous.name,
            "to": new.name,
        }
        if new is Status.FAILURE and node.failure_reason:
            record["reason"] = node.failure_reason
        self._file.write(json.dumps(record) + "\n")

    def close(self) -> None:
        self._file.close()


@dataclass
class NodeCount:
    ticks: int = 0
    successes: int = 0
    failures: int = 0
    skipped: int = 0
    time_running: float = 0.0
    last_status: Status = IDLE
    first_failure: str = ""
    """The reason the node gave the first time it failed with one."""


class NodeCounters:
    """Per node: ticks, results, simulated time spent RUNNING, last non-IDLE status."""

    def __init__(self) -> None:
        self.tree: Tree | None = None
        self._running_since: dict[int, float] = {}
        self._time_running: dict[int, float] = {}
        self._last_status: dict[int, Status] = {}
        self._first_failure: dict[int, str] = {}

    def attach(self, tree: Tree) -> None:
        self.tree = tree
        self.reset()

    def reset(self) -> None:
        """Start counting afresh (a new run of the same tree)."""
        self._running_since.clear()
        self._time_running.clear()
        self._last_status.clear()
        self._first_failure.clear()
        for node in self.tree.node_list:
            node.tick_counts = [0] * len(Status)

    def on_transition(self, time: float, node: TreeNode, previous: Status, new: Status) -> None:
        if new is RUNNING:
            self._running_since[node.uid] = time
        elif previous is RUNNING and node.uid in self._running_since:
            started = self._running_since.pop(node.uid)
            self._time_running[node.uid] = self._time_running.get(node.uid, 0.0) + time - started
        if new is not IDLE:
            self._last_status[node.uid] = new
        if new is Status.FAILURE and node.failure_reason:
            self._first_failure.setdefault(node.uid, node.failure_reason)

    def count(self, node: TreeNode) -> NodeCount:
        counts = node.tick_counts or [0] * len(Status)
        running = self._time_running.get(node.uid, 0.0)
        if node.uid in self._running_since:
            running += self.tree.now - self._running_since[node.uid]
        return NodeCount(
            ticks=sum(counts),
            successes=counts[Status.SUCCESS],
            failures=counts[Status.FAILURE],
            skipped=counts[Status.SKIPPED],
            time_running=running,
            last_status=self._last_status.get(node.uid, IDLE),
            first_failure=self._first_failure.get(node.uid, ""),
        )

    def counts(self) -> dict[int, NodeCount]:
        return {node.uid: self.count(node) for node in self.tree.node_list}
