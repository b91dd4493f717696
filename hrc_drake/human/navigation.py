"""Walking round things: a 2-D navigation map of the cell, shortest paths on it, and places
to stand with room.

The map is made from the cell's static collision geometry (hrc_drake's mirror of the
station): every anchored box or cylinder that reaches into the body's height band
(`BAND`) is projected onto the floor (its convex outline, with shapely). The body is
known by its floor outline at the heights an obstacle spans (`BODY`, measured from the
body's collision geometry: standing, stepping round on the spot, walking): each obstacle
is grown by the walking body's half-width at its heights and a margin (`clearance`), and
what is left is where the pelvis may go. A path is the shortest polyline through the free
floor: a visibility graph (networkx) over the corners of the grown obstacles, built once
per map, plus the start and goal.

A start or goal in the clearance (a place to stand at a table) is left or reached by legs
that keep the walking body out of the furniture beyond what it already touches standing
there: the body swept along the leg, less the discs round its ends, stays out. Where no
such path exists (a start with no room at all), the walk first steps out by the shortest
straight step that crosses no furniture (and in by one at a goal only where it must: a
person leaving a pallet stacked with cartons stopped to step the last 3 cm into the place
at a table they could walk straight to); where no path exists at all, there is no walk:
a path never crosses the cell. Walks also keep out of the robot's inner working space
(`robot_keep_out`): its arm moves, so the static map cannot hold it, but nobody walks past
under a robot's elbow.

A place to stand works when the person can stand there facing its way and step round on
the spot without any body part entering the cell's geometry (`stand_problem`); the
planner moves a place that does not to the nearest that does, and `hrc-drake validate`
names it.

Longer than 400 lines: the walks and the places to stand are asked of one map, which holds
the body's slices and the obstacles grown by them that both use.
"""

from dataclasses import dataclass
from functools import cached_property
from itertools import combinations
from math import cos, hypot, sin

import networkx as nx
import numpy as np
import shapely
from pydrake.geometry import Box, Cylinder
from shapely import prepared
from shapely.geometry import LineString, MultiPoint, Point, Polygon
from shapely.ops import nearest_points, unary_union

from hrc_drake.human.anthropometry import DEFAULT_HEIGHT
from hrc_drake.scene_geometry import anchored_collision_shapes

BAND = (0.03, 1.9)
"""m: heights the body occupies (above the soles' clearance, up to the head)."""


@dataclass(frozen=True)
class BodySlice:
    """The body between two heights as seen from above, in its own frame (x forward):
    standing at ease (a rectangle from `back` to `front`, `side` either way), stepping round
    on the spot (a disc of radius `turning`) and walking (`walking` either side of the
    pelvis's path)."""

    low: float
    high: float
    back: float
    front: float
    side: float
    turning: float
    walking: float

    def scaled(self, factor: float) -> "BodySlice":
        return BodySlice(*(factor * value for value in vars(self).values()))


BODY = (
    BodySlice(0.0, 0.1, -0.08, 0.21, 0.16, 0.26, 0.17),
    BodySlice(0.1, 0.5, -0.06, 0.14, 0.19, 0.26, 0.19),
    BodySlice(0.5, 1.1, -0.13, 0.15, 0.34, 0.33, 0.34),
    BodySlice(1.1, 1.9, -0.13, 0.13, 0.30, 0.29, 0.29),
)
"""m: the default adult (DEFAULT_HEIGHT) by height, from its collision geometry over the
idle clip, turns on the spot of 45-180° and a straight walk, rounded up by about a
centimetre (docs/realism.md; tests/human/test_navigation.py measures them): feet, shins
and knees, hands, hips and forearms, chest, shoulders and head. Other heights scale."""
WALK_MARGIN = 0.03
"""m: walks keep this much more than the walking body's half-width from obstacles (the
body leans into the heading's turn at a corner, the pelvis sways)."""
CORNER_MARGIN = 0.01
"""m: paths pass corners this far outside the grown obstacles (not along their edges)."""
STAND_TOLERANCE = 0.01
"""m: a place to stand may touch the cell's geometry by this much (the realism audit's
penetration limit)."""
ON_THE_LINE = 1e-6
"""m: a point this close to the grown obstacles is in their clearance (on its line: a walk
from there leaves it as from inside)."""
EXIT_SPACING = 0.05
"""m: a start or goal with no room is left through one of the free floor's edge points
this far apart (the nearest that a straight step reaches)."""
KEPT_MAPS = 8
"""Maps with extra obstacles (`with_obstacles`) kept per map."""
SEARCH_STEP, SEARCH_RINGS, SEARCH_DIRECTIONS = 0.05, 15, 16
"""A place to stand that does not work moves to the nearest that does on these rings."""
ROBOT_KEEP_OUT = 0.5
"""Fraction of the robot's reach round its base axis that walks keep out of."""


