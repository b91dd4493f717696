"""Property tests on random trees of built-ins (hypothesis)."""

from hypothesis import given, settings
from hypothesis import strategies as st

from tests.bt.bt_helpers import IDLE, R, Recorder, all_idle, tree_of

LEAVES = st.sampled_from(
    [
        "<AlwaysSuccess/>",
        "<AlwaysFailure/>",
        "<RandomResult/>",
        '<Sleep msec="150"/>',
        '<AsyncMock duration="1"/>',
        '<AsyncMock duration="3" result="FAILURE"/>',
        '<Script code="n := 1"/>',
        '<ScriptCondition code="n == 1"/>',
        '<AsyncMock duration="2" _while="true"/>',
        '<RandomResult _skipIf="false"/>',
    ]
)

CONDITIONS = st.sampled_from(
    [
        "<AlwaysFailure/>",
        "<RandomResult/>",
        '<ScriptCondition code="n == 1"/>',
        '<AsyncMock duration="1" result="FAILURE"/>',
    ]
)

DECORATORS = st.sampled_from(
    [
        "Inverter",
        "ForceSuccess",
        "ForceFailure",
        'Repeat num_cycles="2"',
        'RetryUntilSuccessful num_attempts="2"',
        "KeepRunningUntilFailure",
        'Timeout msec="200"',
        'Delay delay_msec="100"',
        "RunOnce",
        'Precondition if="n == 1" else="SUCCESS"',
    ]
)

CONTROLS = st.sampled_from(
    [
        "Sequence",
        "Fallback",
        "ReactiveSequence",
        "ReactiveFallback",
        "SequenceWithMemory",
        "AsyncSequence",
        "AsyncFallback",
        'ParallelAll max_failures="1"',
        "Parallel",
        'Parallel success_count="1"',
        "TryCatch",
    ]
)


def _element(tag: str, children: list[str]) -> str:
    return f"<{tag}>{''.join(children)}</{tag.split()[0]}>"


def _loadable(control: str, children: list[str]) -> bool:
    """BehaviorTree.CPP refuses a ReactiveSequence with two AsyncSequence children (and so
    does our builder: tree_builder's _check_async_children), so no random tree has one."""
    asynchronous = sum(child.startswith("<AsyncSequence>") for child in children)
    return control != "ReactiveSequence" or asynchronous < 2


def _extend(children):
    composite = (
        st.tuples(CONTROLS, st.lists(children, min_size=2, max_size=4))
        .filter(lambda parts: _loadable(*parts))
        .map(lambda parts: _element(*parts))
    )
    decorated = st.builds(lambda tag, child: _element(tag, [child]), DECORATORS, children)
    branching = st.builds(
        lambda tag, condition, branches: _element(tag, [condition, *branches]),
        st.sampled_from(["IfThenElse", "WhileDoElse"]),
        CONDITIONS,  # a skipped condition is an error, as in BT.CPP
        st.lists(children, min_size=1, max_size=2),
    )
    switch = st.builds(
        lambda kids: _element('Switch2 variable="{n}" case_1="1" case_2="2"', kids),
        st.lists(children, min_size=3, max_size=3),
    )
    return composite | decorated | branching | switch


TREES = st.recursive(LEAVES, _extend, max_leaves=12)


def build(body, seed=0):
    return tree_of(f'<Sequence><Script code="n := 1"/>{body}</Sequence>', seed=seed)


def run(tree, count):
    return [tree.tick(0.05 * index) for index in range(count)]


@settings(max_examples=60, deadline=None)
@given(TREES, st.integers(1, 25))
def test_random_trees_tick_without_errors_and_halt_to_idle(body, count):
    tree = build(body)
    recorder = Recorder()
    tree.add_observer(recorder)
    run(tree, count)
    tree.halt()
    assert all_idle(tree)
    for _, _, node in tree.nodes():
        if type(node).__name__ == "AsyncMock":
            assert node.halts <= node.starts
    running_before_halt = {uid for _, uid, _, _, new in recorder.transitions if new is R}
    halted_twice = [
        uid
        for uid in running_before_halt
        if sum(
            1
            for _, u, _, prev, new in recorder.transitions
            if u == uid and prev is R and new is IDLE
        )
        > sum(1 for _, u, _, _, new in recorder.transitions if u == uid and new is R)
    ]
    assert halted_twice == []


@settings(max_examples=40, deadline=None)
@given(TREES, st.integers(0, 2**32 - 1))
def test_same_seed_gives_identical_transition_logs(body, seed):
    logs = []
    for _ in range(2):
        tree = build(body, seed)
        recorder = Recorder()
        tree.add_observer(recorder)
        run(tree, 20)
        logs.append(recorder.transitions)
    assert logs[0] == logs[1]


@settings(max_examples=30, deadline=None)
@given(TREES)
def test_reset_replays_the_same_run(body):
    tree = build(body, seed=5)
    recorder = Recorder()
    tree.add_observer(recorder)
    first = run(tree, 15)
    import numpy as np

    tree.reset(rng=np.random.default_rng(5))
    recorder.transitions.clear()
    assert run(tree, 15) == first
