"""A live Groot2 server for one tree: BehaviorTree.CPP v4's Groot2Publisher protocol on ZeroMQ.

A client (Groot2, btview, ...) connects a REQ socket to ``port`` and a SUB socket to
``port + 1``. A request is a multipart message whose first frame is a 6-byte header
(protocol 2, request type, request id as little-endian uint32); the reply repeats it, adds the
tree's 16-byte UUID, then the payload (BehaviorTree.CPP's groot2_protocol.h):

- ``T`` the tree XML with ``_uid`` attributes and the TreeNodesModel (as the .btlog header);
- ``S`` 3 bytes per node (uid, status; an IDLE node reports 10 + its previous status),
  SubTree instance after instance;
- ``B`` the blackboards named in the second frame (``;``-separated: the main tree's ID or a
  SubTree's path) as a MessagePack map;
- ``I`` ``R`` ``U`` ``A`` ``X`` ``D``: insert, remove, unlock, remove all, disable all and dump
  the hooks (JSON, as Groot2 sends them); ``N`` is published on ``port + 1`` when a
  breakpoint is reached;
- ``r`` start/stop recording transitions, ``t`` fetch them (9 bytes each: 6-byte microsecond
  offset from the start, uid, new status).

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
import enum
import itertools
import json
import struct
import threading
import time
import uuid
from dataclasses import dataclass
from functools import partial
from typing import Any

import msgpack
import zmq

from .model_xml import tree_to_xml
from .node import TreeNode
from .ports import value_to_text
from .status import IDLE, SKIPPED, Status
from .tree import Tree

DEFAULT_PORT = 1667
"""BehaviorTree.CPP's Groot2Publisher default, where Groot2 looks first."""
PROTOCOL = 2
HEADER = struct.Struct("<BBI")
IDLE_FROM = 10
"""Status code of a node gone IDLE: 10 + the status it had."""
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


class Position(enum.IntEnum):
    PRE = 0
    POST = 1


class Mode(enum.IntEnum):
    BREAKPOINT = 0
    REPLACE = 1


class Refused(Exception):
    """A request the server answers with an error reply."""


@dataclass
class Hook:
    """A breakpoint (waits until unlocked) or a replacement (returns ``desired_status``)
    before or after a node's tick, as Groot2 describes it in JSON."""

    uid: int
    position: Position
    mode: Mode = Mode.BREAKPOINT
    once: bool = False
    enabled: bool = True
    desired_status: Status = SKIPPED
    ready: bool = False

    @classmethod
    def from_json(cls, data: dict) -> Hook:
        hook = cls(int(data["uid"]), Position(int(data["position"])))
        hook.update(data)
        return hook

    def update(self, data: dict) -> None:
        self.enabled = bool(data["enabled"])
        self.once = bool(data["once"])
        self.mode = Mode(int(data["mode"]))
        self.desired_status = Status[str(data["desired_status"])]

    def to_json(self) -> dict:
        return {
            "enabled": self.enabled,
            "uid": self.uid,
            "mode": int(self.mode),
            "once": self.once,
            "desired_status": self.desired_status.name,
            "position": int(self.position),
        }


@dataclass(frozen=True)
class Snapshot:
    """The tree as it was at a tick boundary (or at a breakpoint)."""

    time: float
    statuses: bytes
    blackboards: dict[str, dict[str, Any]] | None


def _plain(value: Any) -> Any:
    """A blackboard value as MessagePack can carry it (other types as their text)."""
    if value is None or isinstance(value, bool | int | float | str):
        return value
    if isinstance(value, enum.Enum):
        return value.name
    if isinstance(value, list | tuple):
        return [_plain(item) for item in value]
    return value_to_text(value)


def _json_frame(frames: list[bytes]) -> Any:
    if len(frames) != 2:
        raise Refused("must be 2 parts message")
    return json.loads(frames[1].decode())


def _error(message: str) -> list[bytes]:
    return [b"error", message.encode()]