def robot_keep_out(base_xy, reach: float) -> Polygon:
    return Point(*base_xy).buffer(ROBOT_KEEP_OUT * reach)


def cell_navigation(
    plant, inspector, robot_xy, robot_reach: float, height: float = DEFAULT_HEIGHT
) -> "NavigationMap":
    """The navigation map of a station for a person of `height`: the plant's static
    geometry, walks kept out of the robot's inner working space (what the person walks on,
    and `validate` checks)."""
    return NavigationMap(
        cell_obstacles(plant, inspector),
        keep_out=[robot_keep_out(robot_xy, robot_reach)],
        height=height,
    )


class NoWay(ValueError):
    """No walk between two points keeps the body out of the cell's geometry."""


@dataclass(frozen=True)
class Obstacle:
    """A piece of the cell's geometry: its floor outline and the heights it spans."""

    name: str
    outline: Polygon
    low: float
    high: float


@dataclass(frozen=True)
class StandProblem:
    """Why a place to stand does not work: what the person does there (standing, turning),
    what of the cell they reach into and how far (m)."""

    doing: str
    what: str
    depth: float

    def __str__(self) -> str:
        return f"a person {self.doing} here reaches {self.depth:.2f} m into {self.what}"


def cell_obstacles(plant, inspector) -> list[Obstacle]:
    """Floor outlines of the plant's anchored collision geometry within the body's height."""
    found = []
    for name, shape, X_WG in anchored_collision_shapes(plant, inspector):
        corners = _corners(shape)
        if corners is None:
            continue
        world = np.array([X_WG @ c for c in corners])
        if not in_band(world[:, 2].min(), world[:, 2].max()):
            continue
        outline = MultiPoint(world[:, :2].tolist()).convex_hull
        found.append(Obstacle(name, outline, world[:, 2].min(), world[:, 2].max()))
    return found


def box_obstacle(box) -> Obstacle:
    """A box (centre, heading, extents along its own axes, name: a human.messages.Box) as
    an obstacle: its floor outline and the heights it spans."""
    c, s = cos(box.yaw), sin(box.yaw)
    half_x, half_y, half_z = (extent / 2 for extent in box.size)
    x, y, z = box.center
    corners = [
        (x + c * u - s * v, y + s * u + c * v)
        for u, v in ((-half_x, -half_y), (half_x, -half_y), (half_x, half_y), (-half_x, half_y))
    ]
    return Obstacle(box.name, Polygon(corners), z - half_z, z + half_z)


