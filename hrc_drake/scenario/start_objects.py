"""The objects in the cell at the start, as validate's checks of the trees ask for them:
which a NextObject may find, which lie on one taken. The robot's targets made from found
objects (hrc_drake.scenario.robot_findings) and the person's picks
(hrc_drake.scenario.person_picks) ask the same questions of the same objects."""

from hrc_drake.known_values import Known
from hrc_drake.nodes.objects import parse_filter
from hrc_drake.nodes.stacks import COVER_OVERLAP
from hrc_drake.scenario.cell_findings import CellScene, InitialObject
from hrc_drake.scenario.schema import Scenario
from hrc_drake.tree_types import AreaRef, Pose
from hrc_drake.workpieces.geometry import Solid, footprint, overlaps

ON_IT = 0.01
"""m: an object whose bottom is at most this far above the top of what is taken lies on it
(`_lies_on`)."""


class StartObjects:
    """The scene's initial objects, looked up by what finds them and what lies on them."""

    def __init__(self, scenario: Scenario, scene: CellScene):
        self.scenario = scenario
        self.objects = scene.objects

    def found_by(self, finder, known, unknown_filter=(), made=()) -> list[tuple[str, object]]:
        """The objects at the start, and those `made` (by a SpawnObject, `made_by`, or left
        by a put-down), that the NextObject `finder` may find, with the name of the area
        each lies in (`in_area`); where its filter is not known, those that `unknown_filter`
        (filter texts) lets through."""
        filters = [wanted.value for wanted in known.get((id(finder), "filter"), ())]
        return [
            (area.value.name, obj)
            for area in known.get((id(finder), "area"), ())
            for wanted in filters or unknown_filter
            for obj in self.in_area(area, parse_filter(wanted), made)
        ]

    def in_area(self, area: Known, condition: dict, made=()) -> list:
        """The initial objects, and those `made`, in a known area that a filter of their
        type alone takes."""
        if set(condition) - {"type"} or not isinstance(area.value, AreaRef):
            return []
        if area.value.name not in self.scenario.areas:
            return []
        region = self.scenario.area(area.value.name)
        return [
            obj
            for obj in (*self.objects, *made)
            if condition.get("type", obj.type) == obj.type
            and region.contains(obj.pose.translation()[:2])
        ]

    def made_by(self, spawn, known, resolve) -> list[tuple[str, InitialObject]]:
        """The object the SpawnObject `spawn` makes at each of its known poses (`resolve`: a
        Pose to the scenario's, None when it names no location), with its label."""
        types = self.scenario.workpieces.types
        where = f"{spawn.config.registration_id} at {spawn.config.file}:{spawn.config.line}"
        made = []
        for kind in known.get((id(spawn), "type"), ()):
            for value in known.get((id(spawn), "pose"), ()):
                pose = resolve(value.value) if isinstance(value.value, Pose) else None
                if kind.value in types and pose is not None:
                    label = f"{kind.value} made at {value} ({where})"
                    solid = Solid.of(types[kind.value])
                    made.append(
                        (label, InitialObject((), label, kind.value, solid, pose.to_transform()))
                    )
        return made

    def lying_on(self, taken) -> list:
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
                for obj in self.objects
                if all(obj is not seen for seen in (taken, *above)) and _lies_on(obj, below)
            ]
            above += on_it
            lower += on_it
        return above


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
