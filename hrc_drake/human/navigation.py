"""Walking round things: a 2-D navigation map of the cell and shortest paths on it.

The map is made from the cell's static collision geometry (hrc_drake's mirror of the
station): every anchored box or cylinder that reaches into the body's height band
(`BAND`) is projected onto the floor (its convex outline, with shapely) and grown by the
body's clearance (`CLEARANCE`: half the shoulder width with the arms, or a carried box).
What is left is where the pelvis may go. A path is the shortest polyline through the free
floor: a visibility graph (networkx) over the corners of the grown obstacles, which is
built once per map, plus the start and goal.

A start or goal closer to furniture than the clearance (a place to stand at a table) is
reached straight from the nearest free point; the last leg then approaches it head on.
Walks also keep out of the robot's inner working space (`robot_keep_out`): its arm moves,
so the static map cannot hold it, but nobody walks past under a robot's elbow.
"""

from dataclasses import dataclass
from functools import cached_property
from itertools import combinations
from math import atan2, cos, hypot, sin

import networkx as nx
import numpy as np
from pydrake.geometry import Box, Cylinder
from shapely import prepared
from shapely.geometry import LineString, MultiPoint, Point, Polygon
from shapely.ops import nearest_points, unary_union

from hrc_drake.scene_geometry import anchored_collision_shapes

BAND = (0.03, 1.9)
"""m: heights the body occupies (above the soles' clearance, up to the head)."""
CLEARANCE = 0.3
"""m: from the pelvis's path to an obstacle: half the shoulder width with swinging arms
(0.23 m for the default adult) and a margin; a carried box stays inside it sideways."""
CORNER_MARGIN = 0.01
"""m: paths pass corners this far outside the grown obstacles (not along their edges)."""
STAND_TOLERANCE = 0.01
"""m: a place to stand may touch the cell's geometry by this much (the realism audit's
penetration limit)."""
EXIT_SPACING = 0.05
"""m: a start or goal in the clearance is left through one of the free floor's edge points
this far apart (the nearest that a straight step reaches)."""
SEARCH_STEP, SEARCH_RINGS, SEARCH_DIRECTIONS = 0.05, 10, 16
"""A place to stand that is not clear moves to the nearest clear one on these rings."""
FEET_HEIGHT = 0.1
STANDING = {"feet": (-0.07, 0.21, 0.16), "body": (-0.15, 0.16, 0.23)}
"""m: a standing person's floor outline in their own frame, from the back to the front
along their heading and half as wide: the feet (up to FEET_HEIGHT), the rest of the body."""


ROBOT_KEEP_OUT = 0.5
"""Fraction of the robot's reach round its base axis that walks keep out of."""


def robot_keep_out(base_xy, reach: float) -> Polygon:
    return Point(*base_xy).buffer(ROBOT_KEEP_OUT * reach)


def cell_navigation(plant, inspector, robot_xy, robot_reach: float) -> "NavigationMap":
    """The navigation map of a station: the plant's static geometry, walks kept out of the
    robot's inner working space (what the person walks on, and `validate` checks)."""
    return NavigationMap(
        cell_obstacles(plant, inspector), keep_out=[robot_keep_out(robot_xy, robot_reach)]
    )


@dataclass(frozen=True)
class Obstacle:
    """A piece of the cell's geometry: its floor outline and the heights it spans."""

    name: str
    outline: Polygon
    low: float
    high: float


def cell_obstacles(plant, inspector) -> list[Obstacle]:
    """Floor outlines of the plant's anchored collision geometry within the body's height."""
    found = []
    for name, shape, X_WG in anchored_collision_shapes(plant, inspector):
        corners = _corners(shape)
        if corners is None:
            continue
        world = np.array([X_WG @ c for c in corners])
        if world[:, 2].max() < BAND[0] or world[:, 2].min() > BAND[1]:
            continue
        outline = MultiPoint(world[:, :2].tolist()).convex_hull
        found.append(Obstacle(name, outline, world[:, 2].min(), world[:, 2].max()))
    return found


