"""What the layout view shows of a scenario, gathered without simulating: the furniture
(the person's navigation obstacles, by model), where the person may walk and stand, the
robot's reach at the heights its tree moves the tool to, the named places, areas and
starting objects, the safety sensors with their fields, and `validate`'s findings with their
points in the cell."""

import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from shapely.geometry import MultiPolygon, Polygon
from shapely.ops import unary_union

from hrc_drake.agent_trees import sections
from hrc_drake.human.navigation import FLOOR_LEVEL, NavigationMap, Obstacle
from hrc_drake.known_values import known_inputs
from hrc_drake.layout.reach_map import ReachMap, base_centre, reach_maps
from hrc_drake.nodes.robot import RobotMove, RobotMoveLinear, tool_pose
from hrc_drake.safety.sensors import SensorsConfig
from hrc_drake.scenario.cell_findings import CellScene
from hrc_drake.scenario.findings import Finding, findings
from hrc_drake.scenario.schema import Scenario
from hrc_drake.seeding import stream
from hrc_drake.wiring import ROBOT_MOTION

HEIGHT_BAND = 0.05
"""m: robot targets this close in height share one reach map (the lowest of them)."""
MAX_HEIGHTS = 4
"""Reach maps drawn at most (the band widens until the heights fit)."""
ROOM_STEP, ROOM_MARGIN = 0.04, 0.5
"""m: where a person has room to stand is sampled this finely, this far round the cell."""


@dataclass(frozen=True)
class Furniture:
    """One model of the cell seen from above: its floor outline, the top of its largest
    face (where things are put: a table's top, a belt) and its highest point."""

    name: str
    outline: Polygon | MultiPolygon
    surface: float
    top: float


@dataclass(frozen=True)
class Target:
    """A pose the robot's tree moves the tool to, known before the run."""

    label: str
    """The location's name, or '' for a pose made from one (OffsetPose)."""
    position: tuple[float, float, float]
    linear: bool


@dataclass(frozen=True)
class Place:
    """A named location: a person's place to stand (on the floor, facing `yaw`) or a point
    above it."""

    name: str
    position: tuple[float, float, float]
    yaw: float | None


@dataclass(frozen=True)
class StartingObject:
    label: str
    group: str
    """The scenario field that places it (a grid places many)."""
    outline: Polygon
    top: float

    @property
    def picked(self) -> Target:
        """Where a tool picking it goes: the middle of its top face (a linear move's end)."""
        centre = self.outline.centroid
        return Target("", (centre.x, centre.y, self.top), True)


@dataclass(frozen=True)
class CellLayout:
    name: str
    variant: str
    robot_xy: tuple[float, float]
    furniture: list[Furniture]
    blocked: Polygon | MultiPolygon
    """Where the person's pelvis may not go (the furniture grown by the body, the robot's
    inner space): the rest of the floor is walkable."""
    keep_out: Polygon | MultiPolygon
    no_room: tuple[np.ndarray, np.ndarray, np.ndarray]
    """x (m), y (m) and, on that grid, where a person cannot stand and turn on the spot
    (NavigationMap.stand_problem facing any way): places to stand lie outside it."""
    reach: list[ReachMap]
    targets: list[Target]
    places: list[Place]
    areas: dict[str, Polygon]
    objects: list[StartingObject]
    person_start: tuple[float, float, float] | None
    """x, y (m) and the heading (rad) the person starts at."""
    findings: list[Finding]
    sensors: SensorsConfig = field(default_factory=SensorsConfig)
    """The scanners (with their protective and warning fields) and light curtains."""


def cell_layout(scenario: Scenario, path: Path | None) -> CellLayout:
    """The layout of a loaded scenario; `path` (its file) locates validate's findings
    (None: no findings are looked for)."""
    scene = CellScene(scenario)
    targets = robot_targets(scenario)
    objects = starting_objects(scene)
    heights = reach_heights(targets + [o.picked for o in objects])
    seed = stream(scenario.seed, ROBOT_MOTION)
    human = scenario.human
    return CellLayout(
        name=scenario.name,
        variant=scenario.robot.variant,
        robot_xy=base_centre(scenario.station),
        furniture=furniture(scene.navigation.obstacles),
        blocked=scene.navigation.blocked,
        keep_out=scene.navigation.keep_out,
        no_room=no_room_to_turn(scene.navigation),
        reach=reach_maps(scenario.station, scenario.robot.motion, seed, heights),
        targets=targets,
        places=places(scenario),
        areas={name: Polygon(points) for name, points in scenario.areas.items()},
        objects=objects,
        person_start=(None if human is None else (*human.start[:2], math.radians(human.start[2]))),
        findings=findings(scenario, path) if path is not None else [],
        sensors=scenario.safety.sensors,
    )


