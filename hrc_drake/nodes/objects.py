"""Object nodes: trees create, remove and track workpieces through the objects status.

SpawnObject/DespawnObject command the Workpieces system (its answer comes within one of its
updates); ObjectAttribute, CountObjects and NextObject read the objects status, which is how
one agent finds what the other left somewhere. A filter is `key=value;key=value`, where the
key `type` is the object type and other keys are attributes (`defective=true`).
"""

from hrc_drake.areas import Area
from hrc_drake.bt import InputPort, OneOf, OutputPort, Range, Status, SyncActionNode
from hrc_drake.bt.ports import value_to_text
from hrc_drake.messages import ResultLog
from hrc_drake.nodes.command import CommandNode
from hrc_drake.nodes.stacks import covered
from hrc_drake.tree_types import Pose
from hrc_drake.wiring import WORKPIECES
from hrc_drake.workpieces import messages as wp


def parse_filter(text: str) -> dict[str, str]:
    """`type=box;fragile=true` -> {"type": "box", "fragile": "true"}."""
    pairs = [item.split("=", 1) for item in text.split(";") if item.strip()]
    if any(len(pair) != 2 for pair in pairs):
        raise ValueError(f"a filter is key=value;key=value, got '{text}'")
    return {key.strip(): value.strip() for key, value in pairs}


def matches(obj: wp.ObjectStatus, wanted: dict[str, str]) -> bool:
    for key, value in wanted.items():
        actual = obj.type if key == "type" else obj.attributes.get(key)
        if actual is None or value_to_text(actual) != value:
            return False
    return True


OBJECT_ID = Range(wp.FIRST_ID, why="objects are numbered from 1: the scenario's in their order")
"""The object ids a port takes: a user's `object_id="0"`, meant as the first object, failed its
pick 123 times in a run that validate had passed."""


class ObjectsNode(SyncActionNode):
    """Reads the objects status; FAILURE while no Workpieces system is wired."""

    def free_objects_in(self, area_port: str, filter_port: str) -> list[wp.ObjectStatus]:
        """Objects not held by anyone, lying in the area and matching the filter, oldest
        first."""
        status = self.agent.workpieces
        if status is None:
            return []
        area = self.agent.area(self.get_input(area_port))
        try:
            wanted = parse_filter(self.get_input(filter_port))
        except ValueError as error:
            raise self.error(str(error), port=filter_port) from None
        return [
            obj
            for obj in status.objects
            if obj.holder is None
            and area.contains(obj.pose.translation()[:2])
            and matches(obj, wanted)
        ]


AREA_PORT = InputPort("area", Area, description="area name or triangles")
FILTER_PORT = InputPort("filter", str, default="", description="key=value;... (type, attributes)")


class CountObjects(ObjectsNode):
    """Counts the free objects in an area that match a filter (always SUCCESS)."""

    ports = (AREA_PORT, FILTER_PORT, OutputPort("count", int))

    def tick(self) -> Status:
        self.set_output("count", len(self.free_objects_in("area", "filter")))
        return Status.SUCCESS


class NextObject(ObjectsNode):
    """The oldest free object in an area matching a filter with nothing resting on it (an
    object under another is not offered: a person takes the one on top first); FAILURE
    when there is none. Its pose is the centre without orientation, so a RobotMove
    to it (offset to the top face) keeps the tool pointing down."""

    ports = (
        AREA_PORT,
        FILTER_PORT,
        OutputPort("object_id", int),
        OutputPort("pose", Pose, description="the object's centre (position only)"),
    )

    def tick(self) -> Status:
        found = self.free_objects_in("area", "filter")
        under = covered(self.agent.workpieces.objects) if found else {}
        free = [obj for obj in found if obj.id not in under]
        self.failure_reason = _all_under_others(found, under) if found and not free else ""
        if not free:
            return Status.FAILURE
        self.set_output("object_id", free[0].id)
        self.set_output("pose", Pose(tuple(float(v) for v in free[0].pose.translation())))
        return Status.SUCCESS


