"""The cell as it stands when the run starts, checked without simulating: objects that
start inside the cell's geometry, the robot or each other, and places the person starts at
or stands at that are not clear of the cell.

`CellScene` builds the station's models once (robot at its initial configuration, the
static cell) with every initial object as a body of its own, so Drake's proximity queries
say what overlaps what, and the person's navigation map (hrc_drake.human.navigation) says
where a person can stand.
"""

import dataclasses
import math
from collections.abc import Iterator
from dataclasses import dataclass

import numpy as np
from pydrake.math import RigidTransform
from pydrake.multibody.plant import AddMultibodyPlantSceneGraph, CoulombFriction
from pydrake.multibody.tree import SpatialInertia
from pydrake.systems.framework import DiagramBuilder
from shapely.geometry import Point

from hrc_drake.human.anthropometry import DEFAULT_HEIGHT
from hrc_drake.human.in_the_way import in_the_way
from hrc_drake.human.messages import Box
from hrc_drake.human.navigation import (
    FLOOR_LEVEL,
    SEARCH_RINGS,
    SEARCH_STEP,
    NavigationMap,
    NoWay,
    cell_navigation,
)
from hrc_drake.iisy import VARIANTS
from hrc_drake.nodes.person import box_at
from hrc_drake.scenario.located import Finding, Locator
from hrc_drake.scenario.schema import Scenario
from hrc_drake.station import add_station_models, model_parser
from hrc_drake.workpieces.config import WorkpiecesConfig
from hrc_drake.workpieces.geometry import Solid
from hrc_drake.workpieces.layouts import grid_placements

OVERLAP_TOLERANCE = 0.002
"""m: objects may start this far inside what they rest on or touch (they settle)."""
ON_SURFACE = 0.005
"""m: a conveyor's line lies on a surface when this far above it is free and this far
below it is inside the cell's geometry."""
SURFACE_SEARCH = 0.3
"""m: how far above a conveyor's line the top it lies under is looked for."""
IN_THE_AIR = " (objects on it would move in the air)"
NOTHING_UNDER = "nothing is under its line at"
BASE_SEARCH = 2.0
"""m: how far above the robot's base the top of what it lies in is looked for."""
BELT_SAMPLES = 11
"""Points along a conveyor's line that are checked, its ends included."""


@dataclass(frozen=True)
class InitialObject:
    """An object present at the start, where the scenario gives it (`names`: its field)."""

    names: tuple
    label: str
    type: str
    solid: Solid
    pose: RigidTransform


def initial_objects(config: WorkpiecesConfig, skip_types=()) -> list[InitialObject]:
    """The objects of `objects` and every place of every grid (all occupied: any may be)."""
    found = []
    for i, placed in enumerate(config.objects):
        if placed.type not in skip_types:
            names = ("workpieces", "objects", i, "pose")
            solid = Solid.of(config.types[placed.type])
            pose = placed.pose.GetDeterministicValue()
            found.append(InitialObject(names, placed.type, placed.type, solid, pose))
    for i, grid in enumerate(config.grids):
        if grid.type in skip_types:
            continue
        kind = config.types[grid.type]
        full = dataclasses.replace(grid, occupancy=1.0, attribute_counts={})
        for k, place in enumerate(grid_placements(full, kind, np.random.default_rng(0))):
            names = ("workpieces", "grids", i, "origin")
            label = f"{grid.type} {k + 1} of the grid"
            found.append(InitialObject(names, label, grid.type, Solid.of(kind), place.pose))
    return found


