"""validate's checks of the person's picks and put-downs where the tree has them stand:
the objects each pick may take (found by a NextObject among those at the start and those
put down before it, made by a SpawnObject, named by number, or put down by a place before
it), planned as the run plans them (hrc_drake.human.planning) from the person at ease
there, and refused where the run would refuse them (hrc_drake.human.going_in); the reaches
too far from where they stand (hrc_drake.scenario.reach_from_stand).

Longer than 300 lines: the picks and the put-downs after them share the object lookups
and the plans made once per command and place."""

import dataclasses
import math
from collections.abc import Iterator
from functools import cached_property, partial

import numpy as np
from pydrake.math import RigidTransform

from hrc_drake.human.aiming import Unreachable
from hrc_drake.human.going_in import going_in
from hrc_drake.human.grasp import grasp_hands, hold_of
from hrc_drake.human.messages import AnimateCommand, Box, Grasp, Hold, MoveCommand
from hrc_drake.human.navigation import NoWay
from hrc_drake.human.performer import Performer, sized_performer
from hrc_drake.human.planning import plan_animation, plan_idle, plan_movement
from hrc_drake.known_values import Known
from hrc_drake.nodes.objects import NextObject, SpawnObject
from hrc_drake.nodes.person import NEARBY, box_at
from hrc_drake.nodes.stacks import on_top_of
from hrc_drake.nodes.targeted import TABLE_HEIGHT, ActorPlace
from hrc_drake.scenario.cell_findings import CellScene
from hrc_drake.scenario.known_poses import heading, resolved
from hrc_drake.scenario.located import Finding, Locator
from hrc_drake.scenario.reach_from_stand import point_text, reach_findings
from hrc_drake.scenario.schema import Scenario
from hrc_drake.scenario.start_objects import StartObjects
from hrc_drake.scenario.switch_ways import finder_type
from hrc_drake.scenario.tree_ways import (
    UNKNOWN,
    all_before,
    failed_before,
    finder_of,
    held_at,
    object_source,
    parents_of,
)
from hrc_drake.tree_types import Pose
from hrc_drake.workpieces.geometry import Solid

ANY_OBJECT = ("",)
"""A NextObject filter that lets every object through."""


