"""A live Groot2 server for one tree: BehaviorTree.CPP v4's Groot2Publisher on ZeroMQ, serving
requests on ``port`` and publishing breakpoint notifications on ``port + 1``. The bytes on the
wire are :mod:`.groot2_protocol`'s; breakpoints and replacements, :mod:`.groot2_hooks`'s.

Watching changes nothing it watches: the server answers from snapshots the tick thread
hands over at tick boundaries (statuses at every tick; blackboards only while a client has
asked within the last ``HEARTBEAT`` seconds), and hook changes reach the nodes at tick
boundaries too. Times are simulation times. A breakpoint blocks the tick thread, so a
simulator ticking the tree waits with it; a client silent for ``HEARTBEAT`` seconds disables
every hook (as BT.CPP does), so a vanished client cannot leave the run stopped. Garbage,
truncated or oversized frames get an error reply or are dropped by ZeroMQ, never a stall.
"""

from __future__ import annotations

import collections
import contextlib
import itertools
import json
import threading
import time
import uuid
from dataclasses import dataclass
from typing import Any

import msgpack
import zmq

from .groot2_hooks import HookTable
from .groot2_protocol import (
    HEADER,
    IDLE_FROM,
    NODE_STATUS,
    PROTOCOL,
    Refused,
    error_reply,
    json_payload,
    plain_value,
    transition_record,
)
from .model_xml import tree_to_xml
from .node import TreeNode
from .status import IDLE, Status
from .tree import Tree

DEFAULT_PORT = 1667
"""BehaviorTree.CPP's Groot2Publisher default, where Groot2 looks first."""
HEARTBEAT = 5.0
"""Seconds without a request after which hooks are disabled and blackboards not copied."""
MAX_MESSAGE = 1 << 16
"""Bytes; ZeroMQ drops a peer whose message is larger."""
FRESH_WAIT = 0.5
"""Seconds a blackboard request waits for the next tick to bring a snapshot."""
POLL_MS = 100
"""How long the server thread sleeps between looks at closing, heartbeat and notifications."""
RECORDING_LIMIT = 1000
"""Transitions kept between two ``t`` requests (the newest, as BT.CPP)."""


class ServeError(Exception):
    """The server cannot start (port out of range or in use, bad address): one line."""


@dataclass(frozen=True)
class Snapshot:
    """The tree as it was at a tick boundary (or at a breakpoint)."""

    time: float
    statuses: bytes
    blackboards: dict[str, dict[str, Any]] | None


