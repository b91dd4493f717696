"""The Groot2 server answers as BehaviorTree.CPP's Groot2Publisher does (groot2_publisher.cpp),
from snapshots taken at tick boundaries, and nothing a client does stops or changes the run
except the hooks it asks for."""

from __future__ import annotations

import json
import struct
import threading
import xml.etree.ElementTree as ElementTree

import msgpack
import pytest
import zmq

from hrc_drake.bt import groot2
from hrc_drake.bt.groot2 import Groot2Server, ServeError
from tests.bt.bt_helpers import F, R, Recorder, S, ticks, tree_of

MAIN = """
<Sequence name="top">
  <Script code="count := 0; label := 'start'"/>
  <SubTree ID="Work" name="work" count="{count}"/>
  <AsyncMock name="finish" duration="1"/>
</Sequence>"""
WORK = """
<BehaviorTree ID="Work">
  <Sequence>
    <Script code="count += 1; local := count * 2"/>
    <AsyncMock name="busy" duration="2"/>
  </Sequence>
</BehaviorTree>"""


def work_tree():
    return tree_of(MAIN, extra=WORK)


@pytest.fixture
def served(free_ports, groot):
    """(tree, server, client) on free ports."""
    tree = work_tree()
    with Groot2Server(tree, free_ports()) as server:
        yield tree, server, groot(server.port)


def uid_of(tree, name: str) -> int:
    return tree.node(name).uid


def tick_in_thread(tree, now: float) -> threading.Thread:
    thread = threading.Thread(target=tree.tick, args=(now,), daemon=True)
    thread.start()
    return thread


def test_full_tree_carries_every_node_uid_and_the_palette(served):
    tree, server, client = served
    reply = client.request("T")
    root = ElementTree.fromstring(reply[1])
    uids = [int(e.get("_uid")) for e in root.iter() if e.get("_uid")]
    assert sorted(uids) == sorted(uid for uid, _, _ in tree.nodes())
    assert [e.get("_fullpath") for e in root.findall("BehaviorTree")] == ["", "work"]
    assert root.find("TreeNodesModel/Action[@ID='AsyncMock']") is not None
    assert client.request("S")[0][6:] == reply[0][6:], "one tree UUID for every reply"


def test_status_lists_nodes_subtree_by_subtree_with_idle_from_codes(served):
    tree, server, client = served
    order = [uid for uid, _ in client.statuses()]
    assert order == [node.uid for _, nodes in tree.instance_nodes() for node in nodes]
    assert all(code == 0 for _, code in client.statuses())
    tree.tick(0.05)
    codes = dict(client.statuses())
    assert codes[uid_of(tree, "top")] == R
    assert codes[uid_of(tree, "busy")] == R
    assert codes[uid_of(tree, "finish")] == 0
    ticks(tree, 3, start=0.1)  # busy succeeds, finish runs one tick, top succeeds
    codes = dict(client.statuses())
    assert codes[uid_of(tree, "top")] == 10 + S, "the root was reset after its SUCCESS"
    assert codes[uid_of(tree, "busy")] == 10 + S


def test_blackboards_by_tree_id_or_subtree_path(served):
    tree, server, client = served
    tree.tick(0.05)
    reply = client.request("B", b"Main;work;nowhere")
    assert msgpack.unpackb(reply[1]) == {
        "Main": {"count": 1, "label": "start"},
        "work": {"local": 2},
    }
    assert msgpack.unpackb(client.request("B", b"")[1]) is None
    assert client.request("B") == [b"error", b"must be 2 parts message"]


def test_replace_hooks_force_results_and_are_dumped_removed_and_cleared(served):
    tree, server, client = served
    busy = uid_of(tree, "busy")
    hook = {"uid": busy, "position": 0, "mode": 1, "once": False, "enabled": True}
    client.request("I", {**hook, "desired_status": "FAILURE"})
    assert tree.tick(0.05) is F, "busy replaced by FAILURE before its tick"
    assert tree.node("busy").starts == 0
    assert json.loads(client.request("D")[1]) == [{**hook, "desired_status": "FAILURE"}]
    assert len(client.request("R", {"uid": busy, "position": 0})) == 1, "header only"
    assert client.request("R", {"uid": busy, "position": 0})[0] == b"error", "already removed"
    assert tree.tick(0.1) is R and tree.node("busy").starts == 1
    client.request("I", [{**hook, "position": 1, "desired_status": "SUCCESS"}])
    assert tree.tick(0.15) is R, "post hook: busy's RUNNING replaced by SUCCESS, finish runs"
    assert tree.node("finish").status is R
    client.request("A")
    assert client.request("D")[1] == b"[]"


def test_a_breakpoint_holds_the_tick_until_unlocked(served):
    tree, server, client = served
    busy = uid_of(tree, "busy")
    client.insert_hook(busy, once=True)
    thread = tick_in_thread(tree, 0.05)
    header, uid = client.notifications.recv_multipart()
    assert header[1:2] == b"N" and int(uid) == busy
    assert thread.is_alive(), "the tick waits at the breakpoint"
    codes = dict(client.statuses())
    assert codes[uid_of(tree, "top")] == R and codes[busy] == 0, "a snapshot at the breakpoint"
    assert msgpack.unpackb(client.request("B", b"work")[1]) == {"work": {"local": 2}}
    client.request(
        "U", {"uid": busy, "position": 0, "desired_status": "SUCCESS", "remove_when_done": True}
    )
    thread.join(5)
    assert not thread.is_alive()
    assert tree.node("finish").status is R, "busy reported the SUCCESS given at unlock"
    assert client.request("D")[1] == b"[]", "a once-hook is gone after it fired"