@dataclasses.dataclass
class PersonPicks:
    """The person's checks of one validate, sharing the person as the run has them and
    the plans made of each command at each place (`planned_problems`)."""

    scenario: Scenario
    scene: CellScene
    at: Locator
    objects: StartObjects
    clips: dict
    planned_problems: dict[tuple, str] = dataclasses.field(default_factory=dict)

    def reaches_from_stand(self, tree, agent, inputs) -> Iterator[Finding]:
        """Places and reaches farther from where the tree has the person stand than a
        hand reaches (hrc_drake.scenario.reach_from_stand)."""
        if self.scenario.human is None:
            return iter(())
        known = {(id(node), port): values for node, port, values in inputs}
        parents = parents_of(tree.node_list)

        def point(value: Known):
            pose = resolved(agent, value.value) if isinstance(value.value, Pose) else None
            return None if pose is None else np.asarray(pose.position)

        def taken(pick, way):
            return self._taken(parents, way, known, pick, agent)

        def placing(pick, target, at_pick, picks, way):
            return self._placing(parents, way, known, pick, target, agent, at_pick, picks)

        start = self.scenario.human.start[:2]
        nodes = tree.node_list
        clips = self.performer.clips
        return reach_findings(self.at, nodes, known, point, start, clips, taken, placing)

    def walk_end(self, agent, value: Known) -> tuple[float, float] | None:
        """Where a walk to `value` ends: the place nearest it with room, as the person's
        planner moves it (None: not known, or no place near has room)."""
        pose = resolved(agent, value.value) if isinstance(value.value, Pose) else None
        if pose is None:
            return None
        x, y, _ = pose.position
        try:
            return self.scene.navigation.clear_spot(x, y, heading(pose))
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
            for _, obj in self.objects.found_by(finder, known, unknown_filter=ANY_OBJECT)
        ]

    def _placing(self, parents, way, known, pick, target, agent, at_pick, picks=()):
        """What keeps the person from putting down at `target` what `pick` took the `way`
        the tree went: an object of the one type the NextObject it takes from filters for
        (or the SpawnObject makes: a user's KLT put down into a shelf's board, missed),
        held as the pick takes those of them lying in its area from where the person stands
        there (`at_pick`), when that is one way; held either way round when it is not (none
        lie there at the start: a part the robot's tree makes and puts there, whose drop
        into a floor bin the run refused, a user's cell); what any of `picks` (those that
        have run before the put-down) may have taken is gone from where it lay, and so is
        what lay on it (the run takes only what has nothing on it: a user's full KLT, brought
        where the robot had emptied one, was planned 7.9 cm into the parts taken off it)."""
        kind = finder_type(known, finder_of(pick, parents, way))
        if kind not in self.scenario.workpieces.types:
            return None
        hands = _hands(known, pick)
        taken = [obj for _, obj in self._lying_in(parents, way, known, pick, agent)]
        holds = {
            self._held_as(obj, agent, hands, stand) for obj in taken for _, _, stand in at_pick
        }
        held = holds.pop() if len(holds) == 1 else None
        origins = {
            self._standing_at(agent, stand, obj.pose.translation())
            for obj in taken
            for _, _, stand in at_pick
        }
        came_from = origins.pop() if len(origins) == 1 else None
        gone = taken + [o for p in picks for _, o in self._lying_in(parents, way, known, p, agent)]
        gone += [above for obj in gone for above in self.objects.lying_on(obj)]
        return partial(
            self._place_problem, kind, hands, target, agent, held=held, taken=gone, came=came_from
        )

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
        came=None,
    ) -> str:
        """Why the person standing at `stand` cannot put an object of type `kind`, held in
        `hands` (as `held` says, when known; else either way round as if taken facing it
        as they stand there: "" if one works), down at `target`, as the run would plan it:
        on top of the objects at the start lying there (hrc_drake.nodes.stacks; at the
        target as given, a tote put where another lay was planned inside it), but those the
        pick may have `taken`, which are gone from where they lay; "" when they can. They
        stand where the carry there ends (`_carried_to`, from where they took it: `came`)."""
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
                AnimateCommand(0, clip, target=target, hold=hold, nearby=nearby),
                (x, y, yaw) if stand is None else self._carried_to((x, y, yaw), hold, came, nearby),
            )
            for hold in holds
        ]
        return "" if "" in problems else problems[0]

    def _carried_to(self, stand, hold: Hold, came, nearby) -> tuple[float, float, float]:
        """Where a carry to `stand` (x, y, yaw) of what is held as `hold` ends, from where
        the person took it (`came`; None: not known, a metre behind, coming straight on):
        short of it where what the hands hold would end in what stands there, as the run
        stops (hrc_drake.human.planning.plan_movement; a carton carried to a labelling
        table, judged put down from the walk's target, 4.3 cm in the table: the run's carry
        stopped 12 cm short and put it down)."""
        x, y, yaw = stand
        start = came or (x - math.cos(yaw), y - math.sin(yaw), yaw)
        facing = (math.cos(yaw / 2), 0.0, 0.0, math.sin(yaw / 2))
        command = MoveCommand(0, (x, y), facing, "carry", hold=hold, nearby=nearby)
        try:
            return plan_movement(self.performer, command, start, 0.0).final_pose
        except Unreachable:
            return stand

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
        if isinstance(source, SpawnObject):
            return self.objects.made_by(source, known, partial(resolved, agent))
        where = f"{source.config.registration_id} at {source.config.file}:{source.config.line}"
        return [
            (f"{obj.label} in area '{area}' ({where})", obj)
            for area, obj in self.objects.found_by(
                source, known, made=self._left(source, parents, way, known, agent)
            )
        ]

    def _left(self, finder, parents, way, known, agent) -> list:
        """The objects the put-downs that have run before `finder` leave, labelled with
        where they lie: a NextObject finds them as it finds those at the start (an area is a
        floor polygon: a user's KLT put on a rack's low board was found by the look for a
        full one on the board above, and the run refused its pick, 7.0 cm into the full
        one, which validate never judged)."""
        return [
            dataclasses.replace(obj, label=label)
            for place in all_before(finder, parents, ActorPlace)
            for label, obj in self._put_down(parents, way, known, place, agent)
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

    def _put_down(self, parents, way, known, place, agent) -> list[tuple]:
        """What the pick before `place` may have taken, where `place` puts it down: at its
        known targets, on top of what lies there (as the run puts it, hrc_drake.nodes.stacks)."""
        config = place.config
        where = f"put down by {config.registration_id} at {config.file}:{config.line}"
        points = [resolved(agent, v.value) for v in known.get((id(place), "target"), ())]
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

    def _pick_problem(self, obj, agent, hands: str, gone, stand: Known | None) -> str:
        """Why the person standing at `stand` (a walk's known target, facing as it says or
        the object; None: their start) cannot take `obj` there with `hands` (the pick's
        port), as the run would plan the pick, the objects `gone` gone; "" when they can."""
        x, y, yaw = self._standing_at(agent, stand, obj.pose.translation())
        grasp = self._grasp(obj, hands)
        clip = "pick_table" if grasp.center[2] >= TABLE_HEIGHT else "pick_floor"
        nearby = self._near(grasp.center, (obj, *self.objects.lying_on(obj), *gone))
        command = AnimateCommand(0, clip, grasp=grasp, nearby=nearby)
        return self._planned_problem(command, (x, y, yaw))

    def _planned_problem(self, command: AnimateCommand, stand) -> str:
        """Why the person standing at `stand` (x, y, yaw) cannot do `command`, as the run
        would plan it (refused where it goes into the furniture even with the head and arms
        kept out); "" when they can. Asked once per command and place (each way the tree
        goes asks again)."""
        key = (repr(command), tuple(stand))
        if key not in self.planned_problems:
            self.planned_problems[key] = self._plan_problem(command, stand)
        return self.planned_problems[key]

    def _plan_problem(self, command: AnimateCommand, stand) -> str:
        """`_planned_problem`'s answer: the plan taking over from the person standing at
        ease there, as the run's idle has them when the command comes (from a made-up
        upright pose, arms straight down, a pick off a shelf's board came clear, and the
        run refused it every time: the right arm 2.4 cm into the shelf, a user's cell: #26).
        Judged blended even where the plan itself keeps out, as the run judges it: a 95th-
        percentile man's pick of a KLT off a table came clear, and the run refused it 13
        times, the arms kept out of the table as they came up from at ease leaving the
        palms 8 cm from it (a user's kitting cell)."""
        performer = self.performer
        try:
            activity = plan_animation(performer, command, stand, 0.0)
        except Unreachable as error:
            return str(error)
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
        pose = resolved(agent, stand.value)
        x, y = self.walk_end(agent, stand) or pose.position[:2]
        yaw = heading(pose)
        return x, y, math.atan2(facing[1] - y, facing[0] - x) if yaw is None else yaw

    @cached_property
    def performer(self) -> Performer:
        """The person as the run has them: their body, clips and the cell's walkable floor."""
        return sized_performer(*self.scenario.human.size(), self.clips, self.scene.navigation)


def _moved(obj, point):
    """`obj` (an initial object) with its centre at `point`, turned as it was."""
    return dataclasses.replace(obj, pose=RigidTransform(obj.pose.rotation(), point))


def _hands(known, pick) -> str:
    """The hands a pick takes with, as its `hand` port says (auto: by the object)."""
    return ([v.value for v in known.get((id(pick), "hand"), ())] or ["auto"])[0]
