"""Walks the tree makes that go a long way round because a gap between two pieces of the
cell is a little narrower than the walking person: a packing cell of our own with its
shelf 10 cm closer to the table sent the person 7.8 m round behind the conveyor for a
3.6 m walk (17.7 s where 7.9 s were meant), and neither validate nor the run said so.

A walk is a detour when the navigation map's way (hrc_drake.human.navigation) is more than
DETOUR_RATIO times the straight way and more than DETOUR_LONGER longer. A person a little
slimmer (SLIMMER) is then asked to walk it: when their way is much shorter, the gap it
passes through between two pieces of the cell is what keeps this person out, and validate
names it with its width and the width the map needs there. A detour round a long table
with no such gap is meant, and so is one round the robot's inner working space (the
slimmer person keeps out of it as far as this one): nothing is said.
"""

from collections.abc import Callable, Iterator
from dataclasses import dataclass
from functools import cached_property
from itertools import combinations, pairwise

import numpy as np
from shapely import affinity
from shapely.geometry import LineString, Polygon
from shapely.ops import nearest_points

from hrc_drake.bt import TreeNode
from hrc_drake.human.navigation import (
    CORNER_MARGIN,
    WALK_MARGIN,
    NavigationMap,
    NoWay,
    grown_outline,
)
from hrc_drake.known_values import Known
from hrc_drake.nodes.person import ActorCarry, ActorMovement
from hrc_drake.scenario.located import Finding, Locator
from hrc_drake.scenario.tree_ways import UNKNOWN, walk_before

DETOUR_RATIO = 1.5
"""A walk this many times the straight way may be a detour..."""
DETOUR_LONGER = 2.0
"""m: ...when it is also this much longer (a few steps round a corner are not)."""
SLIMMER = 0.8
"""A person this fraction of the height (the body's widths scale with it) is asked to walk
the same way: the gaps a little too narrow for this person open for them."""

WalkEnd = Callable[[Known], tuple[float, float] | None]
"""A walk's known target to where the walk ends (None: not known, or no room there)."""


@dataclass(frozen=True)
class Piece:
    """A piece of the cell as walks keep clear of it: its name, floor outline, the
    clearance walks keep from it and the outline grown by that."""

    name: str
    outline: Polygon
    clearance: float
    grown: Polygon


class Detours:
    """The detours of one navigation map (the slimmer person's map made when needed)."""

    def __init__(self, navigation: NavigationMap):
        self.navigation = navigation

    @cached_property
    def _slimmer(self) -> NavigationMap:
        """The map of a person SLIMMER times as tall, who keeps as far from the robot's
        inner working space as this person does (walking round the robot is meant)."""
        navigation = self.navigation
        keep_out = []
        if not navigation.keep_out.is_empty:
            nearer = (1.0 - SLIMMER) * (navigation.keep_out_clearance - WALK_MARGIN)
            keep_out.append(navigation.keep_out.buffer(nearer))
        height = SLIMMER * navigation.height
        return NavigationMap(navigation.obstacles, keep_out=keep_out, height=height)

    @cached_property
    def _pieces(self) -> list[Piece]:
        navigation = self.navigation
        clearances = [navigation.clearance(o) for o in navigation.obstacles]
        return [
            Piece(o.name, o.outline, c, grown_outline(o.outline, c))
            for o, c in zip(navigation.obstacles, clearances, strict=True)
        ]

    def problem(self, start, goal, walk: str = "walk") -> tuple[str, tuple | None]:
        """Why the `walk` (or carry) from `start` to `goal` (x, y) goes a long way round
        ("" when it does not): the lengths and the gap a little too narrow for this person,
        and the middle of that gap (x, y, 0), where a view of the cell marks it."""
        try:
            way = [start, *self.navigation.path(start, goal), goal]
        except NoWay:
            return "", None  # walk_problem says so
        straight, length = _length([start, goal]), _length(way)
        if length <= DETOUR_RATIO * straight or length - straight <= DETOUR_LONGER:
            return "", None
        try:
            slim = [start, *self._slimmer.path(start, goal), goal]
        except NoWay:
            return "", None
        if _length(slim) > length - DETOUR_LONGER:
            return "", None
        gap = self._gap(LineString(slim))
        if gap is None:
            return "", None
        message = (
            f"the {walk} from {_xy(start)} to {_xy(goal)} goes round: {length:.1f} m for "
            f"{straight:.1f} m straight; {_gap_words(gap)}"
        )
        middle = gap[3]
        return message, (middle.x, middle.y, 0.0)

    def closing_gap(self, start, goal) -> str:
        """The gap a little too narrow for this person that closes every way from `start`
        to `goal`, where a slimmer person walks through ("": none such; a user's carry round
        a bin was said to have no way, naming no gap)."""
        try:
            slim = [start, *self._slimmer.path(start, goal), goal]
        except NoWay:
            return ""
        gap = self._gap(LineString(slim))
        return "" if gap is None else _gap_words(gap)

    def _gap(self, way: LineString):
        """The gap the slimmer person's `way` passes through that is narrowest for this
        person (its pieces' names, width, the width the map needs there and its middle), or
        None; its pieces lie nearer the way than the widest gap the map closes."""
        widest = 2 * (max((p.clearance for p in self._pieces), default=0.0) + CORNER_MARGIN)
        near = [p for p in self._pieces if p.outline.distance(way) < widest]
        found = []
        for a, b in combinations(near, 2):
            if a.name == b.name:
                continue
            width = a.outline.distance(b.outline)
            across = LineString(nearest_points(a.outline, b.outline))
            if width <= 0.0 or not across.intersects(way):
                continue
            needed = width + _shift_to_open(a, b, across)
            if needed > width:
                middle = across.interpolate(0.5, normalized=True)
                found.append(((a.name, b.name), width, needed, middle))
        return max(found, key=lambda gap: gap[2] - gap[1], default=None)


