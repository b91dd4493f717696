"""What the scenario's trees will do with the values known before a run
(hrc_drake.known_values), checked the way the running nodes use them: what the robot is
told to do (hrc_drake.scenario.robot_findings), what the person picks and puts down and
reaches to from where they stand (hrc_drake.scenario.person_picks), every animation
against the person's clips, every place the person walks to for room to stand and a walk
there, every named configuration, object type and area against the scenario.
"""

from collections.abc import Iterator
from functools import cached_property, partial

from hrc_drake.agent_trees import sections
from hrc_drake.human.clip_files import clip_catalog, no_animation, walks
from hrc_drake.human.navigation import FLOOR_LEVEL
from hrc_drake.known_values import Known, known_inputs, unwritten_inputs
from hrc_drake.nodes.objects import CountObjects, NextObject, SpawnObject, parse_filter
from hrc_drake.nodes.person import ActorAnimation, ActorMovement
from hrc_drake.nodes.robot import RobotMove, RobotMoveJoints, RobotMoveLinear
from hrc_drake.nodes.targeted import ActorPlace, ActorReach
from hrc_drake.scenario.belt_picks import belt_pick_findings
from hrc_drake.scenario.cell_findings import CellScene, stand_problem, walk_problem
from hrc_drake.scenario.detours import Detours, detour_findings
from hrc_drake.scenario.known_poses import heading, resolved
from hrc_drake.scenario.located import Finding, Locator
from hrc_drake.scenario.person_picks import PersonPicks
from hrc_drake.scenario.reach_from_stand import point_text
from hrc_drake.scenario.robot_findings import RobotChecks
from hrc_drake.scenario.schema import Scenario
from hrc_drake.scenario.start_objects import StartObjects
from hrc_drake.tree_types import Pose
from hrc_drake.yaml_check import unknown


def tree_findings(
    scenario: Scenario, scene: CellScene, at: Locator, skip_configurations=(), robot_placed=True
) -> list[Finding]:
    """Blackboard entries read and never set, named configurations the planner refuses
    (but `skip_configurations`, whose magnitudes were found wrong), and the checks of every
    known value a node reads; the robot's configurations and targets only when it is
    `robot_placed` (its base not inside the cell: every one would fail from that)."""
    places = scenario.places()
    found: list[Finding] = []
    reads = []
    checks = _Checks(scenario, scene, at, robot_placed)
    for agent in scenario.trees:
        tree, handle = scenario.agent_tree(agent)
        inputs = list(known_inputs(tree, sections(places)))
        reads += [(handle, *read) for read in inputs]
        found += [
            at.node(node, port, _never_set(key, why))
            for node, port, key, why in unwritten_inputs(tree, sections(places))
        ]
        found += checks.person.reaches_from_stand(tree, handle, inputs)
        found += checks.detours(tree, handle, inputs)
        found += checks.robot.put_downs(tree, handle, inputs)
        found += checks.belt_picks(tree, inputs)
        if robot_placed:
            found += checks.robot.found_reaches(tree, handle, inputs)
    if robot_placed:
        found += checks.robot.configurations(skip_configurations)
    for handle, node, port, known in reads:
        for value in known:
            found += checks.of(handle, node, port, value)
    once: dict[tuple, Finding] = {}  # a SubTree used twice makes the same mistake twice
    for finding in found:
        once.setdefault((finding.file, finding.line, finding.message), finding)
    return list(once.values())


