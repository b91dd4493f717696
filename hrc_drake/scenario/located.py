"""Where a mistake `validate` finds is: the Finding (file, line, field or node and port,
message, and the point in the cell it concerns), and the Locator that makes Findings at a
scenario's fields or at tree nodes."""

from dataclasses import dataclass
from pathlib import Path

from hrc_drake.bt import BTError, TreeNode
from hrc_drake.yaml_check import compose, field_path, node_at, read_text

Point = tuple[float, float, float]


@dataclass(frozen=True)
class Finding:
    """One mistake: `file:line: where: message`, and the point in the cell it concerns."""

    file: str
    line: int | None
    where: str
    """A scenario field (`workpieces.types.part.size`) or a tree's `tree 'T', node 'N',
    port 'P'`."""
    message: str
    point: Point | None = None

    def __str__(self) -> str:
        line = f":{self.line}" if self.line else ""
        where = f" {self.where}:" if self.where else ""
        return f"{self.file}{line}:{where} {self.message}"


class Locator:
    """Makes Findings at the scenario's fields (their lines in its file) or at tree nodes."""

    def __init__(self, path: Path):
        self.path = path
        self.root = compose(path, read_text(path, "scenario file"))

    def field(self, names: tuple, message: str, point: Point | None = None) -> Finding:
        node = node_at(self.root, names)
        line = node.start_mark.line + 1 if node is not None else None
        return Finding(str(self.path), line, field_path(names), message, _point(point))

    def read(self, node: TreeNode, port: str, known, message: str, point=None) -> Finding:
        """At the scenario's field when the value `known` (a Known) is one of its own, read
        as it is (a parameter: `pallet_spot` below a pallet's deck was named at the tree's
        node, whose line is not the mistake), with the node said; else at the node."""
        origin = getattr(known, "origin", None)
        if origin is not None and origin.section and not known.via:
            config = node.config
            reader = f"{config.registration_id} '{node.path}' ({config.file}:{config.line})"
            return self.field((origin.section, origin.key), f"{message}: {reader}", point)
        return self.node(node, port, message, point)

    @staticmethod
    def node(node: TreeNode, port: str | None, message: str, point=None) -> Finding:
        return Locator.error(node.error(message, port=port), point)

    @staticmethod
    def error(error: BTError, point=None) -> Finding:
        return Finding(error.file or "", error.line, error.place, error.problem, _point(point))


def _point(point) -> Point | None:
    return None if point is None else tuple(float(v) for v in point)
