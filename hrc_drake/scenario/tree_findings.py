"""What the scenario's trees will do with the values known before a run
(hrc_drake.known_values), checked the way the running nodes use them: every robot target
for reach (the planner's own inverse kinematics, the tool held as the node holds it) and
for what the robot lets go of there (hrc_drake.scenario.robot_put_downs), every
animation against the person's clips, every place the person walks to for room to stand,
every place the person puts down or reaches to against where they stand then
(hrc_drake.scenario.reach_from_stand), every named configuration, object type and area
against the scenario.

Longer than 400 lines: every check reads the same scenario, scene, planner and person,
built once per validate (`_Checks`); the picks and put-downs planned from where the person
stands share its object lookups.
"""

import dataclasses
import math
from collections.abc import Iterator
from functools import cached_property, partial

import numpy as np
from pydrake.math import RigidTransform

from hrc_drake.agent_trees import sections
from hrc_drake.human.aiming import Unreachable
from hrc_drake.human.clip_files import clip_catalog, no_animation, walks
from hrc_drake.human.going_in import going_in
from hrc_drake.human.grasp import grasp_hands, hold_of
from hrc_drake.human.messages import AnimateCommand, Box, Grasp, Hold
from hrc_drake.human.navigation import FLOOR_LEVEL, NoWay
from hrc_drake.human.performer import Performer, sized_performer
from hrc_drake.human.planning import plan_animation, plan_idle
from hrc_drake.known_values import Known, known_inputs, unwritten_inputs
from hrc_drake.motion.planner import MotionPlanner
from hrc_drake.motion.reach import configuration_problem, reach_problem
from hrc_drake.nodes.objects import CountObjects, NextObject, SpawnObject, parse_filter
from hrc_drake.nodes.person import NEARBY, ActorAnimation, ActorMovement, box_at
from hrc_drake.nodes.robot import RobotMove, RobotMoveJoints, RobotMoveLinear, tool_pose
from hrc_drake.nodes.stacks import COVER_OVERLAP, on_top_of
from hrc_drake.nodes.targeted import TABLE_HEIGHT, ActorPlace, ActorReach
from hrc_drake.scenario.belt_picks import belt_pick_findings
from hrc_drake.scenario.cell_findings import (
    CellScene,
    InitialObject,
    stand_problem,
    walk_problem,
)
from hrc_drake.scenario.detours import Detours, detour_findings
from hrc_drake.scenario.found_targets import found_reach_findings
from hrc_drake.scenario.located import Finding, Locator
from hrc_drake.scenario.put_down_overlaps import overlap_findings
from hrc_drake.scenario.reach_from_stand import point_text, reach_findings
from hrc_drake.scenario.robot_put_downs import (
    carried_configuration_findings,
    carried_move_findings,
    hanging_from_the_tool,
    holding,
    put_down_findings,
)
from hrc_drake.scenario.schema import Scenario
from hrc_drake.scenario.switch_ways import finder_type
from hrc_drake.scenario.tree_ways import (
    UNKNOWN,
    failed_before,
    finder_of,
    held_at,
    object_source,
    parents_of,
)
from hrc_drake.seeding import stream
from hrc_drake.station import HOME
from hrc_drake.tree_types import AreaRef, Pose
from hrc_drake.wiring import ROBOT_MOTION
from hrc_drake.workpieces.geometry import Solid, footprint, overlaps
from hrc_drake.yaml_check import unknown

ANY_OBJECT = ("",)
"""A NextObject filter that lets every object through."""
ON_IT = 0.01
"""m: an object whose bottom is at most this far above the top of what is taken lies on it
(`_lies_on`)."""


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
        found += checks.reaches_from_stand(tree, handle, inputs)
        found += checks.detours(tree, handle, inputs)
        found += checks.robot_put_downs(tree, handle, inputs)
        found += checks.belt_picks(tree, inputs)
        if robot_placed:
            found += checks.found_reaches(tree, handle, inputs)
    if robot_placed:
        found += checks.configurations(skip_configurations)
    for handle, node, port, known in reads:
        for value in known:
            found += checks.of(handle, node, port, value)
    once: dict[tuple, Finding] = {}  # a SubTree used twice makes the same mistake twice
    for finding in found:
        once.setdefault((finding.file, finding.line, finding.message), finding)
    return list(once.values())


