"""Bad behavior trees: `hrc-drake validate` names the tree file, the line, the node and the
port in one line (a blackboard entry no one ever sets too); a fault only the run can find
(weights a script made that do not fit) ends the run cleanly with that line, keeping what
the run wrote."""

import json
from pathlib import Path

import pytest

from hrc_drake.agent_trees import tree_errors
from hrc_drake.evaluation.metrics import WHY_NODES_FAIL
from hrc_drake.scenario import load_scenario
from tests.corpus.corpus_helpers import (
    GOOD_TREE,
    Case,
    assert_one_line_error,
    expected_place,
    write_workspace,
)

XML_BOMB = (
    '<?xml version="1.0"?>\n<!DOCTYPE root [\n<!ENTITY lol0 "lol">\n'
    + "".join(f'<!ENTITY lol{i} "{f"&lol{i - 1};" * 10}">\n' for i in range(1, 10))
    + ']>\n<root BTCPP_format="4"><BehaviorTree ID="Robot">\n'
    + '<Emit event="&lol9;"/></BehaviorTree></root>\n'
)
"""XML's "billion laughs": entities of ten entities each, 10**9 times "lol" expanded."""

T = "robot.xml"
S = "scenario.yaml"
MOVE = '<RobotMove target="{above}"/>'
CASES = {
    "unknown node": Case(
        T,
        MOVE,
        '<RobotMvoe target="{above}"/>',
        ("unknown node type 'RobotMvoe' (did you mean 'RobotMove'?)",),
        "RobotMvoe",
    ),
    "unknown port": Case(
        T,
        MOVE,
        '<RobotMove traget="{above}"/>',
        ("port 'traget' is not declared by 'RobotMove' (did you mean 'target'?)",),
        "traget",
    ),
    "missing port": Case(
        T, MOVE, "<RobotMove/>", ("port 'target': missing required port",), "<RobotMove/>"
    ),
    "unknown location": Case(
        T,
        MOVE,
        '<RobotMove target="pick_spto"/>',
        ("port 'target': unknown location 'pick_spto'",),
        "pick_spto",
    ),
    "unknown area": Case(
        T,
        MOVE,
        f'{MOVE}<InAreaTest pose="{{above}}" area="tabel"/>',
        ("port 'area': unknown area 'tabel'",),
        "tabel",
    ),
    "port value of the wrong type": Case(
        T, 'velocity="{speed}"', 'velocity="fast"', ("port 'velocity'", "fast"), "fast"
    ),
    "output port given a literal": Case(
        T,
        'output="{above}"',
        'output="above"',
        ("port 'output': output port needs a blackboard entry",),
        'output="above"',
    ),
    "wrong number of children": Case(
        T,
        MOVE,
        f"<Inverter>{MOVE}<AlwaysSuccess/></Inverter>",
        ("'Inverter' needs exactly 1 children, has 2",),
        "<Inverter>",
    ),
    "weights that do not fit": Case(
        T,
        MOVE,
        f'<WeightedRandom weights="6;2;3">{MOVE}<AlwaysSuccess/></WeightedRandom>',
        ("port 'weights': needs 2 weights, one per child, got 3: 6;2;3",),
        "WeightedRandom",
    ),
    "Parallel needing more successes than it has children": Case(
        T,
        MOVE,
        f'<Parallel success_count="3">{MOVE}<AlwaysSuccess/></Parallel>',
        ("port 'success_count': 2 children are fewer than 3: it can never succeed",),
        "Parallel",
    ),
    "weight out of range": Case(
        T,
        MOVE,
        f'<WeightedRandom weights="1;-1">{MOVE}<AlwaysSuccess/></WeightedRandom>',
        ("port 'weights': must be at least 0, got 1;-1",),
        "WeightedRandom",
    ),
    "weights all zero": Case(
        T,
        MOVE,
        f'<WeightedRandom weights="0;0">{MOVE}<AlwaysSuccess/></WeightedRandom>',
        ("port 'weights': needs a weight above 0, got 0;0",),
        "WeightedRandom",
    ),
    "velocity out of range": Case(
        T,
        'velocity="{speed}"',
        'velocity="100"',
        ("port 'velocity': must be within 0..1, got 100 (a percentage? 1 is the fraction)",),
        'velocity="100"',
    ),
    "an object numbered from 0": Case(  # a user's pick of object "0" failed 123 times
        T,
        MOVE,
        f'{MOVE}<DespawnObject object_id="0"/>',
        (
            "port 'object_id': must be at least 1, got 0 (objects are numbered from 1: the "
            "scenario's in their order)",
        ),
        "DespawnObject",
    ),
    "a SubTree literal out of the range of the port it reaches": Case(
        T,
        '<SubTree ID="Reach" at="pick_spot"/>\n    </Sequence>\n  </BehaviorTree>\n'
        '  <BehaviorTree ID="Reach">\n    <Sequence>',
        '<SubTree ID="Reach" at="pick_spot" slow="-1"/>\n    </Sequence>\n  </BehaviorTree>\n'
        '  <BehaviorTree ID="Reach">\n    <Sequence><SetRobotVelocity velocity="{slow}"/>',
        (
            "tree 'Robot', node 'Reach::",
            "port 'slow': must be within 0..1, got -1: SetRobotVelocity 'Reach::",
            "reads it as velocity",
        ),
        'slow="-1"',
    ),
    "blackboard key typo": Case(
        T,
        'velocity="{speed}"',
        'velocity="{sped}"',
        (
            "port 'velocity': blackboard entry 'sped' is never set: no scenario parameter, "
            "location or area, SubTree port, node output, SetBlackboard or script writes it "
            "(did you mean 'speed'?)",
        ),
        "sped",
    ),
    "SubTree port name typo": Case(
        T,
        '<SubTree ID="Reach" at="pick_spot"/>\n',
        '<SubTree ID="Reach" att="pick_spot"/>\n',
        (
            "tree 'Reach', node 'Reach::",
            "/OffsetPose::",
            "port 'input': blackboard entry 'at' is never set",
            "(did you mean 'att'?)",
        ),
        'input="{at}"',
    ),
    "a SubTree reads what its caller set": Case(
        T,
        '<SubTree ID="Reach" at="pick_spot"/>\n',
        '<SetBlackboard output_key="at" value="pick_spot"/><SubTree ID="Reach"/>\n',
        (
            "port 'input': blackboard entry 'at' is never set",
            "('at' is set outside this SubTree, whose blackboard is its own: pass it in on "
            'the SubTree (at="{at}") or give the SubTree _autoremap="true")',
        ),
        'input="{at}"',
    ),
    "a SubTree reads a scenario parameter it is not given": Case(
        T,
        MOVE,
        f'<SetRobotVelocity velocity="{{speed}}"/>{MOVE}',
        (
            "tree 'Reach', node 'Reach::",
            "port 'velocity': blackboard entry 'speed' is never set: the scenario parameter "
            "'speed' is on the root blackboard, which this SubTree does not see (its "
            'blackboard is its own): remap it on the SubTree (speed="{speed}") or give the '
            'SubTree _autoremap="true"',
        ),
        '"{speed}"/><RobotMove',
    ),
    "a script counts from a key never set": Case(
        T,
        MOVE,
        f'<Script code="picked := picked + 1"/>{MOVE}',
        ("port 'code': blackboard entry 'picked' is never set",),
        "Script",
    ),
    "a precondition reads a key typo": Case(
        T,
        MOVE,
        '<RobotMove target="{above}" _skipIf="sped > 1"/>',
        ("port '_skipIf': blackboard entry 'sped' is never set", "(did you mean 'speed'?)"),
        "_skipIf",
    ),
    "unknown holder": Case(
        T,
        MOVE,
        f'{MOVE}<HeldObject holder="gripper"/>',
        ("port 'holder': unknown value 'gripper'; known: robot, ",),
        "gripper",
    ),
    "bad script": Case(T, MOVE, f'<Script code="x := ("/>{MOVE}', ("port 'code'",), "Script"),
    "bad precondition": Case(
        T, MOVE, '<RobotMove target="{above}" _skipIf="(("/>', ("port '_skipIf'",), "_skipIf"
    ),
    "entry of two types": Case(
        T,
        '<SetRobotVelocity velocity="{speed}"/>',
        '<SetRobotVelocity velocity="{speed}"/>'
        '<OffsetPose input="door" offset="0;0;0" output="{speed}"/>',
        ("blackboard entry 'speed' has type",),
        'output="{speed}"',
    ),
    "malformed XML": Case(
        T,
        '    </Sequence>\n  </BehaviorTree>\n  <BehaviorTree ID="Reach">',
        '  </BehaviorTree>\n  <BehaviorTree ID="Reach">',
        ("malformed XML: mismatched tag",),
        None,
    ),
    "not a root element": Case(
        T,
        GOOD_TREE,
        GOOD_TREE.replace("root", "tree"),
        ("the top element must be <root>, not <tree>",),
        "<tree",
    ),
    "main tree missing": Case(
        T,
        'main_tree_to_execute="Robot"',
        'main_tree_to_execute="Robto"',
        ("no BehaviorTree with ID 'Robto'", "did you mean 'Robot'?"),
        "main_tree_to_execute",
    ),
    "main tree not named": Case(
        T,
        ' main_tree_to_execute="Robot"',
        "",
        ("several BehaviorTrees and no main_tree_to_execute: choose one of Robot, Reach",),
        "<root",
    ),
    "scenario names a missing tree": Case(
        S,
        "{file: robot.xml,",
        "{file: robot.xml, tree_id: Robto,",
        ("tree 'Robto': no BehaviorTree with ID 'Robto'",),
        None,
    ),
    "unknown SubTree": Case(
        T,
        '<SubTree ID="Reach" at="pick_spot"/>\n    </Sequence>',
        '<SubTree ID="Raech" at="pick_spot"/>\n    </Sequence>',
        ("unknown SubTree ID 'Raech' (did you mean 'Reach'?)",),
        "Raech",
    ),
    "SubTree cycle": Case(
        T,
        MOVE,
        f'{MOVE}<SubTree ID="Reach" at="{{at}}"/>',
        ("SubTree cycle: Robot -> Reach -> Reach",),
        'at="{at}"/>',
    ),
    "tree defined twice": Case(
        T,
        '<BehaviorTree ID="Reach">',
        '<BehaviorTree ID="Robot" _description="again">',
        ("BehaviorTree 'Robot' is already defined",),
        "again",
    ),
    "tree without ID": Case(
        T,
        '<BehaviorTree ID="Reach">',
        "<BehaviorTree>",
        ("<BehaviorTree> without an ID",),
        "<BehaviorTree>",
    ),
    "tree with two roots": Case(
        T,
        "    </Sequence>\n  </BehaviorTree>\n</root>",
        "    </Sequence>\n    <AlwaysSuccess/>\n  </BehaviorTree>\n</root>",
        ("a BehaviorTree must have exactly one root node, has 2",),
        '<BehaviorTree ID="Reach">',
    ),
    "missing include": Case(
        T,
        '  <BehaviorTree ID="Robot">',
        '  <include path="lib.xml"/>\n  <BehaviorTree ID="Robot">',
        ("included file 'lib.xml' not found",),
        "include",
    ),
    "bad SubTree remap flag": Case(
        T,
        '<SubTree ID="Reach" at="pick_spot"/>\n    </Sequence>',
        '<SubTree ID="Reach" at="pick_spot" _autoremap="maybe"/>\n    </Sequence>',
        ("port '_autoremap'",),
        "maybe",
    ),
    "empty tree file": Case(T, GOOD_TREE, "", ("malformed XML",), None),
    "entity bomb": Case(
        T,
        GOOD_TREE,
        XML_BOMB,
        ("malformed XML: limit on input amplification factor (from DTD and entities) breached",),
        "&lol9;",
    ),
    "binary tree file": Case(
        S,
        "{file: robot.xml,",
        "{file: tree.bin,",
        ("the tree file is not UTF-8 text",),
        None,
        {"tree.bin": b"\xff\xfe<\x00r\x00"},
    ),
}