def _corners(shape) -> np.ndarray | None:
    """The corners of the box round a box or cylinder (in its frame)."""
    if isinstance(shape, Box):
        half = np.array([shape.width(), shape.depth(), shape.height()]) / 2
    elif isinstance(shape, Cylinder):
        half = np.array([shape.radius(), shape.radius(), shape.length() / 2])
    else:
        return None
    signs = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)])
    return signs * half


class NavigationMap:
    """The free floor of one cell and the shortest walks across it."""

    def __init__(self, obstacles: list[Obstacle], clearance: float = CLEARANCE, keep_out=()):
        """`keep_out` are floor polygons walks stay out of besides the obstacles (e.g. where
        the robot's arm swings), though places to stand may lie in them."""
        self.obstacles = obstacles
        self.clearance = clearance
        self.keep_out = unary_union(list(keep_out)) if keep_out else Polygon()
        grown = [o.outline.buffer(clearance, join_style="mitre") for o in obstacles]
        grown += [area.buffer(clearance) for area in keep_out]
        self.blocked = unary_union(grown) if grown else Polygon()
        self._blocked = prepared.prep(self.blocked)
        corners = self.blocked.buffer(CORNER_MARGIN, join_style="mitre")
        self._corners = [p for polygon in _polygons(corners) for p in polygon.exterior.coords[:-1]]

    @cached_property
    def _graph(self) -> nx.Graph:
        """The visibility graph of the grown obstacles' corners (built on first use)."""
        graph = nx.Graph()
        graph.add_nodes_from(range(len(self._corners)))
        for i, j in combinations(range(len(self._corners)), 2):
            if self._clear(self._corners[i], self._corners[j]):
                graph.add_edge(i, j, weight=_length(self._corners[i], self._corners[j]))
        return graph

    def _clear(self, a, b) -> bool:
        return not self._blocked.intersects(LineString([a, b])) if a != b else True

    def free(self, point) -> bool:
        return not self._blocked.contains(Point(point))

    def path(self, start, goal) -> list[tuple[float, float]]:
        """Waypoints strictly between `start` and `goal` of the shortest walk that keeps the
        clearance (a start or goal inside it is left or entered along the shortest leg)."""
        start, goal = tuple(map(float, start[:2])), tuple(map(float, goal[:2]))
        entry, exit_ = self._outside(start), self._outside(goal)
        via = [p for p in (entry,) if p != start]
        tail = [p for p in (exit_,) if p != goal]
        if self._clear(entry, exit_):
            return [*via, *tail]
        graph = self._graph.copy()
        for name, point in (("entry", entry), ("exit", exit_)):
            graph.add_node(name)
            for k, corner in enumerate(self._corners):
                if self._clear(point, corner):
                    graph.add_edge(name, k, weight=_length(point, corner))
        try:
            nodes = nx.shortest_path(graph, "entry", "exit", weight="weight")
        except nx.NetworkXNoPath:
            return [*via, *tail]
        return [*via, *(self._corners[k] for k in nodes[1:-1]), *tail]

    def _outside(self, point) -> tuple[float, float]:
        """The point, or, when it lies in the clearance, the nearest point of the free floor
        that a straight step reaches without crossing the cell's geometry (between a pallet
        and a belt, out along the gap rather than over the belt)."""
        if self.free(point):
            return point
        boundary = self.blocked.buffer(CORNER_MARGIN, join_style="mitre").boundary
        nearest = nearest_points(boundary, Point(point))[0]
        candidates = [nearest, *(boundary.interpolate(d) for d in self._exit_spacing(boundary))]
        candidates.sort(key=Point(point).distance)
        exit_ = next((p for p in candidates if self._passable(point, p)), nearest)
        return (float(exit_.x), float(exit_.y))

    @staticmethod
    def _exit_spacing(boundary) -> np.ndarray:
        return np.arange(0.0, boundary.length, EXIT_SPACING)

    @cached_property
    def _furniture(self):
        """The cell's geometry itself (not grown), prepared for crossing tests."""
        return prepared.prep(unary_union([o.outline for o in self.obstacles]))

    def _passable(self, a, b) -> bool:
        return not self._furniture.intersects(LineString([a, (b.x, b.y)]))

    def clear_spot(self, x: float, y: float, yaw: float) -> tuple[float, float]:
        """The place to stand nearest (x, y) where a person facing `yaw` stands clear of
        the cell's geometry ((x, y) itself when it is clear; it too when none is near),
        not moving into the keep-out areas from outside them."""
        if self.stands_clear(x, y, yaw):
            return x, y
        outside = not self.keep_out.contains(Point(x, y))
        for dx, dy in _rings():
            spot = (x + dx, y + dy)
            if outside and self.keep_out.contains(Point(spot)):
                continue
            if self.stands_clear(*spot, yaw):
                return spot
        return x, y

    def stands_clear(self, x: float, y: float, yaw: float) -> bool:
        overlap = self.standing_overlap(x, y, yaw)
        return overlap is None or overlap[0] <= STAND_TOLERANCE

    def standing_overlap(self, x: float, y: float, yaw: float) -> tuple[float, str] | None:
        """How far (m) a person standing at (x, y) facing `yaw` reaches into the cell's
        geometry, and into what; None when they stand clear."""
        c, s = cos(yaw), sin(yaw)
        worst = None
        for part, (back, front, half) in STANDING.items():
            corners = ((back, -half), (front, -half), (front, half), (back, half))
            outline = Polygon([(x + c * u - s * v, y + s * u + c * v) for u, v in corners])
            for obstacle in self.obstacles:
                low, high = (0.0, FEET_HEIGHT) if part == "feet" else (FEET_HEIGHT, BAND[1])
                if obstacle.high <= low or obstacle.low >= high:
                    continue
                overlap = outline.intersection(obstacle.outline)
                if overlap.area <= 0.0:  # apart, or only touching
                    continue
                depth = _depth(overlap, obstacle.outline)
                if worst is None or depth > worst[0]:
                    worst = (depth, obstacle.name)
        return worst


