"""System diagrams as pictures: Drake's Graphviz text rendered by pydot."""

from pathlib import Path

import pydot
from pydrake.systems.framework import Diagram

FORMATS = ("svg", "png", "dot")


def write_diagram(diagram: Diagram, path: Path | str, max_depth: int = 1) -> Path:
    """Writes `diagram` as SVG, PNG or DOT, chosen by the file's suffix."""
    path = Path(path)
    fmt = path.suffix.lstrip(".").lower()
    if fmt not in FORMATS:
        raise ValueError(f"{path}: unknown diagram format '{fmt}' (use .svg, .png or .dot)")
    dot_text = diagram.GetGraphvizString(max_depth=max_depth)
    if fmt == "dot":
        path.write_text(dot_text)
        return path
    (graph,) = pydot.graph_from_dot_data(dot_text)
    path.write_bytes(graph.create(format=fmt))
    return path