class Groot2Server:
    """Serves ``tree`` on ``host:port`` (requests) and ``port + 1`` (breakpoint
    notifications) from a thread of its own, until ``close()``."""

    def __init__(self, tree: Tree, port: int = 1667, host: str = "127.0.0.1"):
        if not 1 <= port <= 65534:
            raise ServeError(f"Groot2 port {port} is out of range (1 to 65534: it uses two)")
        self.tree = tree
        self.port = port
        self.host = host
        self._uuid = uuid.uuid4().bytes
        self._xml = tree_to_xml(tree).encode()
        self._nodes: dict[int, TreeNode] = {}
        self._offsets: dict[int, int] = {}
        self._codes = bytearray()
        self._blackboards = {
            instance.path or instance.tree_id: instance.blackboard
            for instance, _ in tree.instance_nodes()
        }
        for _, nodes in tree.instance_nodes():
            for node in nodes:
                self._nodes[node.uid] = node
                self._offsets[node.uid] = len(self._codes) + 2
                self._codes += struct.pack("<HB", node.uid, node.status)
        self._lock = threading.Condition(threading.RLock())
        self._hooks: dict[tuple[Position, int], Hook] = {}
        self._installed: dict[tuple[Position, int], Hook] = {}
        self._hooks_changed = False
        self._reached: collections.deque[int] = collections.deque()
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
        if self._hooks_changed:
            self._install_hooks()

    def after_tick(self, tree: Tree) -> None:
        self._latest = self._snapshot(with_blackboards=self.watched)

    def _snapshot(self, with_blackboards: bool) -> Snapshot:
        blackboards = (
            {name: board.snapshot() for name, board in self._blackboards.items()}
            if with_blackboards
            else None
        )
        return Snapshot(self.tree.now, bytes(self._codes), blackboards)

    def _install_hooks(self) -> None:
        """Give the nodes the hooks the clients asked for (only in the tick thread)."""
        with self._lock:
            wanted = dict(self._hooks)
            self._hooks_changed = False
        for key in self._installed.keys() | wanted.keys():
            hook = wanted.get(key)
            if self._installed.get(key) is hook:
                continue
            position, uid = key
            node = self._nodes[uid]
            if position is Position.PRE:
                node.set_pre_tick(None if hook is None else partial(self._run_hook, hook))
            else:
                node.set_post_tick(None if hook is None else partial(self._run_hook, hook))
        self._installed = wanted

    def _run_hook(self, hook: Hook, node: TreeNode, status: Status | None = None) -> Status:
        """The hook's part of a tick: notify, wait at a breakpoint, return its status."""
        with self._lock:
            if not hook.enabled:
                return SKIPPED
        self._reached.append(hook.uid)
        if hook.mode is Mode.BREAKPOINT:
            self._pause_at(hook)
        with self._lock:
            if not hook.enabled or self._closing:
                return SKIPPED
            if hook.once:
                hook.enabled = False
                self._forget(hook)
            return hook.desired_status

    def _pause_at(self, hook: Hook) -> None:
        """Block the tick (and so the simulation) until the breakpoint is unlocked,
        disabled or the server closes; hook changes made meanwhile take effect now."""
        self.paused = True
        self._latest = self._snapshot(with_blackboards=True)
        with self._lock:
            while not (hook.ready or not hook.enabled or self._closing):
                self._lock.wait(POLL_MS / 1000)
                if self._hooks_changed:
                    self._install_hooks()
            hook.ready = False

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
            reply = _error(f"{type(error).__name__}: {error}")
        with contextlib.suppress(zmq.ZMQError):  # REP drops replies to vanished clients
            self._server.send_multipart(reply, zmq.NOBLOCK)

    def _reply(self, frames: list[bytes]) -> list[bytes]:
        if len(frames[0]) != HEADER.size:
            return _error("wrong request header")
        _, kind, request_id = HEADER.unpack(frames[0])
        handler = self._handlers.get(chr(kind))
        if handler is None:
            return _error("Request not recognized")
        try:
            payload = handler(self, frames)
        except Refused as refusal:
            return _error(str(refusal))
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
            name: {key: _plain(value) for key, value in boards[name].items()} or None
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
        received = _json_frame(frames)
        with self._lock:
            for data in received if isinstance(received, list) else [received]:
                key = (Position(int(data["position"])), int(data["uid"]))
                if key[1] not in self._nodes:
                    continue  # as BT.CPP: unknown nodes are ignored
                hook = self._hooks.get(key)
                if hook is None:
                    self._hooks[key] = Hook.from_json(data)
                    continue
                was_breakpoint = hook.mode is Mode.BREAKPOINT
                hook.update(data)
                hook.ready = hook.ready or (was_breakpoint and hook.mode is Mode.REPLACE)
            self._hooks_changed = True
            self._lock.notify_all()
        return []

    def _hook_of(self, data: dict) -> Hook:
        hook = self._hooks.get((Position(int(data["position"])), int(data["uid"])))
        if hook is None:
            raise Refused("Node ID not found")
        return hook

    def _unlock(self, frames) -> list[bytes]:
        data = _json_frame(frames)
        desired = str(data["desired_status"])
        with self._lock:
            hook = self._hook_of(data)
            hook.desired_status = Status[desired] if desired in ("SUCCESS", "FAILURE") else SKIPPED
            hook.once = hook.once or bool(data["remove_when_done"])
            hook.ready = hook.mode is Mode.BREAKPOINT
            self._lock.notify_all()
        return []

    def _remove_hook(self, frames) -> list[bytes]:
        data = _json_frame(frames)
        with self._lock:
            self._forget(self._hook_of(data))
        return []

    def _forget(self, hook: Hook) -> None:
        with self._lock:
            hook.enabled = False
            key = (hook.position, hook.uid)
            if self._hooks.get(key) is hook:
                del self._hooks[key]
            self._hooks_changed = True
            self._lock.notify_all()

    def _remove_all_hooks(self, frames=None) -> list[bytes]:
        with self._lock:
            for hook in list(self._hooks.values()):
                self._forget(hook)
        return []

    def _disable_all_hooks(self, frames=None) -> list[bytes]:
        self._enable_all(False)
        return []

    def _enable_all(self, enabled: bool) -> None:
        with self._lock:
            for hook in self._hooks.values():
                hook.enabled = enabled
            self._lock.notify_all()

    def _dump_hooks(self, frames) -> list[bytes]:
        with self._lock:
            return [json.dumps([hook.to_json() for hook in self._hooks.values()]).encode()]

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
            records += struct.pack("<Q", offset)[:6] + struct.pack("<HB", uid, status)
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
        while self._reached:
            uid = self._reached.popleft()
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
            self._enable_all(alive)

    # lifetime -------------------------------------------------------------------------
    def close(self) -> None:
        """Stop serving, release a paused tick and detach from the tree (call it when
        the tree is not being ticked, e.g. after the simulation)."""
        if self._closing:
            return
        with self._lock:
            self._closing = True
            self._lock.notify_all()
        self._thread.join()
        self._remove_all_hooks()
        self._install_hooks()
        self.tree.remove_observer(self)
        self.tree.remove_monitor(self)
        self._server.close()
        self._publisher.close()
        self._context.destroy(linger=0)

    def __enter__(self) -> Groot2Server:
        return self

    def __exit__(self, *exc) -> None:
        self.close()