def no_room_to_turn(navigation: NavigationMap):
    """Where a person cannot stand and turn, sampled every ROOM_STEP round the furniture."""
    if not navigation.obstacles:
        return np.zeros(0), np.zeros(0), np.zeros((0, 0), dtype=bool)
    x0, y0, x1, y1 = unary_union([o.outline for o in navigation.obstacles]).bounds
    xs = np.arange(x0 - ROOM_MARGIN, x1 + ROOM_MARGIN, ROOM_STEP)
    ys = np.arange(y0 - ROOM_MARGIN, y1 + ROOM_MARGIN, ROOM_STEP)
    return xs, ys, navigation.no_room_to_turn(xs, ys)


def furniture(obstacles: list[Obstacle]) -> list[Furniture]:
    """The obstacles of the person's navigation map by the model they belong to."""
    by_model: dict[str, list] = {}
    for obstacle in obstacles:
        by_model.setdefault(obstacle.name, []).append(obstacle)
    return [
        Furniture(
            name,
            unary_union([o.outline for o in parts]),
            max(parts, key=lambda o: o.outline.area).high,
            max(o.high for o in parts),
        )
        for name, parts in by_model.items()
    ]


def robot_targets(scenario: Scenario) -> list[Target]:
    """Every tool pose the robot's tree can move to that is known before the run (as
    validate checks them for reach), once each."""
    if "robot" not in scenario.trees:
        return []
    tree, agent = scenario.agent_tree("robot")
    found: dict[tuple, Target] = {}
    for node, port, known in known_inputs(tree, sections(scenario.places())):
        if port != "target" or not isinstance(node, RobotMove | RobotMoveLinear):
            continue
        for value in known:
            try:
                pose = agent.resolve_pose(value.value)
            except KeyError:  # a location the scenario lacks: loading says so
                continue
            position = tuple(round(float(v), 4) for v in tool_pose(pose)[0].translation())
            label = value.value.name if not value.via and value.value.name else ""
            linear = isinstance(node, RobotMoveLinear)
            key = (position, label)
            if key in found:
                linear = linear and found[key].linear
            found[key] = Target(label, position, linear)
    return sorted(found.values(), key=lambda t: (t.position[2], t.label))


def reach_heights(targets: list[Target]) -> list[tuple[float, bool]]:
    """(height, linear) of each reach map: targets (and the tops of the starting objects,
    where a pick goes) within a band of heights share the lowest one's, reached as a linear
    move's end when every target there is one."""
    band = HEIGHT_BAND
    while True:
        groups: list[list[Target]] = []
        for target in sorted(targets, key=lambda t: t.position[2]):
            if groups and target.position[2] - groups[-1][0].position[2] <= band:
                groups[-1].append(target)
            else:
                groups.append([target])
        if len(groups) <= MAX_HEIGHTS:
            return [(g[0].position[2], all(t.linear for t in g)) for g in groups]
        band *= 2


def places(scenario: Scenario) -> list[Place]:
    found = []
    oriented = scenario.places().locations
    for name in scenario.locations:
        pose = scenario.location(name)
        position = tuple(float(v) for v in pose.translation())
        yaw = None
        if abs(position[2]) <= FLOOR_LEVEL and oriented[name].quaternion is not None:
            R = pose.rotation().matrix()
            yaw = math.atan2(R[1, 0], R[0, 0])
        found.append(Place(name, position, yaw))
    return found


def starting_objects(scene: CellScene) -> list[StartingObject]:
    found = []
    for obj in scene.objects:
        X = obj.pose
        corners = [X.multiply([x, y, 0.0])[:2] for x, y in obj.solid.outline()]
        top = X.translation()[2] + obj.solid.height / 2
        group = ".".join(str(n) for n in obj.names)
        found.append(StartingObject(obj.label, group, Polygon(corners), float(top)))
    return found
