"""SubTrees, remapping, _autoremap, {@key}, typed entries, includes and reset, modelled on
BT.CPP tests/gtest_subtree.cpp, gtest_blackboard.cpp and gtest_factory.cpp."""

import pytest

from hrc_drake.bt import BTError, InputPort, OutputPort, SyncActionNode, TreeFactory
from tests.bt.bt_helpers import F, R, S, registry, tree_of

SUB = (
    '<BehaviorTree ID="Sub"><Sequence><Script code="inner := inner + 1"/>'
    '<Script code="private := 5"/></Sequence></BehaviorTree>'
)


def test_remapped_port_reads_and_writes_parent_entry():
    tree = tree_of(
        '<Sequence><Script code="x := 1"/><SubTree ID="Sub" inner="{x}"/></Sequence>', extra=SUB
    )
    assert tree.tick(0) is S
    assert tree.root_blackboard.get("x") == 2
    assert not tree.root_blackboard.has("private")
    assert tree.subtrees[1].blackboard.get("private") == 5


def test_literal_port_sets_subtree_entry():
    tree = tree_of(
        '<SubTree ID="Sub" inner="41"/>',
        extra=SUB.replace("inner := inner + 1", "out := inner .. '!'"),
    )
    assert tree.tick(0) is S
    assert tree.subtrees[1].blackboard.get("out") == "41!"


def test_same_name_shorthand_remaps_a_subtree_port_to_the_parents_entry():
    """BT.CPP's `port="{=}"`: the parent's entry named like the port."""
    tree = tree_of(
        '<Sequence><Script code="x := 3"/><SubTree ID="Negate" x="{=}"/></Sequence>',
        extra='<BehaviorTree ID="Negate"><Script code="x = -x"/></BehaviorTree>',
    )
    assert tree.tick(0) is S
    assert tree.root_blackboard.get("x") == -3
    assert tree.subtrees[1].blackboard.keys() == []


def test_same_name_shorthand_on_a_nodes_port():
    """On a node's port `{=}` and a bare `=` both mean the entry named like the port."""
    tree = tree_of(
        '<Sequence><Script code="value := 4"/><Consumer value="="/><Producer out="{=}"/>'
        "</Sequence>",
        typed_registry(),
    )
    assert tree.tick(0) is S
    assert tree.root_blackboard.as_dict() == {"value": 4, "seen": 4.0, "out": 12}


def test_autoremap_shares_every_key_but_private_ones():
    tree = tree_of(
        '<Sequence><Script code="inner := 10"/><SubTree ID="Sub" _autoremap="true"/></Sequence>',
        extra=SUB.replace("private := 5", "_private := 5"),
    )
    assert tree.tick(0) is S
    assert tree.root_blackboard.get("inner") == 11
    assert not tree.root_blackboard.has("_private")


def test_root_blackboard_reference_from_nested_subtree():
    tree = tree_of(
        '<SubTree ID="Outer"/>',
        extra=(
            '<BehaviorTree ID="Outer"><SubTree ID="Inner"/></BehaviorTree>'
            '<BehaviorTree ID="Inner"><Script code="@global := 7"/></BehaviorTree>'
        ),
    )
    assert tree.tick(0) is S
    assert tree.root_blackboard.get("global") == 7
    assert [instance.path for instance in tree.subtrees] == ["", "Outer::1", "Outer::1/Inner::2"]


class Producer(SyncActionNode):
    ports = (OutputPort("out", int),)

    def tick(self):
        self.set_output("out", "12")
        return S


class Consumer(SyncActionNode):
    ports = (InputPort("value", float),)

    def tick(self):
        self.blackboard.set("seen", self.get_input("value"))
        return S


def typed_registry():
    reg = registry()
    reg.register(Producer)
    reg.register(Consumer)
    return reg


def test_typed_entries_convert_strings():
    tree = tree_of('<Producer out="{n}"/>', typed_registry())
    tree.tick(0)
    assert tree.root_blackboard.get("n") == 12


def test_type_mismatch_through_subtree_remapping_is_reported():
    with pytest.raises(
        BTError,
        match=r"^<string>:1: tree 'Use', node 'Use::3/Consumer::4', "
        r"port 'value': blackboard entry 'v' has type int, but is used here "
        r"as double$",
    ):
        tree_of(
            '<Sequence><Producer out="{n}"/><SubTree ID="Use" v="{n}"/></Sequence>',
            typed_registry(),
            extra='<BehaviorTree ID="Use"><Consumer value="{v}"/></BehaviorTree>',
        )


def test_subtree_result_and_halt_propagate():
    tree = tree_of(
        '<SubTree ID="Work"/>',
        extra='<BehaviorTree ID="Work"><AsyncMock name="A" duration="1" '
        'result="FAILURE"/></BehaviorTree>',
    )
    assert [tree.tick(0), tree.tick(1)] == [R, F]
    tree.tick(2)
    tree.halt()
    assert tree.node("A").halts == 1


def test_reset_restores_blackboards_and_node_memory():
    tree = tree_of(
        '<Sequence><RunOnce><Script code="count := 1"/></RunOnce>'
        '<Script code="count += 1"/></Sequence>'
    )
    tree.root_blackboard.set("count", 0)
    tree.tick(0)
    tree.tick(1)
    assert tree.root_blackboard.get("count") == 3
    tree.reset()
    assert not tree.root_blackboard.has("count")
    tree.tick(0)
    assert tree.root_blackboard.get("count") == 2


def test_include_and_subtrees_across_files(tmp_path):
    (tmp_path / "lib").mkdir()
    (tmp_path / "lib" / "shared.xml").write_text(
        '<root BTCPP_format="4"><BehaviorTree ID="Shared"><Script code="@done := true"/>'
        "</BehaviorTree></root>"
    )
    (tmp_path / "main.xml").write_text(
        '<root BTCPP_format="4" main_tree_to_execute="Main"><include path="lib/shared.xml"/>'
        '<BehaviorTree ID="Main"><SubTree ID="Shared"/></BehaviorTree>'
        '<BehaviorTree ID="Other"><AlwaysFailure/></BehaviorTree></root>'
    )
    factory = TreeFactory(registry())
    factory.load_file(tmp_path / "main.xml")
    tree = factory.create_tree()
    assert tree.tick(0) is S
    assert tree.root_blackboard.get("done") is True
    assert factory.create_tree("Other").tick(0) is F


def test_nodes_are_numbered_depth_first_with_subtrees_expanded():
    tree = tree_of(
        '<Sequence><SubTree ID="Sub" inner="{x}"/><AlwaysSuccess name="last"/></Sequence>',
        extra=SUB,
    )
    assert [(uid, path) for uid, path, _ in tree.nodes()] == [
        (1, "Sequence::1"),
        (2, "Sub::2"),
        (3, "Sub::2/Sequence::3"),
        (4, "Sub::2/Script::4"),
        (5, "Sub::2/Script::5"),
        (6, "last"),
    ]


def test_agent_now_and_rng_reach_nodes():
    seen = {}

    def remember(node):
        seen.update(agent=node.agent, now=node.now, draw=node.rng.integers(100))
        return S

    reg = registry()
    reg.register_function("Remember", remember)
    tree = tree_of("<Remember/>", reg, seed=3, agent="the agent")
    tree.tick(2.5)
    assert seen["agent"] == "the agent" and seen["now"] == 2.5
    import numpy as np

    assert seen["draw"] == np.random.default_rng(3).integers(100)
