"""Validation without running: every error names file, line, tree, node and port."""

import pytest

from hrc_drake.bt import BTError, load_tree, validate
from tests.bt.bt_helpers import registry


def write(tmp_path, body, extra="", name="trees.xml"):
    path = tmp_path / name
    path.write_text(
        f'<root BTCPP_format="4" main_tree_to_execute="Main">\n'
        f'<BehaviorTree ID="Main">\n{body}\n</BehaviorTree>\n{extra}</root>\n'
    )
    return path


def messages(path):
    return [error.message for error in validate(path, registry())]


def test_valid_file_has_no_errors(tmp_path):
    assert messages(write(tmp_path, "<Sequence><AlwaysSuccess/></Sequence>")) == []


def test_unknown_node_id_suggests_closest(tmp_path):
    path = write(tmp_path, '<Sequence>\n<AlwaysSucess name="ok"/>\n</Sequence>')
    assert messages(path) == [
        f"{path}:4: tree 'Main', node 'ok': unknown node type "
        f"'AlwaysSucess' (did you mean 'AlwaysSuccess'?)"
    ]


def test_missing_required_port(tmp_path):
    path = write(tmp_path, "<Repeat>\n<AlwaysSuccess/></Repeat>")
    assert messages(path) == [
        f"{path}:3: tree 'Main', node 'Repeat::1', port 'num_cycles': "
        f"missing required port of 'Repeat'"
    ]


def test_port_not_declared_by_node(tmp_path):
    path = write(tmp_path, '<Sleep name="nap" msecs="10"/>')
    assert messages(path) == [
        f"{path}:3: tree 'Main', node 'nap', port 'msecs': port "
        f"'msecs' is not declared by 'Sleep' (did you mean 'msec'?)",
        f"{path}:3: tree 'Main', node 'nap', port 'msec': missing required port of 'Sleep'",
    ]


def test_value_that_cannot_be_converted(tmp_path):
    path = write(tmp_path, '<Sleep name="nap" msec="soon"/>')
    assert messages(path) == [
        f"{path}:3: tree 'Main', node 'nap', port 'msec': cannot "
        f"convert 'soon' to int: invalid literal for int() with base "
        f"10: 'soon'"
    ]


def test_script_syntax_error_in_port_and_precondition(tmp_path):
    path = write(
        tmp_path,
        '<Sequence>\n<Script name="s" code="x := := 1"/>\n'
        '<AlwaysSuccess name="a" _skipIf="x &lt;"/>\n</Sequence>',
    )
    assert messages(path) == [
        f"{path}:4: tree 'Main', node 's', port 'code': script syntax error at column 6: "
        f"expected a value, found ':=' in 'x := := 1'",
        f"{path}:5: tree 'Main', node 'a', port '_skipIf': script syntax error at column 4: "
        f"expected a value, found end of script in 'x <'",
    ]


def test_subtree_cycle(tmp_path):
    path = write(
        tmp_path,
        '<SubTree ID="A"/>',
        '<BehaviorTree ID="A">\n<SubTree ID="B"/>\n</BehaviorTree>\n'
        '<BehaviorTree ID="B">\n<SubTree ID="A"/>\n</BehaviorTree>\n',
    )
    assert messages(path) == [
        f"{path}:9: tree 'B', node 'A::1/B::2/A::3': SubTree cycle: Main -> A -> B -> A"
    ]


def test_unknown_subtree_and_missing_include(tmp_path):
    path = write(
        tmp_path,
        '<SubTree ID="Grasp"/>',
        '<BehaviorTree ID="Grab"><AlwaysSuccess/></BehaviorTree>\n',
    )
    assert messages(path) == [
        f"{path}:3: tree 'Main', node 'Grasp::1': unknown SubTree ID 'Grasp' (did you mean 'Grab'?)"
    ]
    path = write(tmp_path, "<AlwaysSuccess/>", '<include path="lib/missing.xml"/>\n', "inc.xml")
    assert messages(path) == [
        f"{path}:5: included file 'lib/missing.xml' not found (looked in {tmp_path})"
    ]


def test_wrong_number_of_children_and_output_literal(tmp_path):
    path = write(tmp_path, '<Inverter name="inv"><AlwaysSuccess/><AlwaysFailure/></Inverter>')
    assert messages(path) == [
        f"{path}:3: tree 'Main', node 'inv': 'Inverter' needs exactly 1 children, has 2"
    ]
    path = write(tmp_path, '<LoopInt name="l" queue="1;2" value="v"><AlwaysSuccess/></LoopInt>')
    assert messages(path) == [
        f"{path}:3: tree 'Main', node 'l', port 'value': output port "
        f"needs a blackboard entry like '{{v}}', not the literal 'v'"
    ]


def test_several_errors_are_all_reported_and_load_raises_the_first(tmp_path):
    path = write(tmp_path, '<Sequence><Foo/><Sleep/><Script code="("/></Sequence>')
    assert len(messages(path)) == 3
    with pytest.raises(BTError, match=r"unknown node type 'Foo'"):
        load_tree(path, registry())


def test_malformed_xml_and_unknown_main_tree(tmp_path):
    path = tmp_path / "bad.xml"
    path.write_text('<root>\n<BehaviorTree ID="Main">\n<Sequence>\n</root>\n')
    assert messages(path) == [f"{path}:4: malformed XML: mismatched tag"]
    good = write(tmp_path, "<AlwaysSuccess/>")
    assert [e.message for e in validate(good, registry(), tree_id="Mian")] == [
        f"{good}:1: tree 'Mian': no BehaviorTree with ID 'Mian' (trees: Main) "
        "(did you mean 'Main'?)"
    ]
