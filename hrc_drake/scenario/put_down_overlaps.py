"""What the robot's tree sets down into an object lying there, known before a run: the part
a RobotRelease lets go of (hrc_drake.scenario.robot_put_downs) against the objects the
scenario places at the start and those the tree's earlier put-downs left, as upright
solids. A user's palletizing cell had a slot 10 cm from its neighbour and a second layer at
the first layer's height; validate said ok, and the run refused the move after minutes of
simulation ("... would be 5.0 cm into carton 2 resting there").

How the tool took the part is not known before a run (a target without a rotation leaves
the tool free to turn, and the run turns what it holds by quarter turns to fit beside
the objects, hrc_drake.motion.planner), so a put-down is said only where the part lies
inside the object whichever way either of them is turned. Nor is it said where what lies
there may be gone: an object the tree may look for (a NextObject or CountObjects whose
area is not known or holds it; a CountObjects is how a tree waits for a place to be
cleared), or may remove or move (any DespawnObject or MoveObject), at the start or since
the put-down; or where the tree's way there is not known (a choice, a loop's earlier
rounds, a script's pose)."""

import math
from collections.abc import Iterator
from dataclasses import dataclass
from functools import partial
from pathlib import Path

import numpy as np

from hrc_drake.areas import Area
from hrc_drake.bt import TreeNode
from hrc_drake.known_values import Known, step_of
from hrc_drake.nodes.objects import CountObjects, DespawnObject, MoveObject, NextObject
from hrc_drake.nodes.robot import RobotRelease, tool_pose
from hrc_drake.scenario.cell_findings import InitialObject
from hrc_drake.scenario.located import Finding
from hrc_drake.scenario.reach_from_stand import point_text
from hrc_drake.scenario.robot_put_downs import Locate, put_down_of
from hrc_drake.scenario.tree_ways import all_before, last_before, parents_of
from hrc_drake.scene_geometry import OBJECT_DEPTH_LIMIT
from hrc_drake.tree_types import AreaRef, Pose
from hrc_drake.workpieces.geometry import Solid, edge_normals, yaw_of
from hrc_drake.yaml_check import field_path

HEADING_STEP = math.radians(1.0)
"""The headings a part whose turn is not known is tried at, this far apart."""
HEADINGS = np.arange(0.0, math.pi, HEADING_STEP)
"""A half turn of them: a box's outline (and a cylinder's polygon) turned by one is the same."""
TAKERS = NextObject | CountObjects | DespawnObject | MoveObject
"""Nodes after which an object may be gone: those that look for it in an area (the tree
takes it, or waits for it to be taken), and those that remove or move an object."""
UPRIGHT = 1e-6
"""How far from 1 the cosine of a solid's tilt may be and still be judged by its outline."""


@dataclass(frozen=True)
class Lying:
    """An upright solid where validate knows it lies, at one of `headings` (its yaw, one
    when known), and what messages call it."""

    label: str
    solid: Solid
    centre: np.ndarray
    headings: np.ndarray

    @property
    def bottom(self) -> float:
        return float(self.centre[2]) - self.solid.height / 2

    @property
    def top(self) -> float:
        return float(self.centre[2]) + self.solid.height / 2

    def outlines(self) -> np.ndarray:
        """Its outline at each of its headings, in the floor plane: (headings, n, 2)."""
        c, s = np.cos(self.headings), np.sin(self.headings)
        turns = np.stack([np.stack([c, s], -1), np.stack([-s, c], -1)], -2)
        return self.solid.outline() @ turns + self.centre[:2]

    def reach(self) -> float:
        """How far its outline reaches from its centre."""
        return float(np.linalg.norm(self.solid.outline(), axis=1).max())


