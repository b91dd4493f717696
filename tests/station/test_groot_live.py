"""Groot2 clients see a running simulation live, as they see BehaviorTree.CPP itself.

- The same tree served by BT.CPP's own Groot2Publisher (behaviortreepy) and by ours answers
  the full tree, status and blackboard requests with replies of the same structure, the
  same node order and, tick after tick, the same statuses.
- `hrc-drake run --groot` serves both trees of a scenario; the terminal client btview shows
  the tree, streams its transitions and reads its blackboard, and the run directory is the
  same, byte for byte, as without a client.
- A breakpoint holds the whole simulation until it is unlocked.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import threading
import time
import xml.etree.ElementTree as ElementTree
from pathlib import Path

import behaviortreepy as btcpp
import msgpack
import pytest
import zmq
from pydrake.systems.analysis import Simulator

from hrc_drake.bt import StatefulActionNode, Status, default_registry, load_tree
from hrc_drake.bt.groot2 import Groot2Server
from hrc_drake.builder import build_diagram
from hrc_drake.groot import serve_groot
from hrc_drake.scenario import load_scenario
from tests.groot_client import GrootClient, first_free_port

ROOT = Path(__file__).resolve().parents[2]
BTVIEW = [sys.executable, "-m", "btview"]
WORK_TICKS = 2

XML = """
<root BTCPP_format="4" main_tree_to_execute="Main">
  <BehaviorTree ID="Main">
    <Sequence name="top">
      <Script code="count := 0; label := 'go'; ratio := 0.5"/>
      <SubTree ID="Step" name="first" amount="{count}"/>
      <Fallback>
        <ScriptCondition code="count &gt; 5"/>
        <SubTree ID="Step" amount="{count}"/>
      </Fallback>
      <SubTree ID="Leaf" _autoremap="true" level="3"/>
    </Sequence>
  </BehaviorTree>
  <BehaviorTree ID="Step">
    <Sequence>
      <Script code="amount += 1; doubled := amount * 2"/>
      <Working/>
    </Sequence>
  </BehaviorTree>
  <BehaviorTree ID="Leaf">
    <Inverter><ScriptCondition code="level &lt; count"/></Inverter>
  </BehaviorTree>
</root>"""


class Working(StatefulActionNode):
    """RUNNING for WORK_TICKS ticks, then SUCCESS."""

    def on_start(self):
        self.left = WORK_TICKS
        return Status.RUNNING

    def on_running(self):
        self.left -= 1
        return Status.RUNNING if self.left else Status.SUCCESS


def btcpp_tree():
    """The same tree in BehaviorTree.CPP, with the same Working action."""
    left: dict[int, int] = {}

    def start(node):
        left[node.uid()] = WORK_TICKS
        return btcpp.NodeStatus.RUNNING

    def running(node):
        left[node.uid()] -= 1
        return btcpp.NodeStatus.RUNNING if left[node.uid()] else btcpp.NodeStatus.SUCCESS

    factory = btcpp.BehaviorTreeFactory()
    factory.register_simple_stateful_action("Working", start, running)
    factory.register_behavior_tree_from_text(XML)
    return factory.create_tree("Main")


def our_tree():
    registry = default_registry()
    registry.register(Working)
    return load_tree(XML, registry)


def tree_layout(xml: bytes) -> list:
    """Each BehaviorTree element: its ID, path and nodes (tag, uid, attribute names)."""
    return [
        (
            tree.get("ID"),
            tree.get("_fullpath"),
            [(e.tag, e.get("_uid"), sorted(e.attrib)) for e in tree.iter() if e.get("_uid")],
        )
        for tree in ElementTree.fromstring(xml).findall("BehaviorTree")
    ]


def as_numbers(boards: dict) -> dict:
    """Blackboards with numbers and numeric text alike as floats: BT.CPP 4.8 (behaviortreepy)
    keeps a SubTree's literal port as text, 4.9.1 and we as a number (bt-conformance.md)."""

    def number(value):
        try:
            return float(value)
        except (TypeError, ValueError):
            return value

    return {
        name: {key: number(value) for key, value in (board or {}).items()}
        for name, board in boards.items()
    }


