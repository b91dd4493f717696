"""Groot2's hooks on one tree: breakpoints (the tick waits until a client unlocks it) and
replacements (the node's tick gives way to a chosen status), before or after a node's tick.

Clients change the table from the server's thread; the changes reach the nodes only at tick
boundaries (``install``, in the tick thread), so no tick sees a hook half-changed. One lock,
a Condition, guards the table; a tick paused at a breakpoint waits on it.
"""

from __future__ import annotations

import collections
import enum
import threading
from collections.abc import Callable
from dataclasses import dataclass
from functools import partial

from .groot2_protocol import Refused
from .node import TreeNode
from .status import SKIPPED, Status


class Position(enum.IntEnum):
    PRE = 0
    POST = 1


class Mode(enum.IntEnum):
    BREAKPOINT = 0
    REPLACE = 1


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


class HookTable:
    """The hooks clients asked for, by (position, node uid), and those the nodes have.

    ``on_pause`` is called in the tick thread when a breakpoint is reached, before it waits;
    ``reached`` collects the uids of the hooks reached, for the server to announce.
    """

    def __init__(
        self, nodes: dict[int, TreeNode], on_pause: Callable[[], None], poll_seconds: float
    ):
        self._nodes = nodes
        self._on_pause = on_pause
        self._poll_seconds = poll_seconds
        self._lock = threading.Condition(threading.RLock())
        self._hooks: dict[tuple[Position, int], Hook] = {}
        self._installed: dict[tuple[Position, int], Hook] = {}
        self.changed = False
        self.reached: collections.deque[int] = collections.deque()
        self._released = False

    # the tick thread ------------------------------------------------------------------
    def install(self) -> None:
        """Give the nodes the hooks the clients asked for (only in the tick thread)."""
        with self._lock:
            wanted = dict(self._hooks)
            self.changed = False
        for key in self._installed.keys() | wanted.keys():
            hook = wanted.get(key)
            if self._installed.get(key) is hook:
                continue
            position, uid = key
            node = self._nodes[uid]
            if position is Position.PRE:
                node.set_pre_tick(None if hook is None else partial(self._run, hook))
            else:
                node.set_post_tick(None if hook is None else partial(self._run, hook))
        self._installed = wanted

    def _run(self, hook: Hook, node: TreeNode, status: Status | None = None) -> Status:
        """The hook's part of a tick: notify, wait at a breakpoint, return its status."""
        with self._lock:
            if not hook.enabled:
                return SKIPPED
        self.reached.append(hook.uid)
        if hook.mode is Mode.BREAKPOINT:
            self._pause_at(hook)
        with self._lock:
            if not hook.enabled or self._released:
                return SKIPPED
            if hook.once:
                hook.enabled = False
                self.forget(hook)
            return hook.desired_status

    def _pause_at(self, hook: Hook) -> None:
        """Block the tick (and so the simulation) until the breakpoint is unlocked,
        disabled or released; hook changes made meanwhile take effect now."""
        self._on_pause()
        with self._lock:
            while not (hook.ready or not hook.enabled or self._released):
                self._lock.wait(self._poll_seconds)
                if self.changed:
                    self.install()
            hook.ready = False

    # the clients' requests ------------------------------------------------------------
    def insert(self, received: dict | list[dict]) -> None:
        """Add or change hooks (Groot2's JSON, one or a list)."""
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
            self.changed = True
            self._lock.notify_all()

    def _hook_of(self, data: dict) -> Hook:
        hook = self._hooks.get((Position(int(data["position"])), int(data["uid"])))
        if hook is None:
            raise Refused("Node ID not found")
        return hook

    def unlock(self, data: dict) -> None:
        """Let a paused breakpoint go on, with the status the client chose."""
        desired = str(data["desired_status"])
        with self._lock:
            hook = self._hook_of(data)
            hook.desired_status = Status[desired] if desired in ("SUCCESS", "FAILURE") else SKIPPED
            hook.once = hook.once or bool(data["remove_when_done"])
            hook.ready = hook.mode is Mode.BREAKPOINT
            self._lock.notify_all()

    def remove(self, data: dict) -> None:
        with self._lock:
            self.forget(self._hook_of(data))

    def forget(self, hook: Hook) -> None:
        with self._lock:
            hook.enabled = False
            key = (hook.position, hook.uid)
            if self._hooks.get(key) is hook:
                del self._hooks[key]
            self.changed = True
            self._lock.notify_all()

    def remove_all(self) -> None:
        with self._lock:
            for hook in list(self._hooks.values()):
                self.forget(hook)

    def enable_all(self, enabled: bool) -> None:
        with self._lock:
            for hook in self._hooks.values():
                hook.enabled = enabled
            self._lock.notify_all()

    def to_json(self) -> list[dict]:
        with self._lock:
            return [hook.to_json() for hook in self._hooks.values()]

    def release(self) -> None:
        """Let a paused tick go on and every later hook pass (the server is closing)."""
        with self._lock:
            self._released = True
            self._lock.notify_all()