FLOOR_LEVEL = 1e-6


def stand_problems(navigation: NavigationMap, locations: dict) -> list[tuple[str, str]]:
    """(location name, problem) for every place to stand (a location at floor level) where
    a person standing would reach into the cell's geometry."""
    problems = []
    for name, X in locations.items():
        x, y, z = X.translation()
        if abs(z) > FLOOR_LEVEL:
            continue
        R = X.rotation().matrix()
        yaw = atan2(R[1, 0], R[0, 0])
        overlap = navigation.standing_overlap(x, y, yaw)
        if overlap is not None and overlap[0] > STAND_TOLERANCE:
            depth, what = overlap
            problems.append(
                (name, f"a person standing here reaches {depth:.2f} m into {what}: move it")
            )
    return problems


def _rings():
    """Offsets to try round a place to stand that is not clear, nearest first."""
    angles = np.arange(SEARCH_DIRECTIONS) * 2 * np.pi / SEARCH_DIRECTIONS
    for radius in np.arange(1, SEARCH_RINGS + 1) * SEARCH_STEP:
        for angle in angles:
            yield radius * cos(angle), radius * sin(angle)


def _depth(overlap, outline: Polygon) -> float:
    """How far the overlap reaches into the outline (its deepest point's distance to the
    outline's boundary)."""
    points = [Point(p) for polygon in _polygons(overlap) for p in polygon.exterior.coords]
    return max(outline.exterior.distance(p) for p in points)


def _polygons(geometry) -> list[Polygon]:
    """The polygons of a shapely geometry (an intersection may also hold lines, points)."""
    if geometry.is_empty:
        return []
    return [g for g in getattr(geometry, "geoms", [geometry]) if isinstance(g, Polygon)]


def _length(a, b) -> float:
    return hypot(b[0] - a[0], b[1] - a[1])
