"""Delay, Timeout and Sleep on simulation time (a fake clock: the times passed to tick),
modelled on BT.CPP tests/gtest_decorator.cpp (timeout) and gtest_async_action_node.cpp."""

from tests.bt.bt_helpers import F, R, S, all_idle, ticks, tree_of


def test_sleep_succeeds_after_its_duration_of_simulated_time():
    tree = tree_of('<Sleep msec="200"/>')
    assert [tree.tick(t) for t in (1.0, 1.1, 1.19)] == [R, R, R]
    assert tree.tick(1.2) is S  # 1.0 + 0.2 despite float rounding
    assert tree_of('<Sleep msec="0"/>').tick(0) is S


def test_delay_ticks_child_after_delay():
    tree = tree_of('<Delay delay_msec="100"><Mock name="A"/></Delay>')
    assert ticks(tree, 3, step=0.05) == [R, R, S]
    assert tree.node("A").ticks == 1
    assert ticks(tree, 1, start=5.0) == [R]  # restarted


def test_timeout_halts_slow_child_and_fails():
    tree = tree_of('<Timeout msec="250"><AsyncMock name="A" duration="99"/></Timeout>')
    assert ticks(tree, 3) == [R, R, R]
    assert tree.tick(0.3) is F
    assert tree.node("A").halts == 1
    assert all_idle(tree)


def test_timeout_lets_fast_child_finish():
    tree = tree_of('<Timeout msec="1000"><AsyncMock name="A" duration="2"/></Timeout>')
    assert ticks(tree, 3) == [R, R, S]
    assert tree.node("A").halts == 0


def test_same_times_give_same_results_whatever_the_tick_rate():
    slow = tree_of('<Sequence><Sleep msec="500"/><AlwaysSuccess/></Sequence>')
    fast = tree_of('<Sequence><Sleep msec="500"/><AlwaysSuccess/></Sequence>')
    assert [slow.tick(t) for t in (0.0, 0.5)] == [R, S]
    assert ticks(fast, 51, step=0.01)[-2:] == [R, S]
