"""Rendering with pydot and the TreeNodesModel export for Groot2."""

import xml.etree.ElementTree as ElementTree

from hrc_drake.bt import (
    InputPort,
    NodeCounters,
    OutputPort,
    StatefulActionNode,
    Status,
    register_type,
    render_tree,
    tree_graph,
    tree_nodes_model_xml,
)
from tests.bt.bt_helpers import registry, ticks, tree_of


class Pose2(tuple):
    @classmethod
    def from_string(cls, text):
        return cls(float(part) for part in text.split(";"))


register_type(Pose2, Pose2.from_string, "Pose2")


class MoveTo(StatefulActionNode):
    """Move to a target pose."""

    ports = (
        InputPort("target", Pose2, description="where to go"),
        InputPort("speed", float, 0.5),
        OutputPort("reached", Pose2),
    )

    def on_start(self):
        self.set_output("reached", self.get_input("target"))
        return Status.SUCCESS

    def on_running(self):
        return Status.SUCCESS


def test_tree_nodes_model_lists_custom_nodes_with_ports():
    reg = registry()
    reg.register(MoveTo)
    root = ElementTree.fromstring(tree_nodes_model_xml(reg))
    move = root.find("TreeNodesModel/Action[@ID='MoveTo']")
    ports = [(p.tag, p.get("name"), p.get("type"), p.get("default"), p.text) for p in move]
    assert ports == [
        ("input_port", "target", "Pose2", None, "where to go"),
        ("input_port", "speed", "double", "0.5", None),
        ("output_port", "reached", "Pose2", None, None),
    ]
    assert root.find("TreeNodesModel/Control[@ID='Sequence']") is None
    assert (
        ElementTree.fromstring(tree_nodes_model_xml(reg, include_builtin=True)).find(
            "TreeNodesModel/Control[@ID='Sequence']"
        )
        is not None
    )


def test_registered_type_is_read_from_xml_literal():
    reg = registry()
    reg.register(MoveTo)
    tree = tree_of('<MoveTo target="1;2;0.5" reached="{p}"/>', reg)
    tree.tick(0)
    assert tree.root_blackboard.get("p") == (1.0, 2.0, 0.5)


def test_render_svg_png_and_colours(tmp_path):
    tree = tree_of('<Sequence><AlwaysSuccess/><AsyncMock name="A"/></Sequence>')
    counters = NodeCounters()
    tree.add_observer(counters)
    ticks(tree, 2)
    svg = render_tree(tree, tmp_path / "t.svg", color_by="status", counters=counters)
    assert "<svg" in svg.read_text()
    png = render_tree(tree, tmp_path / "t.png", color_by="ticks", counters=counters)
    assert png.read_bytes().startswith(b"\x89PNG")
    dot = tree_graph(tree, color_by="status").to_string()
    assert "AsyncMock\\nA" in dot and "#ffd966" in dot  # A is RUNNING
