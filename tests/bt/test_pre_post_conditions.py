"""Pre- and post-conditions, modelled on BT.CPP tests/gtest_preconditions.cpp,
gtest_postconditions.cpp and gtest_skipping.cpp."""

from tests.bt.bt_helpers import F, K, R, S, all_idle, ticks, tree_of


def test_failure_success_skip_if_are_checked_only_when_idle():
    tree = tree_of(
        '<Sequence><Script code="a := 1"/><AsyncMock name="A" duration="2" '
        '_failureIf="a == 2"/></Sequence>'
    )
    assert tree.tick(0) is R
    tree.root_blackboard.set("a", 2)
    assert tree.tick(1) is R  # A is RUNNING: _failureIf not evaluated
    assert tree.tick(2) is S
    assert tree_of('<Mock name="A" _successIf="true"/>').tick(0) is S
    assert tree_of('<Mock name="A" _failureIf="true" _successIf="true"/>').tick(0) is F
    skipped = tree_of('<Sequence><Mock name="A" _skipIf="true"/><Mock name="B"/></Sequence>')
    assert skipped.tick(0) is S
    assert skipped.node("A").ticks == 0


def test_while_halts_running_node_when_false():
    tree = tree_of(
        '<Sequence><Script code="go := true"/><AsyncMock name="A" duration="9" '
        '_while="go"/><Mock name="B"/></Sequence>'
    )
    assert ticks(tree, 2) == [R, R]
    tree.root_blackboard.set("go", False)
    assert tree.tick(1) is S  # A halted and SKIPPED, B runs
    assert tree.node("A").halts == 1
    assert tree.node("B").ticks == 1
    assert all_idle(tree)


def test_post_conditions_run_on_result_and_on_halt():
    tree = tree_of(
        "<Sequence><Script code=\"log := ''\"/>"
        '<Mock name="A" _onSuccess="log := log .. \'s\'" _post="log := log .. \'p\'"/>'
        '<Mock name="B" _onFailure="log := log .. \'f\'"/></Sequence>'
    )
    tree.node("B").result = F
    assert tree.tick(0) is F
    assert tree.root_blackboard.get("log") == "spf"
    halted = tree_of('<AsyncMock duration="9" _onHalted="halted := true"/>')
    assert halted.tick(0) is R
    halted.halt()
    assert halted.root_blackboard.get("halted") is True


def test_skipped_node_stays_idle():
    tree = tree_of('<Fallback><Mock name="A" _skipIf="true"/><AlwaysFailure/></Fallback>')
    assert tree.tick(0) is F
    assert tree.node("A").status.name == "IDLE"
    assert tree_of('<Sequence _skipIf="true"><AlwaysFailure/></Sequence>').tick(0) is K
