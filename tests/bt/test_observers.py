"""Observers: the .btlog writer checked by an independent reader, JSON lines, counters."""

import json
import struct
import xml.etree.ElementTree as ElementTree

import pytest

from hrc_drake.bt.observers import BtlogWriter, JsonLinesWriter, NodeCounters
from tests.bt.bt_helpers import R, Recorder, S, ticks, tree_of

BODY = (
    '<Sequence><Script code="x := 1"/><SubTree ID="Sub"/><AsyncMock name="A" '
    'duration="2"/></Sequence>'
)
SUB = (
    '<BehaviorTree ID="Sub"><Fallback><AlwaysFailure/><Sleep msec="100"/></Fallback></BehaviorTree>'
)


def read_btlog(data: bytes):
    """Decode FileLogger2 as Groot2 does, from the format description alone."""
    magic = b"BTCPP4-FileLogger2"
    assert data.startswith(magic)
    offset = len(magic)
    (protocol,) = struct.unpack_from("<B", data, offset)
    (xml_length,) = struct.unpack_from("<i", data, offset + 1)
    offset += 5
    xml = data[offset : offset + xml_length].decode()
    offset += xml_length
    (start_us,) = struct.unpack_from("<q", data, offset)
    offset += 8
    records = []
    while offset < len(data):
        time_offset = int.from_bytes(data[offset : offset + 6], "little")
        uid, status = struct.unpack_from("<HB", data, offset + 6)
        records.append((time_offset, uid, status))
        offset += 9
    return protocol, xml, start_us, records


def test_btlog_round_trip_matches_observed_transitions(tmp_path):
    tree = tree_of(BODY, extra=SUB)
    recorder = Recorder()
    writer = BtlogWriter(tmp_path / "run.btlog")
    tree.add_observer(recorder)
    tree.add_observer(writer)
    assert ticks(tree, 5, start=0.0, step=0.05) == [R, R, R, R, S]
    writer.close()
    protocol, xml, start_us, records = read_btlog((tmp_path / "run.btlog").read_bytes())
    assert protocol == 1 and start_us == 0
    expected = [(round(t * 1e6), uid, int(new)) for t, uid, _, _, new in recorder.transitions]
    assert records == expected
    root = ElementTree.fromstring(xml)
    trees = root.findall("BehaviorTree")
    assert [(t.get("ID"), t.get("_fullpath")) for t in trees] == [("Main", ""), ("Sub", "Sub::3")]
    uids = [int(e.get("_uid")) for t in trees for e in t.iter() if e.get("_uid")]
    assert sorted(uids) == [uid for uid, _, _ in tree.nodes()]
    assert trees[0].find(".//SubTree").get("_fullpath") == "Sub::3"
    assert root.find("TreeNodesModel/Action[@ID='AsyncMock']") is not None


def test_json_lines_writer(tmp_path):
    tree = tree_of(BODY, extra=SUB)
    writer = JsonLinesWriter(tmp_path / "run.jsonl")
    tree.add_observer(writer)
    tree.tick(0.5)
    writer.close()
    lines = [json.loads(line) for line in (tmp_path / "run.jsonl").read_text().splitlines()]
    assert lines[0] == {
        "t": 0.5,
        "uid": 1,
        "path": "Sequence::1",
        "node": "Sequence",
        "from": "IDLE",
        "to": "RUNNING",
    }
    assert {"Script", "AlwaysFailure", "Sleep"} <= {line["node"] for line in lines}


def test_node_counters_count_ticks_results_and_running_time():
    tree = tree_of(
        '<ReactiveSequence><MockCondition name="C"/><AsyncMock name="A" '
        'duration="3"/></ReactiveSequence>'
    )
    counters = NodeCounters()
    tree.add_observer(counters)
    ticks(tree, 4, start=1.0, step=0.5)
    condition, action = counters.count(tree.node("C")), counters.count(tree.node("A"))
    assert (condition.ticks, condition.successes, condition.failures) == (4, 4, 0)
    assert (action.ticks, action.successes) == (4, 1)
    assert action.time_running == pytest.approx(1.5)
    assert action.last_status is S
    assert set(counters.counts()) == {1, 2, 3}