class _Checks:
    """The checks of one validate, made once: the robot's (`RobotChecks`), the person's
    picks and put-downs (`PersonPicks`), and those of each known value a node reads (`of`)."""

    def __init__(self, scenario: Scenario, scene: CellScene, at: Locator, robot_placed=True):
        self.scenario = scenario
        self.scene = scene
        self.at = at
        human = scenario.human
        self.clips = clip_catalog(human.clips if human is not None else ())
        objects = StartObjects(scenario, scene)
        self.robot = RobotChecks(scenario, scene, at, objects, robot_placed)
        self.person = PersonPicks(scenario, scene, at, objects, self.clips)
        self.walk_problems: dict[tuple, str] = {}

    def belt_picks(self, tree, inputs) -> Iterator[Finding]:
        """Picks of what a belt carries off (hrc_drake.scenario.belt_picks)."""
        known = {(id(node), port): values for node, port, values in inputs}
        areas = {name: self.scenario.area(name) for name in self.scenario.areas}
        return belt_pick_findings(tree.node_list, known, areas, self.scenario.workpieces)

    def detours(self, tree, agent, inputs) -> Iterator[Finding]:
        """Walks that go a long way round a gap a little too narrow for the person
        (hrc_drake.scenario.detours)."""
        if self.scenario.human is None:
            return iter(())
        known = {(id(node), port): values for node, port, values in inputs}
        start = self.scenario.human.start[:2]
        walk_end = partial(self.person.walk_end, agent)
        return detour_findings(tree.node_list, known, walk_end, start, self._detours)

    @cached_property
    def _detours(self) -> Detours:
        return Detours(self.scene.navigation)

    def of(self, agent, node, port: str, known: Known) -> Iterator[Finding]:
        value = known.value
        if isinstance(node, RobotMove | RobotMoveLinear) and port == "target":
            if self.robot.robot_placed:
                yield from self.robot.reach(agent, node, known)
        elif isinstance(node, ActorMovement) and port == "target":
            yield from self._standing(agent, node, known)
        elif isinstance(node, ActorMovement) and port == "animation_name":
            yield from self._walk_clip(node, known)
        elif isinstance(node, ActorAnimation) and port == "animation_name":
            if value not in self.clips:
                yield self.at.read(node, port, known, no_animation(value, self.clips))
        elif isinstance(node, RobotMoveJoints) and port == "configuration":
            names = self.scenario.station.configuration_names
            if value not in names:
                yield self.at.read(node, port, known, unknown("configuration", value, names))
        elif isinstance(node, SpawnObject) and port == "type":
            yield from self._object_type(node, port, known, value)
            kind = self.scenario.workpieces.types.get(value)
            if kind is not None and kind.capacity == 0:
                message = f"object type '{value}' has capacity 0: none can ever be made"
                yield self.at.read(node, port, known, message)
        elif isinstance(node, SpawnObject | ActorPlace | ActorReach) and isinstance(value, Pose):
            yield from self._inside(agent, node, port, known)
        elif isinstance(node, SpawnObject) and port == "area" and value:
            if value not in self.scenario.areas:
                yield self.at.read(node, port, known, unknown("area", value, self.scenario.areas))
        elif isinstance(node, NextObject | CountObjects) and port == "filter":
            wanted = parse_filter(value).get("type")
            if wanted is not None:
                yield from self._object_type(node, port, known, wanted)

    def _object_type(self, node, port: str, known: Known, name: str) -> Iterator[Finding]:
        types = self.scenario.workpieces.types
        if name not in types:
            yield self.at.read(node, port, known, unknown("object type", name, types))

    def _inside(self, agent, node, port: str, known: Known) -> Iterator[Finding]:
        """A point an object is made at, or a hand puts one down or reaches to, inside the
        cell's geometry."""
        pose = resolved(agent, known.value)
        inside = self.scene.inside_cell(pose.position) if pose is not None else None
        if inside is not None:
            what, depth = inside
            where = point_text(pose.position)
            message = f"{known} at {where} lies {depth:.3f} m inside {what}"
            yield self.at.read(node, port, known, message, pose.position)

    def _walk_clip(self, node, known: Known) -> Iterator[Finding]:
        name = known.value
        if name not in self.clips:
            yield self.at.read(node, "animation_name", known, no_animation(name, self.clips))
        elif not walks(self.clips[name]):
            walking = ", ".join(sorted(n for n, clip in self.clips.items() if walks(clip)))
            message = f"'{name}' is not a walking animation (the person walks with: {walking})"
            yield self.at.read(node, "animation_name", known, message)

    def _standing(self, agent, node, known: Known) -> Iterator[Finding]:
        """A place to walk to: room to stand and turn there (floor-level locations are
        checked as locations, in cell_findings), and a walk from the person's start."""
        pose = resolved(agent, known.value)
        if pose is None:
            return
        x, y, z = pose.position
        yaw = heading(pose)
        location = known.value.name and abs(z) <= FLOOR_LEVEL
        problem = "" if location else stand_problem(self.scene.navigation, x, y, yaw)
        if not problem:
            problem = self._no_walk(x, y, yaw)
        if problem:
            yield self.at.read(node, "target", known, f"{known}: {problem}", (x, y, 0.0))

    def _no_walk(self, x: float, y: float, yaw: float | None) -> str:
        """Why no walk from the person's start reaches the place a walk to (x, y) ends at
        (what walk_problem says, asked once per place)."""
        key = (round(x, 9), round(y, 9), yaw)
        if key not in self.walk_problems:
            start = self.scenario.human.start[:2]
            self.walk_problems[key] = walk_problem(
                self.scene.navigation, start, x, y, yaw, self._detours.closing_gap
            )
        return self.walk_problems[key]


def _never_set(key: str, why: str) -> str:
    """What a run would end with ("blackboard entry 'key' is not set"), said before it."""
    return f"blackboard entry '{key}' is never set: {why}"