def in_band(low: float, high: float) -> bool:
    """Whether something spanning these heights reaches into the body's height band."""
    return high >= BAND[0] and low <= BAND[1]


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
    """The free floor of one cell, the shortest walks across it and its places to stand,
    for a person of `height`."""

    def __init__(self, obstacles: list[Obstacle], keep_out=(), height: float = DEFAULT_HEIGHT):
        """`keep_out` are floor polygons walks stay out of besides the obstacles (e.g. where
        the robot's arm swings), though places to stand may lie in them."""
        self.obstacles = obstacles
        self.height = height
        self.body = tuple(s.scaled(height / DEFAULT_HEIGHT) for s in BODY)
        self._reach = [self._body_at(o.low, o.high) for o in obstacles]
        self._keep_out_areas = tuple(keep_out)
        self.keep_out = unary_union(list(keep_out)) if keep_out else Polygon()
        self.keep_out_clearance = max(s.walking for s in self.body) + WALK_MARGIN
        grown = [grown_outline(o.outline, self.clearance(o)) for o in obstacles] + [
            area.buffer(self.keep_out_clearance) for area in keep_out
        ]
        self.blocked = unary_union(grown) if grown else Polygon()
        self._blocked = prepared.prep(self.blocked)
        corners = self.blocked.buffer(CORNER_MARGIN, join_style="mitre")
        self._edge = corners.boundary
        self._corners = [p for polygon in _polygons(corners) for p in _rings_of(polygon)]
        self._outlines = np.array([o.outline for o in obstacles], dtype=object)
        self._with: dict[tuple[Obstacle, ...], NavigationMap] = {}

    def with_obstacles(self, extra: tuple[Obstacle, ...]) -> "NavigationMap":
        """This map with the `extra` obstacles too (what the robot holds still over the
        floor). The last KEPT_MAPS are kept: a robot stopped holding something stays so
        for several walks, and a map's graph is built on its first walk."""
        if extra not in self._with:
            if len(self._with) >= KEPT_MAPS:
                del self._with[next(iter(self._with))]
            obstacles = [*self.obstacles, *extra]
            self._with[extra] = NavigationMap(obstacles, self._keep_out_areas, self.height)
        return self._with[extra]

    def walked_into(self, path, obstacles: tuple[Obstacle, ...]) -> tuple[Obstacle, ...]:
        """The `obstacles` that the walking body, swept along the polyline `path` short of
        its end, or the body stepping round on the spot at its end, enters deeper than
        STAND_TOLERANCE (none along an empty path): the end is a place to stand, judged as
        `stand_problem` judges one (a walk told again and again of what stood beside its
        place, walked there again each time)."""
        if not path:
            return ()
        end = Point(path[-1])
        line = LineString(path) if len(path) > 1 else end
        found = []
        for o in obstacles:
            body = self._body_at(o.low, o.high)
            swept = line.buffer(body.walking - STAND_TOLERANCE)
            passing = swept.difference(end.buffer(body.walking + CORNER_MARGIN))
            standing = end.distance(o.outline) < body.turning - STAND_TOLERANCE
            if standing or passing.intersects(o.outline):
                found.append(o)
        return tuple(found)

    def _body_at(self, low: float, high: float) -> BodySlice:
        """The body's slices that share heights with [low, high], as one (the largest of
        each extent)."""
        within = [s for s in self.body if s.low < high and s.high > low] or [self.body[0]]
        return BodySlice(
            low,
            high,
            min(s.back for s in within),
            max(s.front for s in within),
            max(s.side for s in within),
            max(s.turning for s in within),
            max(s.walking for s in within),
        )

    def clearance(self, obstacle: Obstacle) -> float:
        """How far walks keep the pelvis from `obstacle`: the walking body's half-width at
        its heights and WALK_MARGIN."""
        return self._reach[self.obstacles.index(obstacle)].walking + WALK_MARGIN

    @cached_property
    def _furniture_by_width(self) -> list[tuple[float, object]]:
        """The obstacles grouped by the walking body's half-width at their heights, each
        group's outlines as one prepared geometry: what a body that wide keeps out of."""
        groups: dict[float, list] = {}
        for obstacle, reach in zip(self.obstacles, self._reach, strict=True):
            groups.setdefault(reach.walking, []).append(obstacle.outline)
        return [(width, prepared.prep(unary_union(o))) for width, o in groups.items()]

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
        """Whether `point` lies outside every obstacle's clearance (not on its line)."""
        return self.blocked.distance(Point(point)) > ON_THE_LINE

    def path(self, start, goal) -> list[tuple[float, float]]:
        """Waypoints strictly between `start` and `goal` of the shortest walk that keeps the
        clearance (a start or goal in it is left or reached keeping the body out of the
        furniture). NoWay when there is none."""
        start, goal = tuple(map(float, start[:2])), tuple(map(float, goal[:2]))
        route = self._route(start, goal)
        if route is not None:
            return route
        entry, exit_ = self._way_out(start), self._way_out(goal)
        for a, b in dict.fromkeys(((entry, goal), (start, exit_), (entry, exit_))):
            route = self._route(a, b) if (a, b) != (start, goal) else None
            if route is not None:
                via = [p for p in (a,) if p != start]
                tail = [p for p in (b,) if p != goal]
                return [*via, *route, *tail]
        raise NoWay(
            f"no walk from ({start[0]:.2f}, {start[1]:.2f}) to ({goal[0]:.2f}, "
            f"{goal[1]:.2f}) keeps clear of the cell"
        )

    def _route(self, start, goal) -> list[tuple[float, float]] | None:
        """The shortest walk's waypoints over the visibility graph, or None. A start or
        goal in the clearance also connects through the nearest point of the free floor
        (stepping straight back from a table, arriving head on)."""
        inside = tuple(p for p in (start, goal) if not self.free(p))
        if self._leg_clear(start, goal, inside):
            return []
        ends = {"start": start, "goal": goal}
        ends.update({f"{name} out": self._nearest_free(ends[name]) for name in ends})
        graph = self._graph.copy()
        for name, point in ends.items():
            within = tuple(p for p in (point,) if p in inside)
            for k, corner in enumerate(self._corners):
                if self._leg_clear(point, corner, within):
                    graph.add_edge(name, k, weight=_length(point, corner))
        for (a, p), (b, q) in combinations(ends.items(), 2):
            if self._leg_clear(p, q, tuple(e for e in (p, q) if e in inside)):
                graph.add_edge(a, b, weight=_length(p, q))
        try:
            nodes = nx.shortest_path(graph, "start", "goal", weight="weight")
        except (nx.NetworkXNoPath, nx.NodeNotFound):
            return None
        return [ends[k] if k in ends else self._corners[k] for k in nodes[1:-1]]

    def _nearest_free(self, point) -> tuple[float, float]:
        """The nearest point of the free floor (just outside the clearance)."""
        if self.free(point):
            return point
        nearest = nearest_points(self._edge, Point(point))[0]
        return (float(nearest.x), float(nearest.y))

    def walkable(self, a, b) -> bool:
        """Whether the walking body, going straight from a to b, keeps out of the furniture
        (without the clearance's margin; the ends in the clearance exempt as in path)."""
        return self._body_clear(a, b, tuple(p for p in (a, b) if not self.free(p)))

    def _leg_clear(self, a, b, inside: tuple) -> bool:
        """Whether a straight leg of a path from a to b is clear: between free points it
        keeps the clearance; from or to its ends `inside` the clearance, the walking body
        keeps out of the furniture."""
        return self._body_clear(a, b, inside) if inside else self._clear(a, b)

    def _body_clear(self, a, b, inside: tuple) -> bool:
        """Whether the walking body swept along the leg from a to b keeps out of the
        furniture (touching it by STAND_TOLERANCE at most), and the pelvis out of the
        robot's space, beyond the discs round its ends `inside` the clearance as wide as the
        body (a little more: the shapes are polygons), where the body stands as it stands
        at that end."""
        leg = LineString([a, b])
        if leg.length == 0.0:
            return True
        for width, furniture in self._furniture_by_width:
            exempt = unary_union([Point(p).buffer(width + CORNER_MARGIN) for p in inside])
            swept = leg.buffer(width - STAND_TOLERANCE).difference(exempt)
            if furniture.intersects(swept):
                return False
        return self._keeps_out_of_the_robots_space(leg, inside)

    def _keeps_out_of_the_robots_space(self, leg: LineString, inside: tuple) -> bool:
        """Whether the pelvis, walking the leg, keeps the clearance from the keep-out
        areas, or, from a start or goal within it (a place to stand by the robot), gets no
        deeper into it than that end (less a centimetre)."""
        if self.keep_out.is_empty:
            return True
        grown = self._keep_out_grown
        depth = max(
            (grown.boundary.distance(Point(p)) for p in inside if grown.contains(Point(p))),
            default=0.0,
        )
        if depth == 0.0:
            return not self._keep_out_grown_prepared.intersects(leg)
        deeper = self.keep_out.buffer(self.keep_out_clearance - depth - CORNER_MARGIN)
        return not deeper.intersects(leg)

    @cached_property
    def _keep_out_grown(self) -> Polygon:
        return self.keep_out.buffer(self.keep_out_clearance)

    @cached_property
    def _keep_out_grown_prepared(self):
        return prepared.prep(self._keep_out_grown)

    def _way_out(self, point) -> tuple[float, float]:
        """The point, or, when it lies in the clearance, the nearest point of the free floor
        that a straight step reaches without crossing the cell's geometry (between a pallet
        and a belt, out along the gap rather than over the belt)."""
        if self.free(point):
            return point
        boundary = self._edge
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

    def clear_spot(self, x: float, y: float, yaw: float | None) -> tuple[float, float]:
        """The place to stand nearest (x, y) that works for a person facing `yaw` (None: any
        way, so only stepping round is checked): (x, y) itself when it works, else the
        nearest within SEARCH_RINGS * SEARCH_STEP, not moving into the keep-out areas from
        outside them. NoWay when there is none."""
        problem = self.stand_problem(x, y, yaw)
        if problem is None:
            return x, y
        outside = not self.keep_out.contains(Point(x, y))
        radius = SEARCH_RINGS * SEARCH_STEP
        room = nearest_points(self._no_room_to_turn.boundary, Point(x, y))[0]
        for spot in ((room.x, room.y), *((x + dx, y + dy) for dx, dy in _rings())):
            if outside and self.keep_out.contains(Point(spot)):
                continue
            if _length((x, y), spot) <= radius and self.stand_problem(*spot, yaw) is None:
                return spot
        raise NoWay(f"{problem}, and no place within {radius:.2f} m has room")

    @cached_property
    def _no_room_to_turn(self) -> Polygon:
        """Where a person stepping round on the spot would touch the cell's geometry (each
        obstacle grown by the turning body's radius at its heights): the nearest place with
        room is usually on its edge, which leaves the tolerance to the walk arriving there."""
        grown = [
            o.outline.buffer(reach.turning + ON_THE_LINE)
            for o, reach in zip(self.obstacles, self._reach, strict=True)
        ]
        return unary_union(grown) if grown else Polygon()

    def no_room_to_turn(self, xs: np.ndarray, ys: np.ndarray) -> np.ndarray:
        """(len(ys), len(xs)): where `stand_problem(x, y, None)` finds a problem (turning on
        the spot reaches an obstacle deeper than STAND_TOLERANCE), all points at once."""
        x, y = np.meshgrid(xs, ys)
        found = np.zeros(x.shape, dtype=bool)
        for outline, body in zip(self._outlines, self._reach, strict=True):
            near = _within_box(x, y, outline.bounds, body.turning - STAND_TOLERANCE) & ~found
            distances = shapely.distance(outline, shapely.points(x[near], y[near]))
            found[near] = body.turning - distances > STAND_TOLERANCE
        return found

    def stand_problem(self, x: float, y: float, yaw: float | None) -> StandProblem | None:
        """Why a person cannot stand at (x, y) facing `yaw` (radians; None: only stepping
        round on the spot is checked) and step round there to face any other way: the
        deepest reach into the cell's geometry beyond STAND_TOLERANCE, or None when the
        place works."""
        worst = None
        point = Point(x, y)
        reach = max(max(s.turning, s.front, -s.back, s.side) for s in self.body)
        distances = shapely.distance(self._outlines, point) if len(self._outlines) else []
        for k in np.flatnonzero(np.asarray(distances) < reach):
            obstacle, body = self.obstacles[k], self._reach[k]
            found = [("turning on the spot", body.turning - float(distances[k]))]
            if yaw is not None:
                found.append(("standing", _overlap_depth(body, x, y, yaw, obstacle.outline)))
            for doing, depth in found:
                if depth > STAND_TOLERANCE and (worst is None or depth > worst.depth):
                    worst = StandProblem(doing, obstacle.name, depth)
        return worst


