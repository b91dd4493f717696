"""Decorators, modelled on BT.CPP tests/gtest_decorator.cpp, gtest_loop.cpp,
gtest_updates.cpp and gtest_preconditions.cpp (Precondition node)."""

from tests.bt.bt_helpers import IDLE, F, K, R, S, all_idle, ticks, tree_of


def test_inverter_and_force_nodes():
    assert tree_of("<Inverter><AlwaysSuccess/></Inverter>").tick(0) is F
    assert tree_of("<Inverter><AlwaysFailure/></Inverter>").tick(0) is S
    assert tree_of("<ForceSuccess><AlwaysFailure/></ForceSuccess>").tick(0) is S
    assert tree_of("<ForceFailure><AlwaysSuccess/></ForceFailure>").tick(0) is F
    running = tree_of('<Inverter><AsyncMock duration="1" result="FAILURE"/></Inverter>')
    assert ticks(running, 2) == [R, S]


def test_repeat_runs_one_synchronous_cycle_per_tick():
    tree = tree_of('<Repeat num_cycles="3"><Mock name="A"/></Repeat>')
    assert ticks(tree, 3) == [R, R, S]
    assert tree.node("A").ticks == 3
    tree.node("A").result = F
    assert tree.tick(1) is F


def test_repeat_with_async_child_and_forever():
    tree = tree_of('<Repeat num_cycles="2"><AsyncMock name="A" duration="1"/></Repeat>')
    assert ticks(tree, 3) == [R, R, S]  # the second cycle starts in the same tick
    assert tree.node("A").starts == 2
    forever = tree_of('<Repeat num_cycles="-1"><Mock name="A"/></Repeat>')
    assert set(ticks(forever, 50)) == {R}


def test_retry_until_successful():
    tree = tree_of('<RetryUntilSuccessful num_attempts="3"><Mock name="A"/></RetryUntilSuccessful>')
    tree.node("A").result = F
    assert ticks(tree, 3) == [R, R, F]
    tree.node("A").result = S
    assert tree.tick(1) is S


def test_keep_running_until_failure():
    tree = tree_of('<KeepRunningUntilFailure><Mock name="A"/></KeepRunningUntilFailure>')
    assert ticks(tree, 3) == [R, R, R]
    tree.node("A").result = F
    assert tree.tick(1) is F


def test_run_once_then_skip_or_repeat_result():
    tree = tree_of('<Sequence><RunOnce><Mock name="A"/></RunOnce><AlwaysSuccess/></Sequence>')
    assert ticks(tree, 3) == [S, S, S]
    assert tree.node("A").ticks == 1
    tree = tree_of('<RunOnce then_skip="false"><AlwaysFailure/></RunOnce>')
    assert ticks(tree, 2) == [F, F]
    tree = tree_of("<RunOnce><AlwaysFailure/></RunOnce>")
    assert ticks(tree, 2) == [F, K]
    tree.reset()
    assert tree.tick(0) is F


def test_precondition_decorator_not_rechecked_while_running():
    tree = tree_of(
        '<Precondition if="go == 1" else="SKIPPED"><AsyncMock name="A" '
        'duration="2"/></Precondition>'
    )
    tree.root_blackboard.set("go", 0)
    assert tree.tick(0) is K
    tree.root_blackboard.set("go", 1)
    assert tree.tick(1) is R
    tree.root_blackboard.set("go", 0)
    assert ticks(tree, 2, 2) == [R, S]
    assert tree.tick(3) is K
    assert tree_of('<Precondition if="false"><AlwaysSuccess/></Precondition>').tick(0) is F


def test_loop_static_queue_outputs_each_value():
    tree = tree_of('<LoopInt queue="1;2;3" value="{v}"><Script code="total += v"/></LoopInt>')
    tree.root_blackboard.set("total", 0)
    assert ticks(tree, 4) == [R, R, R, S]
    assert tree.root_blackboard.get("total") == 6
    empty = tree_of('<LoopString queue="" if_empty="FAILURE"><AlwaysSuccess/></LoopString>')
    assert empty.tick(0) is F


def test_loop_over_blackboard_list_consumes_it_and_stops_on_failure():
    tree = tree_of(
        '<LoopDouble queue="{items}" value="{x}"><ScriptCondition code="x &lt; 2"/></LoopDouble>'
    )
    items = [0.5, 1.5, 2.5, 3.5]
    tree.root_blackboard.set("items", items)
    assert ticks(tree, 3) == [R, R, F]
    assert items == [3.5]


def test_skip_unless_updated_and_wait_value_update():
    tree = tree_of(
        '<Sequence><SkipUnlessUpdated entry="{x}"><Mock name="A"/>'
        '</SkipUnlessUpdated><WaitValueUpdate entry="y"><Mock name="B"/>'
        "</WaitValueUpdate></Sequence>"
    )
    tree.root_blackboard.set("x", 1)
    tree.root_blackboard.set("y", 1)
    assert tree.tick(0) is S
    assert tree.tick(1) is R  # A skipped (x unchanged); B waits for y
    assert tree.node("A").ticks == 1
    tree.root_blackboard.set("y", 2)
    assert tree.tick(2) is S
    assert tree.node("B").ticks == 2


def test_halting_a_decorator_chain_halts_leaf_once():
    tree = tree_of(
        '<Inverter><ForceSuccess><Repeat num_cycles="5"><AsyncMock name="A" '
        'duration="9"/></Repeat></ForceSuccess></Inverter>'
    )
    ticks(tree, 2)
    tree.halt()
    tree.halt()
    assert tree.node("A").halts == 1
    assert all_idle(tree)
    assert tree.root.status is IDLE