def overlap_findings(
    nodes: list[TreeNode],
    known: dict,
    resolve,
    solids: dict[str, Solid],
    initial: list[InitialObject],
    areas: dict[str, Area],
    locate: Locate,
) -> Iterator[Finding]:
    """A Finding at each put-down's target where the part the robot lets go of would lie
    deeper than OBJECT_DEPTH_LIMIT inside an object lying there at the start (`initial`)
    or left by an earlier put-down (`resolve`: a Pose to the scenario's, None when it names
    no location; `solids`: each object type's shape; `areas`: the scenario's)."""
    parents = parents_of(nodes)
    takers = [n for n in nodes if isinstance(n, TAKERS)]
    may_take = partial(_may_take, known, areas)
    at_start = [
        lying
        for obj in initial
        if (lying := _lying_at_start(obj)) is not None
        and not any(may_take(taker, lying.centre) for taker in takers)
    ]
    put_downs = _PutDowns(parents, known, resolve, solids)
    for release in put_downs.releases(nodes):
        move, kind = put_downs.of[id(release)]
        there = at_start + put_downs.left_before(release, may_take)
        value, part = put_downs.placed(release)
        found = _deepest_inside(part, there) if part is not None else None
        if found is not None:
            tip = part.centre + [0, 0, part.solid.height / 2]
            yield locate(move, "target", value, _inside(value, move, kind, tip, *found), tip)


def _deepest_inside(part: Lying, there: list[Lying]) -> tuple[str, float] | None:
    """(what, how deep) of the object `part` lies deepest inside, turned any way, when
    deeper than the limit (`_limit`); else None."""
    deep = [(o.label, d) for o in there if (d := _depth(part, o)) > _limit(part, o)]
    return max(deep, key=lambda found: found[1], default=None)


class _PutDowns:
    """The robot's put-downs whose move and part are known, and where they put the part."""

    def __init__(self, parents: dict, known: dict, resolve, solids: dict[str, Solid]):
        self.parents = parents
        self.known = known
        self.resolve = resolve
        self.solids = solids
        self.of: dict[int, tuple[TreeNode, str]] = {}
        """By id(release): its move and the type of what it lets go of."""
        self.nodes: list[TreeNode] = []
        """The releases in `of`, in the tree's order."""

    def releases(self, nodes: list[TreeNode]) -> list[TreeNode]:
        """The RobotReleases whose move and part of a known shape are known."""
        for release in (n for n in nodes if isinstance(n, RobotRelease)):
            found = put_down_of(release, self.parents, self.known)
            if found is not None and found[1] in self.solids:
                self.of[id(release)] = found
                self.nodes.append(release)
        return self.nodes

    def part(self, kind: str, value: Known) -> Lying | None:
        """The part let go of with its top at the target `value`, the tool pointing down,
        at any heading (None: not a known location, or the tool not pointing down)."""
        pose = self.resolve(value.value) if isinstance(value.value, Pose) else None
        if pose is None:
            return None
        target, _ = tool_pose(pose)
        if target.rotation().matrix()[2, 2] > -1 + UPRIGHT:
            return None
        solid = self.solids[kind]
        centre = target.translation() + [0, 0, -solid.height / 2]
        return Lying("", solid, centre, HEADINGS)

    def left_before(self, release: TreeNode, may_take) -> list[Lying]:
        """The parts the put-downs that surely ran before `release` left, but those a node
        that may have run since may take away (`may_take(node, centre)`)."""
        left = []
        for earlier in self.nodes:
            if last_before(release, self.parents, partial(_is, earlier)) is not earlier:
                continue
            value, part = self.placed(earlier)
            if part is not None and not self._taken_since(earlier, release, may_take, part):
                move, kind = self.of[id(earlier)]
                label = f"the {kind} put down at {_written(value, move)}"
                left.append(Lying(label, part.solid, part.centre, part.headings))
        return left

    def placed(self, release: TreeNode) -> tuple[Known | None, Lying | None]:
        """The one known target of the move before `release`, and the part it lets go of
        there ((None, None): no one target known, as where a loop counts its slots)."""
        move, kind = self.of[id(release)]
        values = self.known.get((id(move), "target"), ())
        if len(values) != 1:
            return None, None
        return values[0], self.part(kind, values[0])

    def _taken_since(self, earlier: TreeNode, release: TreeNode, may_take, part: Lying) -> bool:
        """Whether a node that may have run after `earlier` and before `release` may take
        away what `earlier` left (`part`)."""
        before = {id(n) for n in all_before(earlier, self.parents, _taker)}
        since = all_before(release, self.parents, _taker)
        return any(may_take(n, part.centre) for n in since if id(n) not in before)