class CellScene:
    """The station's models, the initial objects and the person's navigation map."""

    def __init__(self, scenario: Scenario, skip_types=()):
        self.scenario = scenario
        builder = DiagramBuilder()
        self.plant, self.scene_graph = AddMultibodyPlantSceneGraph(builder, 0.0)
        arm, robot = add_station_models(self.plant, model_parser(self.plant), scenario.station)
        self.robot = set(robot)
        self.objects = initial_objects(scenario.workpieces, skip_types)
        bodies = [self._add_object(i, obj) for i, obj in enumerate(self.objects)]
        self.plant.Finalize()
        self.diagram = builder.Build()
        self.context = self.diagram.CreateDefaultContext()
        plant_context = self.plant.GetMyMutableContextFromRoot(self.context)
        self.plant.SetPositions(plant_context, arm, scenario.station.initial_positions)
        for body, obj in zip(bodies, self.objects, strict=True):
            self.plant.SetFreeBodyPose(plant_context, body, obj.pose)
        robot_xy = scenario.station.base_pose.translation()[:2]
        self.navigation = cell_navigation(
            self.plant,
            self.scene_graph.model_inspector(),
            robot_xy,
            VARIANTS[scenario.robot.variant].reach,
            scenario.human.size()[0] if scenario.human is not None else DEFAULT_HEIGHT,
        )
        boxes = tuple(
            Box(*box_at(obj.pose, obj.solid.shape, obj.solid.size), name=self.named(i))
            for i, obj in enumerate(self.objects)
        )
        self.standing = self.navigation.with_obstacles(in_the_way(boxes))
        """The map with the objects too, where places to stand are judged: a walk to a
        place goes round the objects the person meets there, and a place with no room
        beside one moves as it would beside the furniture (hrc_drake.nodes.person)."""

    def _add_object(self, index: int, obj: InitialObject):
        instance = self.plant.AddModelInstance(f"initial_object_{index}")
        body = self.plant.AddRigidBody("object", instance, SpatialInertia.Zero())
        self.plant.RegisterCollisionGeometry(
            body, RigidTransform(), obj.solid.drake_shape(), "object", CoulombFriction()
        )
        return body

    def inside_cell(self, point, robot: bool = True) -> tuple[str, float] | None:
        """The part of the static cell (and the robot where it starts, with `robot`) a
        point lies in, and how deep (None: in none)."""
        query = self._query()
        deepest = None
        for found in query.ComputeSignedDistanceToPoint(np.asarray(point, dtype=float)):
            body = self.plant.GetBodyFromFrameId(query.inspector().GetFrameId(found.id_G))
            if not self.plant.IsAnchored(body) or (
                not robot and body.model_instance() in self.robot
            ):
                continue
            if deepest is None or found.distance < deepest[1]:
                deepest = (self.plant.GetModelInstanceName(body.model_instance()), found.distance)
        if deepest is None or deepest[1] >= -OVERLAP_TOLERANCE:
            return None
        return deepest[0], -deepest[1]

    def _query(self):
        return self.scene_graph.get_query_output_port().Eval(
            self.scene_graph.GetMyContextFromRoot(self.context)
        )

    def overlaps(self) -> Iterator[tuple[int, int | str, float, np.ndarray]]:
        """(object index, what it overlaps: another's index or a model's name, depth,
        normal) of every initial object deeper than OVERLAP_TOLERANCE in the cell, the robot
        or another object (each pair once)."""
        query = self._query()
        inspector = query.inspector()
        for pair in query.ComputePointPairPenetration():
            if pair.depth <= OVERLAP_TOLERANCE:
                continue
            a, b = (self._owner(inspector, g) for g in (pair.id_A, pair.id_B))
            if isinstance(a, int):
                yield a, b, pair.depth, pair.nhat_BA_W
            elif isinstance(b, int):
                yield b, a, pair.depth, -pair.nhat_BA_W

    def _owner(self, inspector, geometry) -> int | str:
        """An initial object's index, or the name of the model the geometry belongs to."""
        body = self.plant.GetBodyFromFrameId(inspector.GetFrameId(geometry))
        name = self.plant.GetModelInstanceName(body.model_instance())
        prefix = "initial_object_"
        return int(name.removeprefix(prefix)) if name.startswith(prefix) else name

    def named(self, owner: int | str) -> str:
        if isinstance(owner, str):
            return owner
        obj = self.objects[owner]
        return f"the {obj.label} at {_xyz(obj.pose.translation())}"


def cell_findings(
    scenario: Scenario, scene: CellScene, at: Locator, skip_locations=()
) -> Iterator[Finding]:
    """Objects in the cell or each other, the person's start and the places to stand (the
    locations at floor level but `skip_locations`, whose magnitudes were found wrong)."""
    yield from _robot_findings(scenario, scene, at)
    yield from _overlap_findings(scene, at)
    yield from _conveyor_findings(scenario, scene, at)
    yield from _start_findings(scenario, scene, at)
    for name in (n for n in scenario.locations if n not in skip_locations):
        pose = scenario.location(name)
        x, y, z = pose.translation()
        if abs(z) <= FLOOR_LEVEL:
            problem = stand_problem(scene.standing, x, y, _yaw(pose))
            if problem:
                yield at.field(("locations", name), problem, (x, y, z))


