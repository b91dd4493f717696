"""BehaviorTree.CPP v4's Groot2 protocol (its groot2_protocol.h): the bytes of requests,
replies and notifications.

A client (Groot2, btview, ...) connects a REQ socket to the server's ``port`` and a SUB socket
to ``port + 1``. A request is a multipart message whose first frame is a 6-byte header
(protocol 2, request type, request id as little-endian uint32); the reply repeats it, adds the
tree's 16-byte UUID, then the payload:

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

A request the server cannot answer gets an error reply: ``error`` and one line.
"""

from __future__ import annotations

import enum
import json
import struct
from typing import Any

from .ports import value_to_text

PROTOCOL = 2
HEADER = struct.Struct("<BBI")
NODE_STATUS = struct.Struct("<HB")
"""One node of an ``S`` reply or of a recorded transition: uid, then the status byte."""
IDLE_FROM = 10
"""Status code of a node gone IDLE: 10 + the status it had."""


class Refused(Exception):
    """A request the server answers with an error reply."""


def plain_value(value: Any) -> Any:
    """A blackboard value as MessagePack can carry it (other types as their text)."""
    if value is None or isinstance(value, bool | int | float | str):
        return value
    if isinstance(value, enum.Enum):
        return value.name
    if isinstance(value, list | tuple):
        return [plain_value(item) for item in value]
    return value_to_text(value)


def json_payload(frames: list[bytes]) -> Any:
    """The JSON second frame of a hook request."""
    if len(frames) != 2:
        raise Refused("must be 2 parts message")
    return json.loads(frames[1].decode())


def error_reply(message: str) -> list[bytes]:
    return [b"error", message.encode()]


def transition_record(offset_us: int, uid: int, status: int) -> bytes:
    """One recorded transition of a ``t`` reply: 6-byte microsecond offset, uid, status."""
    return struct.pack("<Q", offset_us)[:6] + NODE_STATUS.pack(uid, status)