def test_btcpp_and_we_answer_tree_status_and_blackboard_alike(free_ports, groot):
    theirs, ours = btcpp_tree(), our_tree()
    their_port, our_port = free_ports(), free_ports()
    publisher = btcpp.Groot2Publisher(theirs, their_port)
    with Groot2Server(ours, our_port):
        them, us = groot(their_port), groot(our_port)
        their_tree, our_tree_reply = them.request("T"), us.request("T")
        assert len(their_tree) == len(our_tree_reply) == 2
        layout = tree_layout(their_tree[1])
        assert tree_layout(our_tree_reply[1]) == layout
        names = ";".join(path or tree_id for tree_id, path, _ in layout).encode()
        for tick in range(8):
            assert them.request("S")[1] == us.request("S")[1], f"statuses after {tick} ticks"
            their_boards = msgpack.unpackb(them.request("B", names)[1])
            assert as_numbers(their_boards) == as_numbers(
                msgpack.unpackb(us.request("B", names)[1])
            )
            assert str(theirs.tick_exactly_once()).endswith(ours.tick(0.1 * tick).name)
    del publisher


RUN_SECONDS = 6.0  # simulated; paced at 0.5 the watched run lasts 12 s of wall time
ECHO_SECONDS = 5.0  # the robot's nodes change at least every 1.1 s simulated (2.2 s paced)


def hrc_drake_run(out: Path, *options) -> subprocess.Popen:
    command = [sys.executable, "-m", "hrc_drake.cli", "run", "getting_started"]
    return subprocess.Popen(
        [*command, "--duration", str(RUN_SECONDS), "--out", str(out), *map(str, options)],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        cwd=ROOT,
        env={**os.environ, "PYTHONUNBUFFERED": "1"},
    )


def btview(*args) -> subprocess.CompletedProcess:
    return subprocess.run([*BTVIEW, *map(str, args)], capture_output=True, text=True, timeout=60)


@pytest.fixture(scope="module")
def watched_run(tmp_path_factory):
    """A `--groot` run watched by btview (snapshot, echo, blackboard) and by a client
    polling status and blackboards, and the same run unwatched."""
    base = tmp_path_factory.mktemp("groot")
    port = first_free_port(4)
    process = hrc_drake_run(base / "watched", "--groot", port, "--realtime", "0.5")
    announced = [process.stdout.readline() for _ in range(2)]
    assert all(line.startswith("Groot2:") for line in announced), process.stderr.read()
    outputs = {}
    commands = {
        "snapshot": ("snapshot", "--port", port, "--no-color"),
        "echo": ("echo", "--json", "--port", port, "--duration", ECHO_SECONDS),
        "blackboard": ("blackboard", "--json", "--port", port, "Robot"),
    }
    threads = [
        threading.Thread(target=lambda n=name, c=command: outputs.__setitem__(n, btview(*c)))
        for name, command in commands.items()
    ]
    for thread in threads:
        thread.start()
    poller = GrootClient(port + 2)
    polled = [poller.request("B", b"Human") for _ in range(20)]
    poller.close()
    for thread in threads:
        thread.join()
    rest, errors = process.communicate(timeout=120)
    assert process.returncode == 0, errors
    plain = hrc_drake_run(base / "plain")
    plain.communicate(timeout=120)
    assert plain.returncode == 0
    return base, announced, outputs, polled, port


def test_run_tells_which_tree_is_on_which_port(watched_run):
    _, announced, _, _, port = watched_run
    assert f"robot tree 'Robot' on 127.0.0.1:{port} " in announced[0]
    assert f"human tree 'Human' on 127.0.0.1:{port + 2} " in announced[1]


