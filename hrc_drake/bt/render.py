"""Drawing a tree with Graphviz (pydot): SVG, PNG or DOT, by file extension."""

from __future__ import annotations

import os
from pathlib import Path

import pydot

from .observers import NodeCounters
from .status import Status
from .tree import Tree

STATUS_COLORS = {
    Status.IDLE: "white",
    Status.RUNNING: "#ffd966",
    Status.SUCCESS: "#93c47d",
    Status.FAILURE: "#e06666",
    Status.SKIPPED: "#cccccc",
}
SHAPES = {
    "Control": "box",
    "Decorator": "hexagon",
    "SubTree": "component",
    "Action": "box",
    "Condition": "ellipse",
}


def _heat(fraction: float) -> str:
    """White (never ticked) to orange (ticked most)."""
    green_blue = round(255 * (1 - 0.7 * fraction))
    return f"#ff{green_blue:02x}{round(green_blue * 0.6):02x}"


def tree_graph(
    tree: Tree, color_by: str | None = None, counters: NodeCounters | None = None
) -> pydot.Dot:
    """Graph of the tree. ``color_by``: None, "status" (last status seen by
    ``counters``, else the current one) or "ticks" (needs ``counters``)."""
    if color_by == "ticks" and counters is None:
        raise ValueError("color_by='ticks' needs the NodeCounters that observed the run")
    graph = pydot.Dot(graph_type="digraph", rankdir="TB")
    counts = counters.counts() if counters is not None else {}
    most_ticks = max((count.ticks for count in counts.values()), default=0) or 1
    for uid, _, node in tree.nodes():
        label = (
            node.registration_id
            if node.name == node.registration_id
            else f"{node.registration_id}\\n{node.name}"
        )
        attributes = {
            "shape": SHAPES.get(node.kind, "box"),
            "style": "filled,rounded",
            "fillcolor": "white",
            "fontname": "Helvetica",
        }
        count = counts.get(uid)
        if count is not None:
            label += f"\\nticks {count.ticks}  ok {count.successes}  fail {count.failures}"
        if color_by == "status":
            status = count.last_status if count is not None else node.status
            attributes["fillcolor"] = STATUS_COLORS[status]
        elif color_by == "ticks":
            attributes["fillcolor"] = _heat(count.ticks / most_ticks)
        graph.add_node(pydot.Node(str(uid), label=f'"{label}"', **attributes))
        for child in node.children_nodes():
            graph.add_edge(pydot.Edge(str(uid), str(child.uid)))
    return graph


def render_tree(
    tree: Tree,
    path: str | os.PathLike,
    color_by: str | None = None,
    counters: NodeCounters | None = None,
) -> Path:
    """Write the tree drawing to ``path`` (.svg, .png or .dot)."""
    path = Path(path)
    graph = tree_graph(tree, color_by, counters)
    fmt = path.suffix.lstrip(".").lower() or "svg"
    if fmt == "dot":
        path.write_text(graph.to_string())
    else:
        path.write_bytes(graph.create(format=fmt))
    return path
