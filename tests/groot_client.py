"""A client speaking the Groot2 protocol as Groot2 does, and free ports on this machine
(the Groot2 tests' own tools; `conftest.py` hands them out as fixtures)."""

from __future__ import annotations

import json
import random
import socket
import struct

import zmq

HEADER = struct.Struct("<BBI")


def _free(port: int) -> bool:
    with socket.socket() as probe:
        try:
            probe.bind(("127.0.0.1", port))
        except OSError:
            return False
    return True


def first_free_port(count: int = 2) -> int:
    """The first of ``count`` consecutive free local ports."""
    for _ in range(200):
        first = random.randrange(20000, 60000, 2)
        if all(_free(port) for port in range(first, first + count)):
            return first
    raise RuntimeError("no free ports")


class GrootClient:
    """Requests over a REQ socket, breakpoint notifications over a SUB socket."""

    def __init__(self, port: int, host: str = "127.0.0.1", timeout_ms: int = 3000):
        self.context = zmq.Context()
        self.socket = self.context.socket(zmq.REQ)
        self.socket.setsockopt(zmq.RCVTIMEO, timeout_ms)
        self.socket.setsockopt(zmq.LINGER, 0)
        self.socket.connect(f"tcp://{host}:{port}")
        self.notifications = self.context.socket(zmq.SUB)
        self.notifications.setsockopt(zmq.SUBSCRIBE, b"")
        self.notifications.setsockopt(zmq.RCVTIMEO, timeout_ms)
        self.notifications.connect(f"tcp://{host}:{port + 1}")
        self.next_id = 100

    def raw(self, *frames: bytes) -> list[bytes]:
        self.socket.send_multipart(list(frames))
        return self.socket.recv_multipart()

    def request(self, kind: str, *payload) -> list[bytes]:
        """Reply frames; payload items that are not bytes are sent as JSON."""
        self.next_id += 1
        frames = [p if isinstance(p, bytes) else json.dumps(p).encode() for p in payload]
        reply = self.raw(HEADER.pack(2, ord(kind), self.next_id), *frames)
        if reply[0] != b"error":
            assert reply[0][:6] == HEADER.pack(2, ord(kind), self.next_id)
            assert len(reply[0]) == 22
        return reply

    def insert_hook(
        self, uid: int, mode: int = 0, once: bool = False, desired: str = "SKIPPED", position=0
    ) -> list[bytes]:
        """A breakpoint (mode 0) or a replacement (mode 1), as Groot2 sends it."""
        hook = {"uid": uid, "position": position, "mode": mode, "once": once, "enabled": True}
        return self.request("I", {**hook, "desired_status": desired})

    def statuses(self) -> list[tuple[int, int]]:
        buffer = self.request("S")[1]
        return [struct.unpack_from("<HB", buffer, i) for i in range(0, len(buffer), 3)]

    def close(self) -> None:
        self.context.destroy(linger=0)