def _gap_words(gap) -> str:
    (a, b), width, needed, _ = gap
    return f"the gap between '{a}' and '{b}' is {width:.2f} m, {needed:.2f} m needed"


def _shift_to_open(a: Piece, b: Piece, across: LineString, steps: int = 20) -> float:
    """How far `b` must move away from `a` (along the line `across` between their nearest
    points) for the map to leave a way between them: their grown outlines, and the margin
    walks keep from corners, apart."""
    (x0, y0), (x1, y1) = across.coords
    direction = np.array([x1 - x0, y1 - y0]) / across.length
    first = a.grown.buffer(CORNER_MARGIN)
    second = b.grown.buffer(CORNER_MARGIN)
    if not first.intersects(second):
        return 0.0
    low, high = 0.0, 2 * (a.clearance + b.clearance + 2 * CORNER_MARGIN)
    for _ in range(steps):
        middle = (low + high) / 2
        moved = affinity.translate(second, *(middle * direction))
        low, high = (middle, high) if first.intersects(moved) else (low, middle)
    return high


def detour_findings(
    nodes: list[TreeNode],
    known: dict[tuple[int, str], list[Known]],
    walk_end: WalkEnd,
    start,
    detours: Detours,
) -> Iterator[Finding]:
    """A Finding at each walk (ActorMovement, ActorCarry) that goes a long way round from
    where the person stands before it (the last walk's end, or their `start`) because a gap
    is a little too narrow; walks from where the person stands uncertainly are not judged."""
    parents = {id(child): node for node in nodes for child in node.children_nodes()}
    for node in nodes:
        if not isinstance(node, ActorMovement):
            continue
        before = walk_before(node, parents)
        if before is UNKNOWN:
            continue
        values = [None] if before is None else known.get((id(before), "target"), ())
        starts = [tuple(start) if v is None else walk_end(v) for v in values]
        for value in known.get((id(node), "target"), ()):
            goal = walk_end(value)
            walk = "carry" if isinstance(node, ActorCarry) else "walk"
            problems = [detours.problem(s, goal, walk) for s in starts if s and goal]
            problem, gap = next(((p, g) for p, g in problems if p), ("", None))
            if problem:
                yield Locator.node(node, "target", f"{value}: {problem}", gap)


def _length(points) -> float:
    return sum(float(np.hypot(b[0] - a[0], b[1] - a[1])) for a, b in pairwise(points))


def _xy(p) -> str:
    return f"[{p[0]:.2f}, {p[1]:.2f}]"
