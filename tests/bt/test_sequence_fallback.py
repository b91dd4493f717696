"""Sequence / Fallback family, modelled on BT.CPP tests/gtest_sequence.cpp,
gtest_fallback.cpp and gtest_reactive.cpp."""

from tests.bt.bt_helpers import IDLE, F, K, R, S, all_idle, statuses, ticks, tree_of


def test_sequence_resumes_at_running_child_without_reticking_earlier_ones():
    tree = tree_of(
        '<Sequence><Mock name="A"/><AsyncMock name="B" duration="2"/><Mock name="C"/></Sequence>'
    )
    assert ticks(tree, 3) == [R, R, S]
    assert tree.node("A").ticks == 1
    assert tree.node("C").ticks == 1
    assert all_idle(tree)


def test_sequence_failure_resets_to_first_child():
    tree = tree_of('<Sequence><Mock name="A"/><Mock name="B"/></Sequence>')
    tree.node("B").result = F
    assert ticks(tree, 2) == [F, F]
    assert tree.node("A").ticks == 2
    assert all_idle(tree)


def test_sequence_with_memory_does_not_restart_after_failure():
    tree = tree_of('<SequenceWithMemory><Mock name="A"/><Mock name="B"/></SequenceWithMemory>')
    tree.node("B").result = F
    assert ticks(tree, 3) == [R, F, F]  # R: yields after the synchronous child A
    assert tree.node("A").ticks == 1
    assert tree.node("B").ticks == 2
    tree.node("B").result = S
    assert tree.tick(1.0) is S
    assert tree.node("A").ticks == 1


def test_sequence_with_memory_keeps_position_when_halted():
    tree = tree_of(
        '<SequenceWithMemory><Mock name="A"/><AsyncMock name="B" duration="5"/>'
        "</SequenceWithMemory>"
    )
    ticks(tree, 3)
    tree.halt()
    assert all_idle(tree)
    assert tree.node("B").halts == 1
    tree.tick(1.0)
    assert tree.node("A").ticks == 1
    assert tree.node("B").starts == 2


def test_async_sequence_yields_between_synchronous_children():
    tree = tree_of(
        '<AsyncSequence><Mock name="A"/><Mock name="B"/><Mock name="C"/></AsyncSequence>'
    )
    assert ticks(tree, 3) == [R, R, S]
    plain = tree_of("<Sequence><Mock/><Mock/><Mock/></Sequence>")
    assert ticks(plain, 1) == [S]


def test_fallback_mirrors_sequence():
    tree = tree_of(
        '<Fallback><Mock name="A"/><AsyncMock name="B" duration="1"/><Mock name="C"/></Fallback>'
    )
    tree.node("A").result = F
    assert ticks(tree, 2) == [R, S]
    assert tree.node("C").ticks == 0
    tree.node("A").result = S
    assert ticks(tree, 1) == [S]
    async_fallback = tree_of("<AsyncFallback><AlwaysFailure/><AlwaysFailure/></AsyncFallback>")
    assert ticks(async_fallback, 2) == [R, F]


def test_all_children_skipped_means_skipped():
    tree = tree_of('<Sequence><Mock _skipIf="true"/><Mock _skipIf="true"/></Sequence>')
    assert tree.tick(0) is K
    fallback = tree_of('<Fallback><Mock _skipIf="true"/><Mock _skipIf="false"/></Fallback>')
    assert fallback.tick(0) is S


def test_reactive_sequence_reevaluates_conditions_and_halts_running_action():
    tree = tree_of(
        '<ReactiveSequence><MockCondition name="C1"/><MockCondition name="C2"/>'
        '<AsyncMock name="A" duration="3"/></ReactiveSequence>'
    )
    assert ticks(tree, 2) == [R, R]
    assert tree.node("C1").ticks == 2
    assert statuses(tree)["C1"] is IDLE  # halted by the running sibling
    tree.node("C2").result = F
    assert tree.tick(1.0) is F
    assert tree.node("A").halts == 1
    assert all_idle(tree)


def test_reactive_sequence_halts_previous_running_child():
    tree = tree_of(
        '<ReactiveSequence><ReactiveFallback><MockCondition name="Busy"/>'
        '<AsyncMock name="First" duration="9"/></ReactiveFallback>'
        '<AsyncMock name="Second" duration="9"/></ReactiveSequence>'
    )
    tree.node("Busy").result = F
    ticks(tree, 2)
    assert tree.node("First").status is R
    tree.node("Busy").result = S
    assert tree.tick(1.0) is R
    assert tree.node("First").halts == 1
    assert tree.node("Second").status is R


def test_reactive_fallback_stops_action_when_condition_becomes_true():
    tree = tree_of(
        '<ReactiveFallback><MockCondition name="Done"/>'
        '<AsyncMock name="Work" duration="5"/></ReactiveFallback>'
    )
    tree.node("Done").result = F
    assert ticks(tree, 2) == [R, R]
    tree.node("Done").result = S
    assert tree.tick(1.0) is S
    assert tree.node("Work").halts == 1
    assert all_idle(tree)