@pytest.mark.parametrize("name", CASES)
def test_bad_tree_is_one_located_line(name, tmp_path, hrc_drake):
    case = CASES[name]
    scenario = write_workspace(tmp_path, case)
    status, _, err = hrc_drake("validate", scenario)
    where = expected_place(tmp_path, case) if case.at else str(tmp_path / "")
    line = assert_one_line_error(status, err, where, *case.says)
    assert "<unknown>" not in line


@pytest.mark.parametrize("command", ["validate", "run"])
def test_a_node_commanding_an_actor_its_agent_may_not_is_one_located_line(
    command, tmp_path, hrc_drake
):
    """The robot's tree given to the person: its SetRobotVelocity (line 4) and RobotMove
    would command the robot, which only the robot's tree does; nothing would carry their
    commands out, so the tree is refused before any simulation."""
    robot_tree_to_the_person = Case(
        S, "  robot: {file: robot.xml,", "  human: {file: robot.xml,", ()
    )
    scenario = write_workspace(tmp_path, robot_tree_to_the_person)
    status, _, err = hrc_drake(
        command, scenario, *(["--out", tmp_path / "run"] * (command == "run"))
    )
    assert_one_line_error(
        status,
        err,
        f"{tmp_path / 'robot.xml'}:4:",
        "SetRobotVelocity",
        "the human's tree may not command the robot (it commands: human, workpieces)",
    )
    assert not (tmp_path / "run").exists()