class _Checks:
    """The checks of one known value read by one node's port."""

    def __init__(self, scenario: Scenario, scene: CellScene, at: Locator, robot_placed=True):
        self.scenario = scenario
        self.robot_placed = robot_placed
        self.scene = scene
        self.at = at
        human = scenario.human
        self.clips = clip_catalog(human.clips if human is not None else ())
        self.reach_problems: dict[tuple, str] = {}
        """What reach_problem said of each target (one pose may be read by many nodes)."""
        self.walk_problems: dict[tuple, str] = {}
        self.planned_problems: dict[tuple, str] = {}

    @cached_property
    def planner(self) -> MotionPlanner:
        """The run's planner (made only when the robot's tree has a known target)."""
        scenario = self.scenario
        seed = stream(scenario.seed, ROBOT_MOTION)
        return MotionPlanner(scenario.station, scenario.robot.motion, seed)

    def configurations(self, skip=()) -> Iterator[Finding]:
        """Every named configuration that the planner would refuse to move the arm to
        (outside the joint limits, touching the cell), at its line, and the robot's start
        when it is the variant's home (`_start`)."""
        station = self.scenario.station
        for name in (n for n in station.configurations_deg if n not in skip):
            problem = configuration_problem(self.planner, station.configuration(name))
            if problem:
                yield self.at.field(("robot", "configurations_deg", name), problem)
        yield from self._start()

    def _start(self) -> Iterator[Finding]:
        """The robot's start when it is the variant's home (a named start is checked by its
        name), at `robot.initial_configuration` or else `robot.variant`: a cell whose furniture the
        home pose reached into failed every move of the run ("the robot starts closer to
        the cell than the planning clearance")."""
        station = self.scenario.station
        if station.initial_configuration in station.configurations_deg:
            return
        problem = configuration_problem(self.planner, station.initial_positions)
        if problem:
            names = ("robot", "initial_configuration")
            finding = self.at.field(names, f"{HOME}, where the robot starts: {problem}")
            if finding.line is None:
                line = self.at.field(("robot", "variant"), "").line
                finding = dataclasses.replace(finding, line=line)
            yield finding

    def reaches_from_stand(self, tree, agent, inputs) -> Iterator[Finding]:
        """Places and reaches farther from where the tree has the person stand than a
        hand reaches (hrc_drake.scenario.reach_from_stand)."""
        if self.scenario.human is None:
            return iter(())
        known = {(id(node), port): values for node, port, values in inputs}
        parents = parents_of(tree.node_list)

        def point(value: Known):
            pose = _resolved(agent, value.value) if isinstance(value.value, Pose) else None
            return None if pose is None else np.asarray(pose.position)

        def taken(pick, way):
            return self._taken(parents, way, known, pick, agent)

        def placing(pick, target, at_pick, picks, way):
            return self._placing(parents, way, known, pick, target, agent, at_pick, picks)

        start = self.scenario.human.start[:2]
        nodes = tree.node_list
        clips = self.performer.clips
        return reach_findings(self.at, nodes, known, point, start, clips, taken, placing)

    def robot_put_downs(self, tree, agent, inputs) -> Iterator[Finding]:
        """Parts the robot lets go of inside the cell's fixed geometry or an object lying
        there (hrc_drake.scenario.put_down_overlaps), and moves it cannot make with the part
        it holds (hrc_drake.scenario.robot_put_downs)."""
        known = {(id(node), port): values for node, port, values in inputs}
        nodes, resolve = tree.node_list, partial(_resolved, agent)
        yield from put_down_findings(nodes, known, resolve, self.solids, self.scene, self.at.read)
        areas = {name: self.scenario.area(name) for name in self.scenario.areas}
        objects = self.scene.objects
        yield from overlap_findings(
            nodes, known, resolve, self.solids, objects, areas, self.at.read
        )
        if self.robot_placed:
            yield from carried_move_findings(
                nodes, known, resolve, self._carried_reach, self.at.read
            )
            yield from carried_configuration_findings(
                nodes, known, self._carried_configuration, self.at.read
            )

    def belt_picks(self, tree, inputs) -> Iterator[Finding]:
        """Picks of what a belt carries off (hrc_drake.scenario.belt_picks)."""
        known = {(id(node), port): values for node, port, values in inputs}
        areas = {name: self.scenario.area(name) for name in self.scenario.areas}
        return belt_pick_findings(tree.node_list, known, areas, self.scenario.workpieces)

    def found_reaches(self, tree, agent, inputs) -> Iterator[Finding]:
        """Targets made from the objects a NextObject can find that the robot cannot reach
        (hrc_drake.scenario.found_targets)."""
        known = {(id(node), port): values for node, port, values in inputs}
        finds = partial(self._finds, known)
        resolve = partial(_resolved, agent)
        return found_reach_findings(
            tree.node_list, known, finds, resolve, self._found_reach, self.at.node
        )

    def _finds(self, known, finder) -> list[tuple[str, Pose]]:
        """(label, centre as its `pose` gives it) of each object at the start that the
        NextObject `finder` can find (`_found_by`)."""
        return [
            (f"{obj.label} in area '{area}' at {point_text(centre)}", Pose(tuple(centre)))
            for area, obj in self._found_by(finder, known)
            for centre in [[float(v) for v in obj.pose.translation()]]
        ]

    @cached_property
    def solids(self) -> dict[str, Solid]:
        """Each object type's shape."""
        return {name: Solid.of(kind) for name, kind in self.scenario.workpieces.types.items()}

    def _found_reach(self, target, free: bool, linear: bool, held: str | None) -> str:
        """Why the robot cannot reach a target made from a found object: the tool alone,
        else the part of type `held` it holds."""
        problem = self._reach_problem(target, free, linear)
        return problem or (self._carried_reach(target, free, held) if held else "")

    def _carried_reach(self, target, free: bool, kind: str) -> str:
        """Why the robot cannot reach `target` holding a part of type `kind` ("" when it
        can, or when the tool alone cannot either: that is said at the target already)."""
        if kind not in self.solids or self._reach_problem(target, free, False):
            return ""
        problem = self._reach_problem(target, free, False, kind)
        return holding(kind, problem) if problem else ""

    def _carried_configuration(self, name: str, kind: str) -> str:
        """Why the planner refuses to move the arm to the configuration `name` holding a
        part of type `kind` ("" when it does not, or the arm alone cannot go there either:
        that is said at the configuration)."""
        station = self.scenario.station
        if name not in station.configuration_names or kind not in self.solids:
            return ""
        q = station.configuration(name)
        if configuration_problem(self.planner, q):
            return ""
        problem = configuration_problem(self.planner, q, hanging_from_the_tool(self.solids[kind]))
        return holding(kind, problem) if problem else ""

    def detours(self, tree, agent, inputs) -> Iterator[Finding]:
        """Walks that go a long way round a gap a little too narrow for the person
        (hrc_drake.scenario.detours)."""
        if self.scenario.human is None:
            return iter(())
        known = {(id(node), port): values for node, port, values in inputs}
        start = self.scenario.human.start[:2]
        walk_end = partial(self._walk_end, agent)
        return detour_findings(tree.node_list, known, walk_end, start, self._detours)

    @cached_property
    def _detours(self) -> Detours:
        return Detours(self.scene.navigation)

    def _walk_end(self, agent, value: Known) -> tuple[float, float] | None:
        """Where a walk to `value` ends: the place nearest it with room, as the person's
        planner moves it (None: not known, or no place near has room)."""
        pose = _resolved(agent, value.value) if isinstance(value.value, Pose) else None
        if pose is None:
            return None
        x, y, _ = pose.position
        try:
            return self.scene.navigation.clear_spot(x, y, _heading(pose))
        except NoWay:
            return None

    def _taken(self, parents, way, known, pick, agent) -> list[tuple[str, np.ndarray, object]]:
        """The objects that a pick may take the `way` the tree went, each with its label,
        centre and what keeps the person from taking it (`_lying_in`)."""
        hands = _hands(known, pick)
        gone = self._not_found(object_source(pick, parents, way), parents, known)
        return [
            (label, obj.pose.translation(), partial(self._pick_problem, obj, agent, hands, gone))
            for label, obj in self._lying_in(parents, way, known, pick, agent)
        ]

    def _not_found(self, source, parents, known) -> list:
        """The objects at the start that are not there when `source` runs: those the
        NextObjects before it in a Fallback look for (they found none; a user's restocking
        SpawnObject was judged making a part inside the one on the board at the start, and
        a pick of a small housing a Fallback's second try finds is judged with the large
        ones its first try looked for gone), all those in their areas where their filter is
        not known (coexistence's restock, its filter made by a Script, was judged taken from
        between the two boxes it replaces)."""
        if not isinstance(source, NextObject | SpawnObject):
            return []
        return [
            obj
            for finder in failed_before(source, parents, NextObject)
            for _, obj in self._found_by(finder, known, unknown_filter=ANY_OBJECT)
        ]

    def _placing(self, parents, way, known, pick, target, agent, at_pick, picks=()):
        """What keeps the person from putting down at `target` what `pick` took the `way`
        the tree went: an object of the one type the NextObject it takes from filters for
        (or the SpawnObject makes: a user's KLT put down into a shelf's board, missed),
        held as the pick takes those of them lying in its area from where the person stands
        there (`at_pick`), when that is one way; held either way round when it is not (none
        lie there at the start: a part the robot's tree makes and puts there, whose drop
        into a floor bin the run refused, a user's cell); what any of `picks` (those that
        have run before the put-down) may have taken is gone from where it lay."""
        kind = finder_type(known, finder_of(pick, parents, way))
        if kind not in self.scenario.workpieces.types:
            return None
        hands = _hands(known, pick)
        taken = [obj for _, obj in self._lying_in(parents, way, known, pick, agent)]
        holds = {
            self._held_as(obj, agent, hands, stand) for obj in taken for _, _, stand in at_pick
        }
        held = holds.pop() if len(holds) == 1 else None
        gone = taken + [o for p in picks for _, o in self._lying_in(parents, way, known, p, agent)]
        return partial(self._place_problem, kind, hands, target, agent, held=held, taken=gone)

    def _held_as(self, obj, agent, hands: str, stand: Known | None) -> Hold:
        """How `hands` hold `obj` once taken from `stand` (its extents along the person's
        forward, sideways and up)."""
        _, _, yaw = self._standing_at(agent, stand, obj.pose.translation())
        hold = hold_of(self._grasp(obj, hands), yaw)
        return Hold(hold.hands, tuple(round(v, 6) for v in hold.size))

    def _grasp(self, obj, hands: str) -> Grasp:
        """How `hands` (the pick's port; auto: by the object) take `obj` where it lies."""
        kind = self.scenario.workpieces.types[obj.type]
        center, heading, size = box_at(obj.pose, kind.shape, kind.size)
        if hands == "auto":
            hands = grasp_hands(size, kind.mass, kind.attributes)
        return Grasp(hands, center, heading, size)

    def _place_problem(
        self,
        kind: str,
        hands: str,
        target,
        agent,
        stand: Known | None,
        held: Hold | None = None,
        taken=(),
    ) -> str:
        """Why the person standing at `stand` cannot put an object of type `kind`, held in
        `hands` (as `held` says, when known; else either way round as if taken facing it
        as they stand there: "" if one works), down at `target`, as the run would plan it:
        on top of the objects at the start lying there (hrc_drake.nodes.stacks; at the
        target as given, a tote put where another lay was planned inside it), but those the
        pick may have `taken`, which are gone from where they lay; "" when they can."""
        x, y, yaw = self._standing_at(agent, stand, target)
        shape = self.scenario.workpieces.types[kind]
        _, _, size = box_at(RigidTransform(), shape.shape, shape.size)
        if hands == "auto":
            hands = grasp_hands(size, shape.mass, shape.attributes)
        lying = [(obj.solid, obj.pose) for obj in self.scene.objects if obj not in taken]
        target = tuple(on_top_of(target, Solid.of(shape), lying))
        holds = (
            [held]
            if held
            else [
                hold_of(Grasp(hands, target, yaw + turn, size), yaw) for turn in (0.0, math.pi / 2)
            ]
        )
        clip = "place_table" if target[2] >= TABLE_HEIGHT else "place_floor"
        nearby = self._near(target, taken)
        problems = [
            self._planned_problem(
                AnimateCommand(0, clip, target=target, hold=hold, nearby=nearby), (x, y, yaw)
            )
            for hold in holds
        ]
        return "" if "" in problems else problems[0]

    def _lying_in(self, parents, way, known, pick, agent) -> list[tuple]:
        """The objects that `pick` may take the `way` the tree went, with their labels:
        those at the start of the type the NextObject that last wrote the entry the pick
        reads filters for (by type alone) in its known area, or the one the SpawnObject
        that did makes at its known pose, or the one its port names by number (`_numbered`);
        moved where a put-down of them since leaves them."""
        source = object_source(pick, parents, way)
        if isinstance(source, ActorPlace):
            return self._put_down(parents, way, known, source, agent)
        if source is UNKNOWN and held_at(pick, parents, way) is None:
            return self._numbered(known, pick)
        if not isinstance(source, NextObject | SpawnObject):
            return []
        where = f"{source.config.registration_id} at {source.config.file}:{source.config.line}"
        if isinstance(source, SpawnObject):
            return self._made(known, source, agent, where)
        return [
            (f"{obj.label} in area '{area}' ({where})", obj)
            for area, obj in self._found_by(source, known)
        ]

    def _numbered(self, known, pick) -> list[tuple[str, object]]:
        """The objects at the start whose ids `pick`'s port gives as a literal, with their
        labels: the run numbers the scenario's `objects` from 1 in their order (a user's
        pick of object 1 off a shelf's board, refused every time, was never judged). Only
        while no pick has run before it: one may have moved the object."""
        ids = {v.value for v in known.get((id(pick), "object_id"), ()) if v.origin.node is pick}
        return [
            (f"object {i + 1} (the {obj.label} of workpieces.objects[{i}])", obj)
            for obj in self.scene.objects
            for kind, i in [obj.names[1:3]]
            if kind == "objects" and i + 1 in ids
        ]

    def _found_by(self, finder, known, unknown_filter=()) -> list[tuple[str, object]]:
        """The objects at the start that the NextObject `finder` may find, with the name of
        the area each lies in (`_in_area`); where its filter is not known, those that
        `unknown_filter` (filter texts) lets through."""
        filters = [wanted.value for wanted in known.get((id(finder), "filter"), ())]
        return [
            (area.value.name, obj)
            for area in known.get((id(finder), "area"), ())
            for wanted in filters or unknown_filter
            for obj in self._in_area(area, parse_filter(wanted))
        ]

    def _made(self, known, spawn, agent, where: str) -> list[tuple]:
        """The object `spawn` makes at each of its known poses, with its label."""
        types = self.scenario.workpieces.types
        made = []
        for kind in known.get((id(spawn), "type"), ()):
            for value in known.get((id(spawn), "pose"), ()):
                pose = _resolved(agent, value.value) if isinstance(value.value, Pose) else None
                if kind.value in types and pose is not None:
                    label = f"{kind.value} made at {value} ({where})"
                    solid = Solid.of(types[kind.value])
                    made.append(
                        (label, InitialObject((), label, kind.value, solid, pose.to_transform()))
                    )
        return made

    def _put_down(self, parents, way, known, place, agent) -> list[tuple]:
        """What the pick before `place` may have taken, where `place` puts it down: at its
        known targets, on top of what lies there (as the run puts it, hrc_drake.nodes.stacks)."""
        config = place.config
        where = f"put down by {config.registration_id} at {config.file}:{config.line}"
        points = [_resolved(agent, v.value) for v in known.get((id(place), "target"), ())]
        moved = []
        held = held_at(place, parents, way)
        for label, obj in self._lying_in(parents, way, known, held, agent):
            lying = [(o.solid, o.pose) for o in self.scene.objects if o is not obj]
            moved += [
                (f"{label}, {where}", _moved(obj, on_top_of(p.position, obj.solid, lying)))
                for p in points
                if p is not None
            ]
        return moved

    def _in_area(self, area: Known, condition: dict) -> list:
        """The initial objects in a known area that a filter of their type alone takes."""
        if set(condition) - {"type"} or not isinstance(area.value, AreaRef):
            return []
        if area.value.name not in self.scenario.areas:
            return []
        region = self.scenario.area(area.value.name)
        return [
            obj
            for obj in self.scene.objects
            if condition.get("type", obj.type) == obj.type
            and region.contains(obj.pose.translation()[:2])
        ]

    def _pick_problem(self, obj, agent, hands: str, gone, stand: Known | None) -> str:
        """Why the person standing at `stand` (a walk's known target, facing as it says or
        the object; None: their start) cannot take `obj` there with `hands` (the pick's
        port), as the run would plan the pick, the objects `gone` gone; "" when they can."""
        x, y, yaw = self._standing_at(agent, stand, obj.pose.translation())
        grasp = self._grasp(obj, hands)
        clip = "pick_table" if grasp.center[2] >= TABLE_HEIGHT else "pick_floor"
        nearby = self._near(grasp.center, (obj, *self._lying_on(obj), *gone))
        command = AnimateCommand(0, clip, grasp=grasp, nearby=nearby)
        return self._planned_problem(command, (x, y, yaw))

    def _lying_on(self, taken) -> list:
        """The objects at the start lying on or in `taken` (`_lies_on`), and those lying on
        them in turn: whether they are still there when it is taken is the tree's doing (the
        machine cell's takes the checked parts out of the tote before it takes the tote;
        planned with them, the tote went 7.6 cm into a part; a stack's bottom tray is found
        only once the trays above it are gone, and planned with the top one, went 8.9 cm
        into it); the run refuses the pick if they are."""
        above, lower = [], [taken]
        while lower:
            below = lower.pop()
            on_it = [
                obj
                for obj in self.scene.objects
                if all(obj is not seen for seen in (taken, *above)) and _lies_on(obj, below)
            ]
            above += on_it
            lower += on_it
        return above

    def _planned_problem(self, command: AnimateCommand, stand) -> str:
        """Why the person standing at `stand` (x, y, yaw) cannot do `command`, as the run
        would plan it (refused where it goes into the furniture even with the head and arms
        kept out, which is worked out only where the plan itself goes in); "" when they can.
        Asked once per command and place (each way the tree goes asks again)."""
        key = (repr(command), tuple(stand))
        if key not in self.planned_problems:
            self.planned_problems[key] = self._plan_problem(command, stand)
        return self.planned_problems[key]

    def _plan_problem(self, command: AnimateCommand, stand) -> str:
        """`_planned_problem`'s answer: the plan taking over from the person standing at
        ease there, as the run's idle has them when the command comes (from a made-up
        upright pose, arms straight down, a pick off a shelf's board came clear, and the
        run refused it every time: the right arm 2.4 cm into the shelf, a user's cell: #26)."""
        performer = self.performer
        try:
            activity = plan_animation(performer, command, stand, 0.0)
        except Unreachable as error:
            return str(error)
        if not going_in(performer, activity, 0.0):
            return ""
        at_ease = plan_idle(performer, stand, 0.0, command.hold).pose(performer, 0.0)
        return going_in(performer, activity.blended_from(performer, at_ease, 0.0), 0.0)

    def _near(self, point, taken=()) -> tuple[Box, ...]:
        """The objects at the start near `point` but those `taken`, as a node tells the
        person (hrc_drake.nodes.person.NEARBY)."""
        types = self.scenario.workpieces.types
        return tuple(
            Box(
                *box_at(obj.pose, types[obj.type].shape, types[obj.type].size),
                name=f"{obj.label} at {point_text(obj.pose.translation())}",
            )
            for obj in self.scene.objects
            if all(obj is not other for other in taken)
            and np.hypot(*(obj.pose.translation()[:2] - np.asarray(point[:2]))) <= NEARBY
        )

    def _standing_at(self, agent, stand: Known | None, facing) -> tuple[float, float, float]:
        """Where the person stands and which way they face: where the walk to its target
        ends (the nearest place with room, as the run's walk moves it: judged from inside a
        table, a pick from it was a second line after the place's own), facing as it says or
        towards what they take (None: their start)."""
        if stand is None:
            x, y, yaw_deg = self.scenario.human.start
            return x, y, math.radians(yaw_deg)
        pose = _resolved(agent, stand.value)
        x, y = self._walk_end(agent, stand) or pose.position[:2]
        yaw = _heading(pose)
        return x, y, math.atan2(facing[1] - y, facing[0] - x) if yaw is None else yaw

    @cached_property
    def performer(self) -> Performer:
        """The person as the run has them: their body, clips and the cell's walkable floor."""
        return sized_performer(*self.scenario.human.size(), self.clips, self.scene.navigation)

    def of(self, agent, node, port: str, known: Known) -> Iterator[Finding]:
        value = known.value
        if isinstance(node, RobotMove | RobotMoveLinear) and port == "target":
            if self.robot_placed:
                yield from self._reach(agent, node, known)
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
        pose = _resolved(agent, known.value)
        inside = self.scene.inside_cell(pose.position) if pose is not None else None
        if inside is not None:
            what, depth = inside
            where = _xyz(pose.position)
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

    def _reach(self, agent, node, known: Known) -> Iterator[Finding]:
        pose = _resolved(agent, known.value)
        if pose is None:
            return
        target, free = tool_pose(pose)
        problem = self._reach_problem(target, free, isinstance(node, RobotMoveLinear))
        if problem:
            message = f"{known} at {_xyz(target.translation())}: {problem}"
            yield self.at.read(node, "target", known, message, target.translation())

    def _reach_problem(self, target, free: bool, linear: bool, held: str | None = None) -> str:
        """reach_problem's answer, once per target (one pose may be read by many nodes),
        holding a part of type `held` when given."""
        key = (*target.GetAsMatrix34().round(9).ravel(), free, linear, held)
        if key not in self.reach_problems:
            part = None if held is None else hanging_from_the_tool(self.solids[held])
            self.reach_problems[key] = reach_problem(self.planner, target, free, linear, part)
        return self.reach_problems[key]

    def _standing(self, agent, node, known: Known) -> Iterator[Finding]:
        """A place to walk to: room to stand and turn there (floor-level locations are
        checked as locations, in cell_findings), and a walk from the person's start."""
        pose = _resolved(agent, known.value)
        if pose is None:
            return
        x, y, z = pose.position
        yaw = _heading(pose)
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