def test_btview_shows_the_robot_tree_streams_transitions_and_reads_the_blackboard(watched_run):
    _, _, outputs, polled, _ = watched_run
    snapshot = outputs["snapshot"]
    assert snapshot.returncode == 0, snapshot.stderr
    assert "RobotMove" in snapshot.stdout and "RUNNING" in snapshot.stdout
    echoed = [json.loads(line) for line in outputs["echo"].stdout.splitlines()]
    assert echoed and {"uid", "node", "from", "to"} <= set(echoed[0])
    assert any(record["to"] == "SUCCESS" for record in echoed)
    blackboard = json.loads(outputs["blackboard"].stdout)
    assert blackboard["Robot"]["robot_speed"] == 1.0
    assert all(msgpack.unpackb(reply[1]).keys() == {"Human"} for reply in polled)


def test_a_watched_run_writes_the_same_files_as_an_unwatched_one(watched_run):
    base = watched_run[0]
    for name in ("report.json", "bt_robot.btlog", "bt_human.btlog", "bt_robot.jsonl"):
        assert (base / "watched" / name).read_bytes() == (base / "plain" / name).read_bytes()


def test_a_port_in_use_stops_the_run_before_it_starts(tmp_path, free_ports):
    port = free_ports()
    context = zmq.Context()
    taken = context.socket(zmq.REP)
    taken.bind(f"tcp://127.0.0.1:{port}")
    process = hrc_drake_run(tmp_path / "run", "--groot", port)
    out, errors = process.communicate(timeout=120)
    context.destroy(linger=0)
    assert process.returncode == 2
    assert errors.strip().splitlines() == [
        f"hrc-drake: error: cannot serve Groot2 on 127.0.0.1:{port}: Address already in use"
    ]
    assert not any((tmp_path / "run").iterdir()), "nothing written"


def test_a_port_out_of_range_is_one_line(tmp_path):
    process = hrc_drake_run(tmp_path / "run", "--groot", 65535)
    out, errors = process.communicate(timeout=120)
    assert process.returncode == 2
    assert errors.strip().splitlines() == [
        "hrc-drake: error: run: argument --groot: port 65535 is out of range (1 to 65534: "
        "it uses two)"
    ]


def test_a_breakpoint_holds_the_simulation_until_unlocked(groot, free_ports):
    diagram = build_diagram(load_scenario("getting_started"))
    simulator = Simulator(diagram)
    with serve_groot(diagram, free_ports(4)) as servers:
        robot = servers.servers["robot"]
        client = groot(robot.port)
        move = robot.tree.node("RobotMove").uid
        client.insert_hook(move, once=True)
        thread = threading.Thread(target=simulator.AdvanceTo, args=(3.0,), daemon=True)
        thread.start()
        assert int(client.notifications.recv_multipart()[1]) == move
        held_at = simulator.get_context().get_time()
        thread.join(1.0)
        assert thread.is_alive() and simulator.get_context().get_time() == held_at
        client.request(
            "U",
            {"uid": move, "position": 0, "desired_status": "SKIPPED", "remove_when_done": True},
        )
        thread.join(120)
        assert not thread.is_alive() and simulator.get_context().get_time() == 3.0


def test_a_paced_run_keeps_its_pace_after_a_breakpoint(groot, free_ports):
    """Drake would run flat out to make up the pause; keep_pace paces on from the unlock."""
    rate, end = 0.25, 0.5
    diagram = build_diagram(load_scenario("getting_started"))
    simulator = Simulator(diagram)
    simulator.set_target_realtime_rate(rate)
    with serve_groot(diagram, free_ports(4)) as servers:
        servers.keep_pace(simulator)
        robot = servers.servers["robot"]
        client = groot(robot.port)
        move = robot.tree.node("RobotMove").uid
        client.insert_hook(move, once=True)
        thread = threading.Thread(target=simulator.AdvanceTo, args=(end,), daemon=True)
        thread.start()
        client.notifications.recv_multipart()
        held_at = simulator.get_context().get_time()
        thread.join(1.5)  # the pause, in wall time
        unlock = {"uid": move, "position": 0, "desired_status": "SKIPPED", "remove_when_done": True}
        client.request("U", unlock)
        start = time.monotonic()
        thread.join(60)
        assert time.monotonic() - start >= 0.9 * (end - held_at) / rate