@pytest.mark.parametrize("name", ["unknown node", "unknown port", "missing port"])
def test_a_mistake_in_a_shared_subtree_is_reported_once(name, tmp_path):
    """Reach is used twice; each of its mistakes is one message, not one per instance."""
    scenario = load_scenario(write_workspace(tmp_path))
    write_workspace(tmp_path, CASES[name])  # the loaded scenario now names a bad tree
    trees = tree_errors(scenario.trees, scenario.places(), scenario.parameters)
    errors = [str(error) for error in trees]
    problems = [error.split(": ", 2)[-1] for error in errors]
    assert errors and len(set(problems)) == len(problems), errors
    assert all(error.startswith(f"{tmp_path / 'robot.xml'}:12:") for error in errors)


RUN_FAULTS = {
    "blackboard key typo": (
        'velocity="{speed}"',
        'velocity="{sped}"',
        "port 'velocity'",
        "blackboard entry 'sped' is not set",
    ),
    "weights a script made that do not fit": (
        MOVE,
        f"<Script code=\"w := '1;2;3'\"/>"
        f'<WeightedRandom weights="{{w}}">{MOVE}<AlwaysSuccess/></WeightedRandom>',
        "port 'weights'",
        "needs 2 weights, one per child, got 3: 1;2;3",
    ),
    "a velocity a script made out of range": (
        '<SetRobotVelocity velocity="{speed}"/>',
        '<Script code="v := 50"/><SetRobotVelocity velocity="{v}"/>',
        "port 'velocity'",
        "must be within 0..1, got 50",
    ),
}