def _heading(pose: Pose) -> float | None:
    """The yaw (rad) a pose turns to (None: it gives no orientation)."""
    if pose.quaternion is None:
        return None
    R = pose.to_transform().rotation().matrix()
    return math.atan2(R[1, 0], R[0, 0])


def _resolved(agent, value) -> Pose | None:
    """A Pose with its location name resolved (None: a name the scenario lacks, which
    loading reports)."""
    try:
        return agent.resolve_pose(value)
    except KeyError:
        return None


def _xyz(p) -> str:
    return "(" + ", ".join(f"{v:.2f}" for v in p) + ")"


def _moved(obj, point):
    """`obj` (an initial object) with its centre at `point`, turned as it was."""
    return dataclasses.replace(obj, pose=RigidTransform(obj.pose.rotation(), point))


def _hands(known, pick) -> str:
    """The hands a pick takes with, as its `hand` port says (auto: by the object)."""
    return ([v.value for v in known.get((id(pick), "hand"), ())] or ["auto"])[0]


def _lies_on(upper, lower) -> bool:
    """Whether the scene object `upper` lies on or in `lower`: higher than its middle, its
    bottom at most ON_IT above its top, and their outlines overlapping as the run's
    NextObject counts one lying on another (hrc_drake.nodes.stacks.covered)."""
    up, down = upper.pose.translation()[2], lower.pose.translation()[2]
    bottom, top = up - upper.solid.height / 2, down + lower.solid.height / 2
    return (
        up > down
        and bottom <= top + ON_IT
        and overlaps(
            footprint(upper.solid, upper.pose), footprint(lower.solid, lower.pose), COVER_OVERLAP
        )
    )
