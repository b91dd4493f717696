"""Script language and blackboard actions, modelled on BT.CPP tests/script_parser_test.cpp
and gtest_blackboard.cpp."""

import pytest

from hrc_drake.bt import Blackboard, BTError
from hrc_drake.bt.script import ScriptEnv, compile_script
from tests.bt.bt_helpers import F, S, tree_of


def run(code, enums=None, **entries):
    blackboard = Blackboard()
    for key, value in entries.items():
        blackboard.set(key, value)
    return compile_script(code)(ScriptEnv(blackboard, enums or {})), blackboard


@pytest.mark.parametrize(
    ("code", "expected"),
    [
        ("1 + 2 * 3", 7),
        ("(1 + 2) * 3", 9),
        ("7 / 2", 3.5),
        ("-3 + 1", -2),
        ("'ab' .. 'cd'", "abcd"),
        ("'n=' .. 3", "n=3"),
        ("'a' + 'b'", "ab"),
        ("1 < 2 && 2 < 3", True),
        ("1 == 1.0", True),
        ("'2' == 2", True),
        ("!true", False),
        ("true || false", True),
        ("3 > 2 ? 'yes' : 'no'", "yes"),
        ("0x10 | 1", 17),
        ("1 < 2 < 3", True),
        ("3 > 2 > 2", False),
        ("'abc' != 'abd'", True),
        ("6 & 3", 2),
    ],
)
def test_expressions(code, expected):
    assert run(code)[0] == expected


@pytest.mark.parametrize(
    ("code", "expected"),
    [
        ("10 - 4 + 2", 8),  # left-associative: (10 - 4) + 2 (BT.CPP 4.8: 10 - (4 + 2))
        ("8 / 4 * 2", 4),
        ("1 || 0 && 0", True),  # && binds tighter than || (BT.CPP 4.8: left to right)
        ("0 && 1 || 1", True),
        ("1 | 2 == 3", True),  # comparisons bind looser than bitwise operators
        ("6 & 3 == 2", True),
        ("1 | 6 ^ 4", 3),  # | and ^ on one level, left to right: (1 | 6) ^ 4
    ],
)
def test_operator_precedence_and_associativity_as_btcpp_4_9(code, expected):
    assert run(code)[0] == expected


def test_concatenation_binds_like_addition():
    with pytest.raises(BTError, match="operator '\\+' not permitted on 'a1' and 1"):
        run("'a' .. 1 + 1")  # ('a' .. 1) + 1, as BT.CPP 4.9


def test_assignments_create_and_update_entries():
    result, blackboard = run("a := 1; b := a + 1; a += 10; b *= 2; s := 'x'; s += 'y'")
    assert (blackboard.get("a"), blackboard.get("b"), blackboard.get("s")) == (11, 4, "xy")
    assert result == "xy"


def test_assign_to_missing_entry_needs_create_operator():
    with pytest.raises(BTError, match="does not exist; use ':=' to create it"):
        run("missing = 1")


def test_enums_in_scripts():
    assert run("color == RED", enums={"RED": 1}, color=1)[0] is True


def test_typed_entry_converts_assigned_value():
    blackboard = Blackboard()
    blackboard.declare("n", int)
    compile_script("n = '42'")(ScriptEnv(blackboard, {}))
    assert blackboard.get("n") == 42
    with pytest.raises(BTError, match="is not a int"):
        compile_script("n = 1.5")(ScriptEnv(blackboard, {}))


@pytest.mark.parametrize("code", ["a := ", "1 +* 2", "a := (1", "x ? 1", "'open", "a $ b"])
def test_syntax_errors(code):
    with pytest.raises(BTError, match="script syntax error"):
        compile_script(code)


def test_script_and_script_condition_nodes():
    tree = tree_of(
        '<Sequence><Script code="n := 3"/><ScriptCondition code="n == 3"/>'
        '<Script code="n = n - 1"/></Sequence>'
    )
    assert tree.tick(0) is S
    assert tree.root_blackboard.get("n") == 2
    assert tree_of('<ScriptCondition code="1 > 2"/>').tick(0) is F


def test_runtime_script_error_names_the_node():
    tree = tree_of('<Sequence><Script name="Bad" code="y := unknown + 1"/></Sequence>')
    with pytest.raises(
        BTError,
        match=r"^<string>:1: tree 'Main', node 'Bad': script: variable 'unknown' is not set$",
    ):
        tree.tick(0)


def test_set_and_unset_blackboard():
    tree = tree_of(
        '<Sequence><SetBlackboard value="42" output_key="answer"/>'
        '<SetBlackboard value="{answer}" output_key="copy"/>'
        '<UnsetBlackboard key="answer"/></Sequence>'
    )
    assert tree.tick(0) is S
    assert tree.root_blackboard.get("copy") == "42"
    assert not tree.root_blackboard.has("answer")


def test_was_entry_updated_and_constants():
    tree = tree_of('<WasEntryUpdated entry="{x}"/>')
    assert tree.tick(0) is F
    tree.root_blackboard.set("x", 1)
    assert [tree.tick(1), tree.tick(2)] == [S, F]
    assert tree_of("<AlwaysSuccess/>").tick(0) is S
    assert tree_of("<AlwaysFailure/>").tick(0) is F