class Groot2Server:
    """Serves ``tree`` on ``host:port`` (requests) and ``port + 1`` (breakpoint
    notifications) from a thread of its own, until ``close()``."""

    def __init__(self, tree: Tree, port: int = DEFAULT_PORT, host: str = "127.0.0.1"):
        if not 1 <= port <= 65534:
            raise ServeError(f"Groot2 port {port} is out of range (1 to 65534: it uses two)")
        self.tree = tree
        self.port = port
        self.host = host
        self._uuid = uuid.uuid4().bytes
        self._xml = tree_to_xml(tree).encode()
        self._offsets: dict[int, int] = {}
        self._codes = bytearray()
        self._blackboards = {
            instance.path or instance.tree_id: instance.blackboard
            for instance, _ in tree.instance_nodes()
        }
        nodes: dict[int, TreeNode] = {}
        for _, instance_nodes in tree.instance_nodes():
            for node in instance_nodes:
                nodes[node.uid] = node
                self._offsets[node.uid] = len(self._codes) + NODE_STATUS.size - 1
                self._codes += NODE_STATUS.pack(node.uid, node.status)
        self.hooks = HookTable(nodes, self._on_pause, POLL_MS / 1000)
        self._recording = False
        self._record_start_us = 0
        self._transitions: collections.deque[tuple[int, int, int]] = collections.deque(
            maxlen=RECORDING_LIMIT
        )
        self._notifications = itertools.count(1)
        self._last_request = time.monotonic()
        self._heartbeat = True
        self.watched = False
        self.paused = False
        self._closing = False
        self._latest = self._snapshot(with_blackboards=True)
        self._context = zmq.Context()
        self._server = self._bind(zmq.REP, port)
        self._publisher = self._bind(zmq.PUB, port + 1)
        tree.add_observer(self)
        tree.add_monitor(self)
        self._thread = threading.Thread(
            target=self._serve, name=f"groot2-{tree.id}-{port}", daemon=True
        )
        self._thread.start()

    @property
    def address(self) -> str:
        return f"{self.host}:{self.port}"

    def _bind(self, kind: int, port: int) -> zmq.Socket:
        socket = self._context.socket(kind)
        socket.setsockopt(zmq.LINGER, 0)
        socket.setsockopt(zmq.MAXMSGSIZE, MAX_MESSAGE)
        try:
            socket.bind(f"tcp://{self.host}:{port}")
        except zmq.ZMQError as error:
            socket.close()
            self._context.destroy(linger=0)
            raise ServeError(
                f"cannot serve Groot2 on {self.host}:{port}: {zmq.strerror(error.errno)}"
            ) from None
        return socket

    # the tick thread ------------------------------------------------------------------
    def on_transition(self, time: float, node: TreeNode, previous: Status, new: Status) -> None:
        self._codes[self._offsets[node.uid]] = new if new is not IDLE else IDLE_FROM + previous
        if self._recording:  # (a simulation restarted from 0 counts from the start)
            offset = max(round(time * 1e6) - self._record_start_us, 0)
            self._transitions.append((offset, node.uid, new))

    def before_tick(self, tree: Tree) -> None:
        if self.hooks.changed:
            self.hooks.install()

    def after_tick(self, tree: Tree) -> None:
        self._latest = self._snapshot(with_blackboards=self.watched)

    def _snapshot(self, with_blackboards: bool) -> Snapshot:
        blackboards = (
            {name: board.snapshot() for name, board in self._blackboards.items()}
            if with_blackboards
            else None
        )
        return Snapshot(self.tree.now, bytes(self._codes), blackboards)

    def _on_pause(self) -> None:
        """A breakpoint was reached: the tick waits, so take the snapshot clients see."""
        self.paused = True
        self._latest = self._snapshot(with_blackboards=True)

    # the server thread ------------------------------------------------------------------
    def _serve(self) -> None:
        poller = zmq.Poller()
        poller.register(self._server, zmq.POLLIN)
        while not self._closing:
            try:
                ready = dict(poller.poll(POLL_MS))
            except zmq.ZMQError:
                break
            if self._server in ready:
                self._answer_one()
            self._publish_reached()
            self._check_heartbeat()

    def _answer_one(self) -> None:
        try:
            frames = self._server.recv_multipart(zmq.NOBLOCK)
        except zmq.ZMQError:
            return
        self._last_request = time.monotonic()
        try:
            reply = self._reply(frames)
        except Exception as error:  # whatever a client sends, the server stays up
            reply = error_reply(f"{type(error).__name__}: {error}")
        with contextlib.suppress(zmq.ZMQError):  # REP drops replies to vanished clients
            self._server.send_multipart(reply, zmq.NOBLOCK)

    def _reply(self, frames: list[bytes]) -> list[bytes]:
        if len(frames[0]) != HEADER.size:
            return error_reply("wrong request header")
        _, kind, request_id = HEADER.unpack(frames[0])
        handler = self._handlers.get(chr(kind))
        if handler is None:
            return error_reply("Request not recognized")
        try:
            payload = handler(self, frames)
        except Refused as refusal:
            return error_reply(str(refusal))
        return [HEADER.pack(PROTOCOL, kind, request_id) + self._uuid, *payload]

    def _full_tree(self, frames) -> list[bytes]:
        return [self._xml]

    def _status(self, frames) -> list[bytes]:
        return [self._latest.statuses]

    def _blackboard(self, frames) -> list[bytes]:
        if len(frames) != 2:
            raise Refused("must be 2 parts message")
        boards = self._fresh_blackboards()
        dump = {
            name: {key: plain_value(value) for key, value in boards[name].items()} or None
            for name in frames[1].decode().split(";")
            if name in boards
        }
        return [msgpack.packb(dump or None, use_bin_type=True)]

    def _fresh_blackboards(self) -> dict[str, dict[str, Any]]:
        """Blackboards of a tick boundary at most one tick old; a request after a silence
        waits for the next tick, or copies them now if the tree is not being ticked."""
        latest = self._latest
        if self.watched and latest.blackboards is not None:
            return latest.blackboards
        self.watched = True
        deadline = time.monotonic() + FRESH_WAIT
        while time.monotonic() < deadline:
            if self._latest is not latest and self._latest.blackboards is not None:
                return self._latest.blackboards
            time.sleep(0.002)
        return self._snapshot(with_blackboards=True).blackboards

    def _insert_hooks(self, frames) -> list[bytes]:
        self.hooks.insert(json_payload(frames))
        return []

    def _unlock(self, frames) -> list[bytes]:
        self.hooks.unlock(json_payload(frames))
        return []

    def _remove_hook(self, frames) -> list[bytes]:
        self.hooks.remove(json_payload(frames))
        return []

    def _remove_all_hooks(self, frames) -> list[bytes]:
        self.hooks.remove_all()
        return []

    def _disable_all_hooks(self, frames) -> list[bytes]:
        self.hooks.enable_all(False)
        return []

    def _dump_hooks(self, frames) -> list[bytes]:
        return [json.dumps(self.hooks.to_json()).encode()]

    def _toggle_recording(self, frames) -> list[bytes]:
        if len(frames) != 2:
            raise Refused("must be 2 parts message")
        command = frames[1].decode()
        if command == "start":
            self._recording = False
            self._transitions.clear()
            self._record_start_us = round(self._latest.time * 1e6)
            self._recording = True
            return [str(self._record_start_us).encode()]
        if command == "stop":
            self._recording = False
        return []

    def _get_transitions(self, frames) -> list[bytes]:
        records = bytearray()
        while self._transitions:
            offset, uid, status = self._transitions.popleft()
            records += transition_record(offset, uid, status)
        return [bytes(records)]

    _handlers = {
        "T": _full_tree,
        "S": _status,
        "B": _blackboard,
        "I": _insert_hooks,
        "R": _remove_hook,
        "U": _unlock,
        "A": _remove_all_hooks,
        "X": _disable_all_hooks,
        "D": _dump_hooks,
        "r": _toggle_recording,
        "t": _get_transitions,
    }

    def _publish_reached(self) -> None:
        while self.hooks.reached:
            uid = self.hooks.reached.popleft()
            header = HEADER.pack(PROTOCOL, ord("N"), next(self._notifications))
            with contextlib.suppress(zmq.ZMQError):  # nobody listening: it still waits
                self._publisher.send_multipart([header, str(uid).encode()], zmq.NOBLOCK)

    def _check_heartbeat(self) -> None:
        """As BT.CPP: no request for HEARTBEAT seconds disables every hook (a vanished
        client must not hold the run), the next request enables them again."""
        alive = time.monotonic() - self._last_request < HEARTBEAT
        self.watched = self.watched and alive
        if alive != self._heartbeat:
            self._heartbeat = alive
            self.hooks.enable_all(alive)

    # lifetime -------------------------------------------------------------------------
    def close(self) -> None:
        """Stop serving, release a paused tick and detach from the tree (call it when
        the tree is not being ticked, e.g. after the simulation)."""
        if self._closing:
            return
        self._closing = True
        self.hooks.release()
        self._thread.join()
        self.hooks.remove_all()
        self.hooks.install()
        self.tree.remove_observer(self)
        self.tree.remove_monitor(self)
        self._server.close()
        self._publisher.close()
        self._context.destroy(linger=0)

    def __enter__(self) -> Groot2Server:
        return self

    def __exit__(self, *exc) -> None:
        self.close()