def _taker(node: TreeNode) -> bool:
    return isinstance(node, TAKERS)


def _may_take(known: dict, areas: dict[str, Area], node: TreeNode, centre) -> bool:
    """Whether `node` (one of TAKERS) may take away an object whose centre is at `centre`:
    it looks in an area that holds it or is not known, or it removes or moves an object."""
    if not isinstance(node, NextObject | CountObjects):
        return True
    given = known.get((id(node), "area"), ())
    names = [a.value.name if isinstance(a.value, AreaRef) else None for a in given]
    if not names or any(n not in areas for n in names):
        return True
    return any(areas[n].contains(centre[:2]) for n in names)


def _lying_at_start(obj: InitialObject) -> Lying | None:
    """An object the scenario places at the start, at its heading (None: not upright)."""
    R = obj.pose.rotation().matrix()
    if R[2, 2] < 1 - UPRIGHT:
        return None
    label = f"the {obj.label} lying there at the start ({field_path(obj.names)})"
    heading = np.array([yaw_of(obj.pose.rotation())])
    return Lying(label, obj.solid, obj.pose.translation(), heading)


def _depth(part: Lying, other: Lying) -> float:
    """How deep `part` lies inside `other` at the headings that put it least deep: the
    least of their overlap in height and the least way apart in the floor plane (0: apart
    at some)."""
    height = min(part.top, other.top) - max(part.bottom, other.bottom)
    if height <= 0:
        return 0.0
    a, b = part.outlines()[:, None], other.outlines()[None, :]
    shape = np.broadcast_shapes(a.shape[:2], b.shape[:2])
    axes = np.concatenate(
        [np.broadcast_to(edge_normals(p), (*shape, p.shape[2], 2)) for p in (a, b)], axis=2
    )
    along_a = np.einsum("...nd,...kd->...nk", a, axes)
    along_b = np.einsum("...nd,...kd->...nk", b, axes)
    overlap = np.minimum(
        along_a.max(axis=-2) - along_b.min(axis=-2), along_b.max(axis=-2) - along_a.min(axis=-2)
    )
    apart = overlap.min(axis=-1)
    return float(max(min(height, apart.min()), 0.0))


def _limit(part: Lying, other: Lying) -> float:
    """OBJECT_DEPTH_LIMIT, and how much less deep either may lie turned between two of the
    headings tried (a vertex turned by an angle moves at most its reach times it)."""
    free = [s.reach() for s in (part, other) if len(s.headings) > 1]
    return OBJECT_DEPTH_LIMIT + sum(free) * HEADING_STEP / 2


def _written(value: Known, move: TreeNode) -> str:
    """A target and the line that gives it: a SubTree's port of a slot, the move's own;
    else the move that reads it."""
    node = value.origin.node
    if node is None or value.via:
        return f"{value} by {step_of(move)}"
    return f"{value} ({Path(node.config.file).name}:{node.config.line})"


def _inside(value: Known, move: TreeNode, kind: str, tip, what: str, depth: float) -> str:
    return (
        f"{_written(value, move)} at {point_text(tip)}: the {kind} the robot lets go of there "
        f"(its top at the tool) would lie {100 * depth:.1f} cm inside {what}, turned any way "
        f"about the tool's axis (limit {100 * OBJECT_DEPTH_LIMIT:.0f} cm): move the target "
        "beside it or onto it"
    )


def _is(node: TreeNode, other: TreeNode) -> bool:
    return other is node