@pytest.mark.parametrize("name", RUN_FAULTS)
def test_a_tree_fault_during_a_run_ends_it_cleanly(name, tmp_path, hrc_drake):
    old, new, port, problem = RUN_FAULTS[name]
    scenario = write_workspace(tmp_path, Case(T, old, new, ()))
    out = tmp_path / "run"
    status, stdout, err = hrc_drake("run", scenario, "--out", out)
    line = assert_one_line_error(status, err, f"{tmp_path / 'robot.xml'}:", port, problem)
    assert f"the run stopped at 0.00 s; what it recorded is in {out}" in line
    report = json.loads((out / "report.json").read_text())
    assert report["stopped"]["error"] in line
    for kept in ("bt_robot.btlog", "bt_robot.jsonl", "diagram.svg", "report.html"):
        assert (out / kept).is_file(), kept


def test_node_failures_come_first_in_the_run_summary(tmp_path, hrc_drake):
    """The robot grips where there is nothing to grip: the run succeeds, and the first thing
    it prints says which node failed, how often and why, before any figure."""
    gripper = Case(
        "robot.xml",
        '<SetRobotVelocity velocity="{speed}"/>',
        '<SetRobotVelocity velocity="{speed}"/><RobotGrip name="grip_nothing"/>',
        (),
    )
    scenario = write_workspace(tmp_path, gripper)
    text = scenario.read_text().replace(
        "  configurations_deg:", "  tool: vacuum_gripper\n  configurations_deg:"
    )
    scenario.write_text(text)
    status, stdout, err = hrc_drake("run", scenario, "--out", tmp_path / "run", "--duration", "0.3")
    assert status == 0, err
    first, reason = stdout.splitlines()[:2]
    assert first == f"corpus: 1 tree node failed {WHY_NODES_FAIL}:"
    assert reason.startswith("  robot grip_nothing: failed ")
    assert reason.endswith("first: failed: nothing graspable at the robot's grasp frame")
    assert stdout.splitlines()[2].startswith("corpus: simulated 0.3 s")


TRAY_WITH_PARTS = Path(__file__).parents[1] / "human" / "cells" / "tray_with_parts" / "cell.yaml"


def test_a_tray_with_parts_on_it_is_never_found_and_the_run_says_why(tmp_path, hrc_drake):
    """A user's tray with two parts lying on it, to be carried away: the person's NextObject
    never offers it (the one on top is taken first), and the run said nothing of why."""
    status, stdout, err = hrc_drake("run", TRAY_WITH_PARTS, "--out", tmp_path / "run")
    assert status == 0, err
    first, reason = stdout.splitlines()[:2]
    assert first == f"tray_with_parts: 1 tree node failed {WHY_NODES_FAIL}:"
    assert reason.startswith("  human NextObject::2: failed ")
    assert reason.endswith(
        "first: every object here that the filter takes has another lying on it (object 3 on "
        "object 1): the one on top is taken first"
    )
