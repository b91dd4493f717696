"""System diagrams as pictures: Drake's Graphviz text rendered by Graphviz's `dot`, given
the text as it is (parsing it into pydot first took a second and drew the same bytes).

Drake names each system in its Graphviz text by the system's id (a process-wide counter, so
it depends on what the process built before) and lists a diagram's connections in the order
of its input ports' addresses in memory. `canonical_dot` numbers the systems by where they
first appear and sorts the connections, so the same diagram draws the same bytes in every
process.
"""

import re
import subprocess
from pathlib import Path

from pydrake.systems.framework import Diagram

FORMATS = ("svg", "png", "dot")
SYSTEM_ID = re.compile(r"(?<![A-Za-z0-9_])(_|clusters|cluster|s)(\d+)")
"""Where Drake's Graphviz text names a system by its id: the graph (`_N`), its clusters
(`clusterNdiagram`, `clustersNout`...) and its nodes and ports (`sN`, `sNout`, `sN:y0`)."""
EDGE = " -> "


def canonical_dot(dot_text: str) -> str:
    """`dot_text` with the systems numbered by first appearance and every run of connection
    lines sorted."""
    numbers: dict[str, int] = {}

    def renumbered(match: re.Match) -> str:
        number = numbers.setdefault(match.group(2), len(numbers))
        return f"{match.group(1)}{number}"

    lines = SYSTEM_ID.sub(renumbered, dot_text).split("\n")
    edges = [k for k, line in enumerate(lines) if EDGE in line]
    for k, line in zip(edges, sorted(lines[k] for k in edges), strict=True):
        lines[k] = line
    return "\n".join(lines)


def write_diagram(diagram: Diagram, path: Path | str, max_depth: int = 1) -> Path:
    """Writes `diagram` as SVG, PNG or DOT, chosen by the file's suffix."""
    path = Path(path)
    fmt = path.suffix.lstrip(".").lower()
    if fmt not in FORMATS:
        raise ValueError(f"{path}: unknown diagram format '{fmt}' (use .svg, .png or .dot)")
    dot_text = canonical_dot(diagram.GetGraphvizString(max_depth=max_depth))
    if fmt == "dot":
        path.write_text(dot_text)
        return path
    drawn = subprocess.run(["dot", f"-T{fmt}"], input=dot_text.encode(), capture_output=True)
    if drawn.returncode != 0:
        raise RuntimeError(f"{path}: Graphviz's dot failed: {drawn.stderr.decode().strip()}")
    path.write_bytes(drawn.stdout)
    return path
