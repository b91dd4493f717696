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
from hrc_drake.human.navigation import (
    FLOOR_LEVEL,
    SEARCH_RINGS,
    SEARCH_STEP,
    NavigationMap,
    NoWay,
    cell_navigation,
)
from hrc_drake.iisy import VARIANTS
from hrc_drake.scenario.located import Finding, Locator
from hrc_drake.scenario.schema import Scenario
from hrc_drake.station import add_station_models, model_parser
from hrc_drake.workpieces.config import WorkpiecesConfig
from hrc_drake.workpieces.geometry import Solid
from hrc_drake.workpieces.layouts import grid_placements

OVERLAP_TOLERANCE = 0.002
"""m: objects may start this far inside what they rest on or touch (they settle)."""


@dataclass(frozen=True)
class InitialObject:
    """An object present at the start, where the scenario gives it (`names`: its field)."""

    names: tuple
    label: str
    solid: Solid
    pose: RigidTransform


def initial_objects(config: WorkpiecesConfig, skip_types=()) -> list[InitialObject]:
    """The objects of `objects` and every place of every grid (all occupied: any may be)."""
    found = []
    for i, placed in enumerate(config.objects):
        if placed.type not in skip_types:
            names = ("workpieces", "objects", i, "pose")
            solid = Solid.of(config.types[placed.type])
            found.append(
                InitialObject(names, placed.type, solid, placed.pose.GetDeterministicValue())
            )
    for i, grid in enumerate(config.grids):
        if grid.type in skip_types:
            continue
        kind = config.types[grid.type]
        full = dataclasses.replace(grid, occupancy=1.0, attribute_counts={})
        for k, place in enumerate(grid_placements(full, kind, np.random.default_rng(0))):
            names = ("workpieces", "grids", i, "origin")
            found.append(
                InitialObject(names, f"{grid.type} {k + 1} of the grid", Solid.of(kind), place.pose)
            )
    return found


class CellScene:
    """The station's models, the initial objects and the person's navigation map."""

    def __init__(self, scenario: Scenario, skip_types=()):
        self.scenario = scenario
        builder = DiagramBuilder()
        self.plant, self.scene_graph = AddMultibodyPlantSceneGraph(builder, 0.0)
        arm, _ = add_station_models(self.plant, model_parser(self.plant), scenario.station)
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

    def _add_object(self, index: int, obj: InitialObject):
        instance = self.plant.AddModelInstance(f"initial_object_{index}")
        body = self.plant.AddRigidBody("object", instance, SpatialInertia.Zero())
        self.plant.RegisterCollisionGeometry(
            body, RigidTransform(), obj.solid.drake_shape(), "object", CoulombFriction()
        )
        return body

    def inside_cell(self, point) -> tuple[str, float] | None:
        """The part of the static cell a point lies in, and how deep (None: in none)."""
        query = self._query()
        deepest = None
        for found in query.ComputeSignedDistanceToPoint(np.asarray(point, dtype=float)):
            body = self.plant.GetBodyFromFrameId(query.inspector().GetFrameId(found.id_G))
            if self.plant.IsAnchored(body) and (deepest is None or found.distance < deepest[1]):
                deepest = (self.plant.GetModelInstanceName(body.model_instance()), found.distance)
        if deepest is None or deepest[1] >= -OVERLAP_TOLERANCE:
            return None
        return deepest[0], -deepest[1]

    def _query(self):
        return self.scene_graph.get_query_output_port().Eval(
            self.scene_graph.GetMyContextFromRoot(self.context)
        )

    def overlaps(self) -> Iterator[tuple[int, str, float, np.ndarray]]:
        """(object index, what it overlaps, depth, normal) of every initial object deeper
        than OVERLAP_TOLERANCE in the cell, the robot or another object (each pair once)."""
        query = self._query()
        inspector = query.inspector()
        for pair in query.ComputePointPairPenetration():
            if pair.depth <= OVERLAP_TOLERANCE:
                continue
            a, b = (self._owner(inspector, g) for g in (pair.id_A, pair.id_B))
            if isinstance(a, int):
                yield a, self._named(b), pair.depth, pair.nhat_BA_W
            elif isinstance(b, int):
                yield b, self._named(a), pair.depth, -pair.nhat_BA_W

    def _owner(self, inspector, geometry) -> int | str:
        """An initial object's index, or the name of the model the geometry belongs to."""
        body = self.plant.GetBodyFromFrameId(inspector.GetFrameId(geometry))
        name = self.plant.GetModelInstanceName(body.model_instance())
        prefix = "initial_object_"
        return int(name.removeprefix(prefix)) if name.startswith(prefix) else name

    def _named(self, owner: int | str) -> str:
        if isinstance(owner, str):
            return owner
        obj = self.objects[owner]
        return f"the {obj.label} at {_xyz(obj.pose.translation())}"


def cell_findings(
    scenario: Scenario, scene: CellScene, at: Locator, skip_locations=()
) -> Iterator[Finding]:
    """Objects in the cell or each other, the person's start and the places to stand (the
    locations at floor level but `skip_locations`, whose magnitudes were found wrong)."""
    yield from _overlap_findings(scene, at)
    yield from _start_findings(scenario, scene, at)
    for name in (n for n in scenario.locations if n not in skip_locations):
        pose = scenario.location(name)
        x, y, z = pose.translation()
        if abs(z) <= FLOOR_LEVEL:
            problem = stand_problem(scene.navigation, x, y, _yaw(pose))
            if problem:
                yield at.field(("locations", name), problem, (x, y, z))


def _overlap_findings(scene: CellScene, at: Locator) -> Iterator[Finding]:
    for index, other, depth, normal in scene.overlaps():
        obj = scene.objects[index]
        centre = obj.pose.translation()
        hint = ""
        if normal[2] > 0.9:  # pushed up out of what it lies in: it was meant to rest on it
            hint = (
                f" (to rest on it, raise its centre {depth:.3f} m to z = {centre[2] + depth:.3f})"
            )
        yield at.field(
            obj.names,
            f"the {obj.label} at {_xyz(centre)} starts {depth:.3f} m inside {other}{hint}",
            centre,
        )


def _start_findings(scenario: Scenario, scene: CellScene, at: Locator) -> Iterator[Finding]:
    if scenario.human is None:
        return
    x, y, yaw_deg = scenario.human.start
    problem = stand_problem(scene.navigation, x, y, math.radians(yaw_deg))
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


def walk_problem(navigation: NavigationMap, start, x: float, y: float, yaw: float | None) -> str:
    """Why no walk from `start` (x, y) reaches the place a walk to (x, y) facing `yaw` ends
    at (the nearest with room, as the person's planner moves it): "" when one does, or when
    no place near has room (stand_problem says so)."""
    try:
        goal = navigation.clear_spot(x, y, yaw)
    except NoWay:
        return ""
    try:
        navigation.path(start, goal)
    except NoWay:
        return (
            f"no walk from the person's start {_xy(start)} to {_xy(goal)} keeps clear of the "
            "cell (the gaps on the way are narrower than a walking person, or the robot's "
            "inner working space closes them)"
        )
    return ""


def _yaw(pose: RigidTransform) -> float:
    R = pose.rotation().matrix()
    return math.atan2(R[1, 0], R[0, 0])


def _xy(p) -> str:
    return f"[{p[0]:.2f}, {p[1]:.2f}]"


def _xyz(p) -> str:
    return "(" + ", ".join(f"{v:.2f}" for v in p) + ")"