def _all_under_others(found, under: dict[int, int]) -> str:
    """Why a NextObject finds none where objects its filter takes lie (a user's tray with
    parts on it was never taken, and the run said nothing of why)."""
    pairs = ", ".join(f"object {under[obj.id]} on object {obj.id}" for obj in found)
    return (
        f"every object here that the filter takes has another lying on it ({pairs}): "
        "the one on top is taken first"
    )


class ObjectAttribute(ObjectsNode):
    """Reads one attribute of an object (its `type` too); FAILURE if either is unknown."""

    ports = (
        InputPort("object_id", int, accepts=OBJECT_ID),
        InputPort("attribute", str),
        OutputPort("value", str),
    )

    def tick(self) -> Status:
        status = self.agent.workpieces
        obj = status.object(self.get_input("object_id")) if status is not None else None
        name = self.get_input("attribute")
        value = obj.type if obj is not None and name == "type" else None
        if obj is not None and value is None:
            value = obj.attributes.get(name)
        if value is None:
            return Status.FAILURE
        self.set_output("value", value_to_text(value))
        return Status.SUCCESS


class HeldObject(ObjectsNode):
    """The object a holder holds (the robot's vacuum cup or the person's hands); FAILURE
    when it holds nothing. This is how the person finds the box the robot presents at a
    hand-over, which NextObject (free objects only) cannot see."""

    ports = (
        InputPort(
            "holder",
            str,
            default=wp.ROBOT_HOLDER,
            description=", ".join(wp.HOLDERS),
            accepts=OneOf(wp.HOLDERS),
        ),
        OutputPort("object_id", int),
        OutputPort("pose", Pose, description="the object's centre (position only)"),
    )

    def tick(self) -> Status:
        holder = self.get_input("holder")
        status = self.agent.workpieces
        held = status.held_by(holder) if status is not None else None
        if held is None:
            return Status.FAILURE
        self.set_output("object_id", held.id)
        self.set_output("pose", Pose(tuple(float(v) for v in held.pose.translation())))
        return Status.SUCCESS


class WorkpiecesCommandNode(CommandNode):
    """A command to the Workpieces system, which answers per issuer (this agent's tree)."""

    actor = WORKPIECES
    commands = (WORKPIECES,)

    def results(self, status) -> ResultLog:
        return status.results_of(self.agent.issuer)


class SpawnObject(WorkpiecesCommandNode):
    """Creates an object of `type` at `pose` or at a random place in `area`; the new id is
    written to `object_id`. FAILURE when the scenario's capacity is used up."""

    ports = (
        InputPort("type", str, description="object type from the scenario"),
        InputPort("pose", Pose, default=None, description="where (or give an area)"),
        InputPort("area", str, default="", description="scenario area to drop it in"),
        InputPort("attributes", str, default="", description="key=value;... overrides"),
        OutputPort("object_id", int),
    )

    def command(self, seq: int):
        pose = self.get_input("pose")
        return wp.Spawn(
            seq,
            self.get_input("type"),
            pose=self.agent.transform(pose) if pose is not None else None,
            area=self.get_input("area"),
            attributes=parse_filter(self.get_input("attributes")),
        )

    def succeeded(self) -> Status:
        self.set_output("object_id", self.result().object_id)
        return Status.SUCCESS


class DespawnObject(WorkpiecesCommandNode):
    """Removes an object from the simulation (e.g. when it leaves the cell)."""

    ports = (InputPort("object_id", int, accepts=OBJECT_ID),)

    def command(self, seq: int):
        return wp.Despawn(seq, self.get_input("object_id"))


class MoveObject(WorkpiecesCommandNode):
    """Sets a free object down at `pose` (upright; it settles on what is below): squaring a
    box up in its place, or a grip that slipped knocking it askew. FAILURE when it is
    held."""

    ports = (
        InputPort("object_id", int, accepts=OBJECT_ID),
        InputPort("pose", Pose, description="where its centre goes, and which way it faces"),
    )

    def command(self, seq: int):
        pose = self.agent.transform(self.get_input("pose"))
        return wp.Move(seq, self.get_input("object_id"), pose)


NODES = (
    CountObjects,
    NextObject,
    HeldObject,
    ObjectAttribute,
    SpawnObject,
    DespawnObject,
    MoveObject,
)