def test_a_silent_client_cannot_hold_the_run(served, monkeypatch):
    tree, server, client = served
    monkeypatch.setattr(groot2, "HEARTBEAT", 0.3)
    busy = uid_of(tree, "busy")
    client.insert_hook(busy, desired="FAILURE")
    thread = tick_in_thread(tree, 0.05)
    client.notifications.recv_multipart()
    thread.join(5)
    assert not thread.is_alive(), "hooks disabled once the client went silent"
    assert tree.node("busy").status is R, "a disabled breakpoint lets the node tick"


def test_recording_reports_transitions_in_simulation_time(served):
    tree, server, client = served
    tree.tick(1.0)
    start = client.request("r", b"start")[1]
    assert start == b"1000000"
    ticks(tree, 2, start=1.25, step=0.25)  # busy succeeds at 1.5 s, finish starts
    records = client.request("t")[1]
    decoded = [
        (int.from_bytes(records[i : i + 6], "little"), *struct.unpack_from("<HB", records, i + 6))
        for i in range(0, len(records), 9)
    ]
    assert (500_000, uid_of(tree, "busy"), S) in decoded
    assert (500_000, uid_of(tree, "finish"), R) in decoded
    assert {offset for offset, _, _ in decoded} == {500_000}, "nothing changed at 1.25 s"
    assert client.request("t")[1] == b"", "transitions are handed out once"
    client.request("r", b"stop")
    tree.tick(1.5)
    assert client.request("t")[1] == b""


@pytest.mark.parametrize(
    "frames, error",
    [
        ([b"abc"], b"wrong request header"),
        ([b"\x02Zabcd"], b"Request not recognized"),
        ([struct.pack("<BBI", 2, ord("I"), 1), b"{not json"], None),
        ([struct.pack("<BBI", 2, ord("I"), 1), b'{"uid": 1}'], None),
        (
            [
                struct.pack("<BBI", 2, ord("U"), 1),
                b'{"uid": 999, "position": 0, '
                b'"desired_status": "SUCCESS", "remove_when_done": false}',
            ],
            b"Node ID not found",
        ),
        ([struct.pack("<BBI", 2, ord("B"), 1), b"\xff\xfe"], None),
        ([struct.pack("<BBI", 2, ord("r"), 1)], b"must be 2 parts message"),
    ],
)
def test_bad_requests_get_an_error_reply_and_the_server_stays_up(served, frames, error):
    tree, server, client = served
    reply = client.raw(*frames)
    assert reply[0] == b"error" and (error is None or reply[1] == error)
    assert client.request("S")[0] != b"error"


def test_garbage_oversized_and_vanished_clients_change_nothing(served, free_ports):
    tree, server, client = served
    reference = work_tree()
    expected, seen = Recorder(), Recorder()
    reference.add_observer(expected)
    tree.add_observer(seen)
    context = zmq.Context()
    stop = threading.Event()

    def misbehave():
        while not stop.is_set():
            rogue = context.socket(zmq.DEALER)
            rogue.setsockopt(zmq.LINGER, 0)
            rogue.connect(f"tcp://127.0.0.1:{server.port}")
            rogue.send_multipart([b"", b"x" * (groot2.MAX_MESSAGE + 10)])  # oversized
            rogue.send_multipart([b"", b"\x02S"])  # truncated header
            rogue.send(b"no delimiter")
            vanishing = context.socket(zmq.REQ)
            vanishing.setsockopt(zmq.LINGER, 0)
            vanishing.connect(f"tcp://127.0.0.1:{server.port}")
            vanishing.send_multipart([struct.pack("<BBI", 2, ord("T"), 7)])
            vanishing.close()  # gone before the reply
            rogue.close()

    thread = threading.Thread(target=misbehave, daemon=True)
    thread.start()
    results = [ticks(t, 40, step=0.05) for t in (reference, tree)]
    stop.set()
    thread.join(5)
    context.destroy(linger=0)
    assert results[0] == results[1]
    assert expected.transitions == seen.transitions
    assert client.request("S")[0] != b"error", "still serving"


def test_ports_in_use_or_out_of_range_fail_in_one_line(served):
    tree, server, client = served
    with pytest.raises(ServeError, match=r"127\.0\.0\.1:\d+: Address already in use$"):
        Groot2Server(work_tree(), server.port)
    with pytest.raises(ServeError, match="out of range"):
        Groot2Server(work_tree(), 65535)


def test_closing_detaches_and_releases_the_ports(free_ports):
    tree = work_tree()
    port = free_ports()
    server = Groot2Server(tree, port)
    server.close()
    assert not tree.observers and not tree.monitors
    Groot2Server(tree, port).close()
