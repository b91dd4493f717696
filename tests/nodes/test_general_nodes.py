"""The thesis system's general nodes (docs/thesis-system.md): random poses over areas, weighted
choices, random failure, resumable sequences — checked statistically and tick by tick."""

import numpy as np
import pytest

from hrc_drake.areas import Area
from hrc_drake.bt import Status, SyncActionNode, load_tree
from hrc_drake.nodes import hrc_registry
from hrc_drake.nodes.agent import Agent, Places

L_SHAPE = Area.from_polygon([[0, 0], [2, 0], [2, 1], [1, 1], [1, 2], [0, 2]])
CHI2_999 = {2: 13.82, 11: 31.26}  # chi-square critical values at p = 0.001


def make_tree(body: str, registry=None, seed=0):
    xml = f'<root BTCPP_format="4"><BehaviorTree ID="Main">{body}</BehaviorTree></root>'
    agent = Agent("robot", Places(areas={"L": L_SHAPE}))
    return load_tree(xml, registry or hrc_registry(), seed=seed, agent=agent)


def chi_square(counts, expected) -> float:
    counts = np.asarray(counts, dtype=float)
    return float(((counts - expected) ** 2 / expected).sum())


def test_generate_xy_pose_is_uniform_over_an_l_shaped_area():
    tree = make_tree('<GenerateXYPose area="L" pose="{p}"/>')
    points = []
    for i in range(1000):
        assert tree.tick(i * 0.05) is Status.SUCCESS
        points.append(tree.root_blackboard.get("p").position[:2])
    points = np.array(points)
    assert all(L_SHAPE.contains(p) for p in points)
    cells = np.floor(points / 0.5).astype(int)
    inside = sorted(
        {
            (i, j)
            for i in range(4)
            for j in range(4)
            if L_SHAPE.contains([(i + 0.5) * 0.5, (j + 0.5) * 0.5])
        }
    )
    counts = [np.sum((cells[:, 0] == i) & (cells[:, 1] == j)) for i, j in inside]
    assert len(inside) == 12 and sum(counts) == 1000
    assert chi_square(counts, 1000 / 12) < CHI2_999[11]


def test_generate_xy_pose_accepts_literal_triangles():
    tree = make_tree('<GenerateXYPose area="0,0;1,0;0,1" pose="{p}"/>')
    tree.tick(0.0)
    x, y, z = tree.root_blackboard.get("p").position
    assert x >= 0 and y >= 0 and x + y <= 1 and z == 0


class Counted(SyncActionNode):
    """Succeeds after failing `failures` times; counts its ticks per instance name."""

    ticks: dict[str, int] = {}

    def tick(self):
        Counted.ticks[self.name] = Counted.ticks.get(self.name, 0) + 1
        return Status.SUCCESS


def test_weighted_random_picks_children_with_the_given_frequencies():
    registry = hrc_registry()
    registry.register(Counted)
    Counted.ticks = {}
    tree = make_tree(
        '<WeightedRandom weights="1;2;7">'
        '<Counted name="a"/><Counted name="b"/><Counted name="c"/></WeightedRandom>',
        registry,
    )
    for i in range(2000):
        assert tree.tick(i * 0.05) is Status.SUCCESS
    counts = [Counted.ticks.get(name, 0) for name in "abc"]
    expected = 2000 * np.array([0.1, 0.2, 0.7])
    assert chi_square(counts, expected) < CHI2_999[2]


def test_weighted_random_sticks_with_a_child_until_it_succeeds():
    tree = make_tree(
        '<WeightedRandom weights="1;1">'
        '<Script code="x := 1" _failureIf="tries &lt; 3" _post="tries += 1"/>'
        '<Script code="x := 2" _failureIf="tries &lt; 3" _post="tries += 1"/>'
        "</WeightedRandom>"
    )
    first_picks = set()
    for seed in range(10):
        tree.reset(rng=np.random.default_rng(seed))
        tree.root_blackboard.set("tries", 0)
        statuses, picks = [], []
        for i in range(4):
            statuses.append(tree.tick(i * 0.05))
            picks.append(tree.root.picked)
        assert statuses == [Status.FAILURE] * 3 + [Status.SUCCESS]
        assert picks[0] == picks[1] == picks[2] is not None and picks[3] is None
        first_picks.add(picks[0])
    assert first_picks == {0, 1}


def test_random_failure_fails_at_its_rate():
    tree = make_tree('<RandomFailure failure_chance="0.3"/>', seed=5)
    failures = sum(tree.tick(i * 0.05) is Status.FAILURE for i in range(4000))
    assert failures / 4000 == pytest.approx(0.3, abs=0.03)


def test_interruptable_sequence_resumes_where_it_was_interrupted():
    tree = make_tree(
        "<ReactiveFallback>"
        '<ScriptCondition code="interrupt"/>'
        "<InterruptableSequence>"
        '<Script code="a += 1"/>'
        '<Sleep msec="100"/>'
        '<Script code="b += 1"/>'
        "</InterruptableSequence>"
        "</ReactiveFallback>"
    )
    board = tree.root_blackboard
    for key, value in (("interrupt", False), ("a", 0), ("b", 0)):
        board.set(key, value)
    assert tree.tick(0.0) is Status.RUNNING  # a done, sleeping
    board.set("interrupt", True)
    assert tree.tick(0.05) is Status.SUCCESS  # the higher-priority branch halts the sequence
    board.set("interrupt", False)
    assert tree.tick(0.10) is Status.RUNNING  # resumes at Sleep, not at the start
    assert tree.tick(0.25) is Status.SUCCESS
    assert (board.get("a"), board.get("b")) == (1, 1)


def test_sequence_restarts_after_interruption_for_comparison():
    tree = make_tree(
        "<ReactiveFallback>"
        '<ScriptCondition code="interrupt"/>'
        '<Sequence><Script code="a += 1"/><Sleep msec="100"/></Sequence>'
        "</ReactiveFallback>"
    )
    board = tree.root_blackboard
    board.set("interrupt", False)
    board.set("a", 0)
    tree.tick(0.0)
    board.set("interrupt", True)
    tree.tick(0.05)
    board.set("interrupt", False)
    tree.tick(0.10)
    assert board.get("a") == 2


def test_in_area_test_and_offset_pose():
    tree = make_tree(
        "<Sequence>"
        '<OffsetPose input="0.5;0.5;0" offset="1;0;0" orientation="1;0;0;0" output="{q}"/>'
        '<InAreaTest pose="{q}" area="L"/>'
        '<OffsetPose input="{q}" offset="0;1;0" output="{r}"/>'
        '<Inverter><InAreaTest pose="{r}" area="L"/></Inverter>'
        "</Sequence>"
    )
    assert tree.tick(0.0) is Status.SUCCESS
    r = tree.root_blackboard.get("r")
    assert r.position == (1.5, 1.5, 0.0) and r.quaternion == (1.0, 0.0, 0.0, 0.0)