def _robot_findings(scenario: Scenario, scene: CellScene, at: Locator) -> Iterator[Finding]:
    """The robot's base inside the cell's geometry (a base pose left at the floor, in its
    pedestal), with the height of the top it would stand on."""
    base = scenario.station.base_pose.translation()
    inside = scene.inside_cell(base + [0.0, 0.0, ON_SURFACE], robot=False)
    if inside is None:
        return
    top = _top_within(scene, base, 1.0, BASE_SEARCH, robot=False)
    if top is None:
        message = f"the robot's base at {_xyz(base)} lies {inside[1]:.3f} m inside {inside[0]}"
    else:
        what, gap = top
        message = (
            f"the robot's base at {_xyz(base)} lies {gap:.3f} m below the top of {what} (to "
            f"stand on it: z = {base[2] + gap:.3f})"
        )
    yield at.field(("robot", "base_pose"), message, base)


def _overlap_findings(scene: CellScene, at: Locator) -> Iterator[Finding]:
    """One line per object field and what it overlaps (a model, or the objects of another
    field): the deepest overlap, and how many more of the field's objects overlap it."""
    groups: dict[tuple, list] = {}
    for index, other, depth, normal in scene.overlaps():
        field = other if isinstance(other, str) else scene.objects[other].names
        groups.setdefault((scene.objects[index].names, field), []).append(
            (depth, index, other, normal)
        )
    for (names, field), found in groups.items():
        depth, index, other, normal = max(found, key=lambda overlap: overlap[0])
        obj = scene.objects[index]
        centre = obj.pose.translation()
        if field == names:  # the places of one grid
            message = (
                f"its objects start up to {depth:.3f} m inside each other ({len(found)} "
                "pairs: is its spacing less than their size?)"
            )
            yield at.field(names, message, centre)
            continue
        more = f" (and {len(found) - 1} more of them)" if len(found) > 1 else ""
        hint = ""
        if normal[2] > 0.9:  # pushed up out of what it lies in: it was meant to rest on it
            hint = (
                f" (to rest on it, raise its centre {depth:.3f} m to z = {centre[2] + depth:.3f})"
            )
        message = (
            f"the {obj.label} at {_xyz(centre)} starts {depth:.3f} m inside "
            f"{scene.named(other)}{hint}{more}"
        )
        yield at.field(names, message, centre)


def _conveyor_findings(scenario: Scenario, scene: CellScene, at: Locator) -> Iterator[Finding]:
    """A conveyor's line (start to end) that does not lie on the surface of the cell's
    geometry (a conveyor model's belt) where some of it does or something lies under it:
    objects on it would move in the air or in it (a belt with nothing at all under it is
    a surface of its own)."""
    for name, conveyor in scenario.workpieces.conveyors.items():
        start, end = np.asarray(conveyor.start, float), np.asarray(conveyor.end, float)
        points = [start + t * (end - start) for t in np.linspace(0.0, 1.0, BELT_SAMPLES)]
        problems = [(_off_the_surface(scene, point), point) for point in points]
        if all(problem.startswith(NOTHING_UNDER) for problem, _ in problems):
            continue  # a belt of its own, with no model under it
        for problem, point in problems:
            if problem:
                yield at.field(("workpieces", "conveyors", name), problem, point)
                break


def _off_the_surface(scene: CellScene, point: np.ndarray) -> str:
    """Why `point` is not on a top surface of the cell ("" when it is): how far it lies
    below the top of what it is in or under, or above what is under it."""
    if scene.inside_cell(point + [0.0, 0.0, ON_SURFACE]) is None:
        if scene.inside_cell(point - [0.0, 0.0, ON_SURFACE]) is not None:
            return ""
        below = _top_within(scene, point, -1.0, point[2])
        if below is not None:
            what, gap = below
            return f"its line at {_xyz(point)} lies {gap:.2f} m above {what}{IN_THE_AIR}"
    above = _top_within(scene, point, 1.0, SURFACE_SEARCH)
    if above is not None:
        what, gap = above
        return f"its line at {_xyz(point)} lies {gap:.2f} m below the top of {what}"
    return f"{NOTHING_UNDER} {_xyz(point)}{IN_THE_AIR}"