FLOOR_LEVEL = 1e-6


def _within_box(x: np.ndarray, y: np.ndarray, bounds, margin: float) -> np.ndarray:
    """Which points lie within `margin` of the box `bounds` (x0, y0, x1, y1): the only ones
    that can lie within it of what the box holds."""
    x0, y0, x1, y1 = bounds
    return (x >= x0 - margin) & (x <= x1 + margin) & (y >= y0 - margin) & (y <= y1 + margin)


def _overlap_depth(body: BodySlice, x: float, y: float, yaw: float, outline: Polygon) -> float:
    """How far the standing body's outline at (x, y) facing yaw reaches into `outline` (0
    when it does not)."""
    c, s = cos(yaw), sin(yaw)
    corners = ((body.back, -body.side), (body.front, -body.side))
    corners += ((body.front, body.side), (body.back, body.side))
    standing = Polygon([(x + c * u - s * v, y + s * u + c * v) for u, v in corners])
    overlap = standing.intersection(outline)
    if overlap.area <= 0.0:  # apart, or only touching
        return 0.0
    return _depth(overlap, outline)


def grown_outline(outline: Polygon, clearance: float) -> Polygon:
    """The outline grown by `clearance`, its corners cut by a bevel that just keeps the
    clearance (fewer corners than round ones, and less in the way than square ones)."""
    return outline.buffer(clearance, join_style="mitre", mitre_limit=1.0)


def _rings():
    """Offsets to try round a place to stand that does not work, nearest first."""
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


def _rings_of(polygon: Polygon) -> list[tuple[float, float]]:
    """The corners of a polygon, of its holes too (free floor enclosed by obstacles)."""
    return [p for ring in (polygon.exterior, *polygon.interiors) for p in ring.coords[:-1]]


def _length(a, b) -> float:
    return hypot(b[0] - a[0], b[1] - a[1])
