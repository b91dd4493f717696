"""Parallel, ParallelAll, IfThenElse, WhileDoElse, SwitchN and TryCatch, modelled on
BT.CPP tests/gtest_parallel.cpp, gtest_if_then_else.cpp, gtest_while_do_else.cpp,
gtest_switch.cpp and gtest_try_catch.cpp."""

import enum

from tests.bt.bt_helpers import F, K, R, S, all_idle, registry, ticks, tree_of


def test_parallel_default_needs_all_successes_and_fails_on_first_failure():
    tree = tree_of(
        '<Parallel><AsyncMock name="A" duration="1"/><AsyncMock name="B" duration="3"/></Parallel>'
    )
    assert ticks(tree, 4) == [R, R, R, S]
    assert tree.node("A").starts == 1  # completed children are not ticked again
    failing = tree_of('<Parallel><AlwaysFailure/><AsyncMock name="B" duration="3"/></Parallel>')
    assert failing.tick(0) is F
    assert failing.node("B").starts == 0  # threshold checked after each child


def test_parallel_thresholds_halt_the_children_still_running():
    tree = tree_of(
        '<Parallel success_count="1" failure_count="2">'
        '<AsyncMock name="A" duration="1"/><AsyncMock name="B" duration="5"/>'
        '<AsyncMock name="C" duration="5"/></Parallel>'
    )
    assert ticks(tree, 2) == [R, S]
    assert tree.node("B").halts == tree.node("C").halts == 1
    assert all_idle(tree)


def test_parallel_fails_when_success_becomes_impossible():
    tree = tree_of(
        '<Parallel success_count="2" failure_count="3"><AlwaysFailure/>'
        '<AlwaysFailure/><AsyncMock name="C"/></Parallel>'
    )
    assert tree.tick(0) is F
    assert tree.node("C").starts == 0  # 3 children - 2 failures < 2 needed successes


def test_parallel_negative_success_count_counts_from_children():
    tree = tree_of(
        '<Parallel success_count="-2"><AlwaysSuccess/><AlwaysFailure/><AlwaysSuccess/></Parallel>'
    )
    assert tree.tick(0) is F  # failure_count=1 reached before the third child
    tree = tree_of(
        '<Parallel success_count="-2" failure_count="2"><AlwaysSuccess/>'
        "<AlwaysFailure/><AlwaysSuccess/></Parallel>"
    )
    assert tree.tick(0) is S


def test_parallel_all_waits_for_every_child():
    tree = tree_of(
        '<ParallelAll max_failures="2"><AlwaysFailure/>'
        '<AsyncMock duration="2"/><AlwaysSuccess/></ParallelAll>'
    )
    assert ticks(tree, 3) == [R, R, S]
    tree = tree_of(
        '<ParallelAll max_failures="1"><AlwaysFailure/><AsyncMock duration="1"/></ParallelAll>'
    )
    assert ticks(tree, 2) == [R, F]


def test_if_then_else_checks_condition_once():
    tree = tree_of(
        '<IfThenElse><MockCondition name="C"/><AsyncMock name="Then" duration="2"/>'
        '<Mock name="Else"/></IfThenElse>'
    )
    assert tree.tick(0) is R
    tree.node("C").result = F
    assert ticks(tree, 2, 1) == [R, S]  # not re-checked while Then runs
    assert tree.node("C").ticks == 1
    assert tree.tick(2) is S
    assert tree.node("Else").ticks == 1
    two = tree_of("<IfThenElse><AlwaysFailure/><AlwaysSuccess/></IfThenElse>")
    assert two.tick(0) is F


def test_while_do_else_halts_branch_when_condition_changes():
    tree = tree_of(
        '<WhileDoElse><MockCondition name="C"/><AsyncMock name="Do" duration="9"/>'
        '<AsyncMock name="Else" duration="9"/></WhileDoElse>'
    )
    assert ticks(tree, 2) == [R, R]
    tree.node("C").result = F
    assert tree.tick(1) is R
    assert tree.node("Do").halts == 1
    assert tree.node("Else").status is R
    assert tree.node("C").ticks == 3
    two = tree_of("<WhileDoElse><AlwaysFailure/><AlwaysSuccess/></WhileDoElse>")
    assert two.tick(0) is F


class Color(enum.IntEnum):
    RED = 1
    BLUE = 2


def test_switch_compares_as_string_int_real_and_enum():
    reg = registry()
    reg.register_enum(Color)
    body = (
        '<Switch3 variable="{v}" case_1="1" case_2="BLUE" case_3="hello">'
        '<Mock name="one"/><Mock name="two"/><Mock name="three"/><Mock name="other"/>'
        "</Switch3>"
    )
    tree = tree_of(body, reg)
    expectations = {
        "1": "one",
        "1.0": "one",
        2: "two",
        "BLUE": "two",
        "hello": "three",
        "x": "other",
    }
    for value, child in expectations.items():
        tree.root_blackboard.set("v", value)
        tree.tick(0)
        assert tree.node(child).ticks >= 1, value
    assert tree.node("one").ticks == 2


def test_switch_halts_running_case_when_variable_changes():
    tree = tree_of(
        '<Sequence><Script code="v := 1"/><Switch2 variable="{v}" case_1="1" '
        'case_2="2"><AsyncMock name="A" duration="9"/><AsyncMock name="B" '
        'duration="9"/><AlwaysFailure/></Switch2></Sequence>'
    )
    assert tree.tick(0) is R
    tree.root_blackboard.set("v", 2)
    assert tree.tick(1) is R
    assert tree.node("A").halts == 1
    assert tree.node("B").status is R


def test_try_catch_runs_catch_branch_then_fails():
    tree = tree_of(
        '<TryCatch><Mock name="T1"/><Mock name="T2"/>'
        '<AsyncMock name="Catch" duration="1"/></TryCatch>'
    )
    assert tree.tick(0) is S
    tree.node("T2").result = F
    assert ticks(tree, 2) == [R, F]
    assert tree.node("Catch").starts == 1
    assert all_idle(tree)


def test_try_catch_on_halt_runs_catch_when_asked():
    tree = tree_of(
        '<TryCatch catch_on_halt="true"><AsyncMock name="T" duration="5"/>'
        '<Script code="caught := true"/></TryCatch>'
    )
    tree.tick(0)
    tree.halt()
    assert tree.root_blackboard.get("caught") is True
    assert all_idle(tree)
    skipped = tree_of('<TryCatch><Mock _skipIf="true"/><AlwaysSuccess/></TryCatch>')
    assert skipped.tick(0) is K