def _top_within(scene: CellScene, point, direction: float, distance: float, robot: bool = True):
    """(what, how far) the nearest top surface lies from `point` going up (direction 1)
    or down (-1) within `distance`: where being inside something ends and two steps above
    are free (the robot counts too, with `robot`)."""
    steps = np.arange(0, int(distance / ON_SURFACE) + 2) * ON_SURFACE * direction
    inside = [scene.inside_cell(point + [0.0, 0.0, step], robot) for step in steps]
    for k in range(len(steps) - 2):
        if direction < 0:
            below, free = k + 1, (k,)
        else:
            below, free = k, (k + 1, k + 2)
        if inside[below] is not None and all(inside[f] is None for f in free):
            return inside[below][0], abs(steps[free[0]])
    return None


def below_top(scene: CellScene, point, within: float) -> tuple[str, float] | None:
    """(what, how far) `point` lies below the top of the cell's fixed geometry it is in
    (the robot where it starts left out), looking up to `within` above it for the top; None
    when it is in none, or no top is that near."""
    if scene.inside_cell(point, robot=False) is None:
        return None
    return _top_within(scene, point, 1.0, within, robot=False)


def _start_findings(scenario: Scenario, scene: CellScene, at: Locator) -> Iterator[Finding]:
    if scenario.human is None:
        return
    x, y, yaw_deg = scenario.human.start
    problem = stand_problem(scene.standing, x, y, math.radians(yaw_deg))
    if problem:
        yield at.field(("human", "start"), problem, (x, y, 0.0))


def stand_problem(navigation: NavigationMap, x: float, y: float, yaw: float | None) -> str:
    """Why a person cannot stand at (x, y) facing `yaw` (radians; None: any way) and step
    round on the spot there (NavigationMap.stand_problem), with the nearest place that has
    room, where a walk there would end instead: "" when they can."""
    problem = navigation.stand_problem(x, y, yaw)
    if problem is None:
        return ""
    facing = f" facing {math.degrees(yaw):.0f}°" if yaw is not None else ""
    what = (
        f"a person at ({x:.2f}, {y:.2f}){facing}, {problem.doing}, reaches "
        f"{problem.depth:.2f} m into {problem.what}"
    )
    within = [o.name for o in navigation.obstacles if o.outline.contains(Point(x, y))]
    if within:
        what = f"({x:.2f}, {y:.2f}) lies within the floor outline of {within[0]}"
    try:
        spot = navigation.clear_spot(x, y, yaw)
    except NoWay:
        near = SEARCH_RINGS * SEARCH_STEP
        return f"{what}, and no place within {near:.2f} m has room to stand and turn"
    return f"{what}: the nearest place with room to stand and turn is {_xy(spot)}"


def walk_problem(
    navigation: NavigationMap, start, x: float, y: float, yaw: float | None, closing_gap
) -> str:
    """Why no walk from `start` (x, y) reaches the place a walk to (x, y) facing `yaw` ends
    at (the nearest with room, as the person's planner moves it): "" when one does, or when
    no place near has room (stand_problem says so). `closing_gap(start, goal)` names the gap
    a little too narrow that closes the way, if one does ("")."""
    try:
        goal = navigation.clear_spot(x, y, yaw)
    except NoWay:
        return ""
    try:
        navigation.path(start, goal)
    except NoWay:
        why = closing_gap(start, goal) or (
            "the gaps on the way are narrower than a walking person, or the robot's inner "
            "working space closes them"
        )
        return (
            f"no walk from the person's start {_xy(start)} to {_xy(goal)} keeps clear of the "
            f"cell ({why})"
        )
    return ""


def _yaw(pose: RigidTransform) -> float:
    R = pose.rotation().matrix()
    return math.atan2(R[1, 0], R[0, 0])


def _xy(p) -> str:
    return f"[{p[0]:.2f}, {p[1]:.2f}]"


def _xyz(p) -> str:
    return "(" + ", ".join(f"{v:.2f}" for v in p) + ")"
