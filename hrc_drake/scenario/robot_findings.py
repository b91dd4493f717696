"""validate's checks of what the robot's tree has the robot do: every named configuration
and the robot's start, every known target for reach (the planner's own inverse kinematics,
the tool held as the node holds it), the targets made from the objects a NextObject finds
(hrc_drake.scenario.found_targets) and what the robot lets go of, where, and the moves it
makes holding a part (hrc_drake.scenario.robot_put_downs)."""

import dataclasses
from collections.abc import Iterator
from functools import cached_property, partial

from hrc_drake.known_values import Known
from hrc_drake.motion.planner import MotionPlanner
from hrc_drake.motion.reach import configuration_problem, reach_problem
from hrc_drake.nodes.objects import SpawnObject
from hrc_drake.nodes.robot import RobotMoveLinear, tool_pose
from hrc_drake.scenario.cell_findings import CellScene
from hrc_drake.scenario.found_targets import found_reach_findings
from hrc_drake.scenario.known_poses import resolved
from hrc_drake.scenario.located import Finding, Locator
from hrc_drake.scenario.put_down_overlaps import overlap_findings
from hrc_drake.scenario.reach_from_stand import point_text
from hrc_drake.scenario.robot_put_downs import (
    carried_configuration_findings,
    carried_move_findings,
    hanging_from_the_tool,
    holding,
    put_down_findings,
)
from hrc_drake.scenario.schema import Scenario
from hrc_drake.scenario.start_objects import StartObjects
from hrc_drake.seeding import stream
from hrc_drake.station import HOME
from hrc_drake.tree_types import Pose
from hrc_drake.wiring import ROBOT_MOTION
from hrc_drake.workpieces.geometry import Solid


@dataclasses.dataclass
class RobotChecks:
    """The robot's checks of one validate, sharing the run's planner (made only when a
    check needs it) and what it said of each target (`reach_problems`: one pose may be read
    by many nodes)."""

    scenario: Scenario
    scene: CellScene
    at: Locator
    objects: StartObjects
    robot_placed: bool
    reach_problems: dict[tuple, str] = dataclasses.field(default_factory=dict)

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

    def put_downs(self, tree, agent, inputs) -> Iterator[Finding]:
        """Parts the robot lets go of inside the cell's fixed geometry or an object lying
        there (hrc_drake.scenario.put_down_overlaps), and moves it cannot make with the part
        it holds (hrc_drake.scenario.robot_put_downs)."""
        known = {(id(node), port): values for node, port, values in inputs}
        nodes, resolve = tree.node_list, partial(resolved, agent)
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

    def found_reaches(self, tree, agent, inputs) -> Iterator[Finding]:
        """Targets made from the objects a NextObject can find that the robot cannot reach
        (hrc_drake.scenario.found_targets)."""
        known = {(id(node), port): values for node, port, values in inputs}
        resolve = partial(resolved, agent)
        made = [
            obj
            for spawn in tree.node_list
            if isinstance(spawn, SpawnObject)
            for _, obj in self.objects.made_by(spawn, known, resolve)
        ]
        finds = partial(self._finds, known, made)
        return found_reach_findings(
            tree.node_list, known, finds, resolve, self._found_reach, self.at.node
        )

    def _finds(self, known, made, finder) -> list[tuple[str, Pose]]:
        """(label, centre as its `pose` gives it) of each object at the start, or `made` by
        the tree's SpawnObjects at a known pose, that the NextObject `finder` can find
        (`StartObjects.found_by`): a user's machine made its parts where the robot could not
        reach, and validate said ok."""
        return [
            (f"{obj.label} in area '{area}' at {point_text(centre)}", Pose(tuple(centre)))
            for area, obj in self.objects.found_by(finder, known, made=made)
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

    def reach(self, agent, node, known: Known) -> Iterator[Finding]:
        """A target the robot's tool cannot reach, read by a RobotMove or RobotMoveLinear."""
        pose = resolved(agent, known.value)
        if pose is None:
            return
        target, free = tool_pose(pose)
        problem = self._reach_problem(target, free, isinstance(node, RobotMoveLinear))
        if problem:
            message = f"{known} at {point_text(target.translation())}: {problem}"
            yield self.at.read(node, "target", known, message, target.translation())

    def _reach_problem(self, target, free: bool, linear: bool, held: str | None = None) -> str:
        """reach_problem's answer, once per target (one pose may be read by many nodes),
        holding a part of type `held` when given."""
        key = (*target.GetAsMatrix34().round(9).ravel(), free, linear, held)
        if key not in self.reach_problems:
            part = None if held is None else hanging_from_the_tool(self.solids[held])
            self.reach_problems[key] = reach_problem(self.planner, target, free, linear, part)
        return self.reach_problems[key]
