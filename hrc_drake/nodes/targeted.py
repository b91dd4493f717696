"""The person's targeted actions: a clip aimed at a point (pick, place, reach, hand-over)
that, at the clip's contact event (`grasp`, `release`, `extended`), tells the Workpieces
system to attach, release or transfer the object, so the object changes hands at the moment
the hand is there. Which hands take an object follows from its size, mass and attributes
(hrc_drake.human.grasp)."""

from abc import abstractmethod

import numpy as np

from hrc_drake.bt import InputPort, OneOf, Status
from hrc_drake.human import messages as human
from hrc_drake.human.grasp import grasp_hands, hold_of, object_center_in_holder
from hrc_drake.messages import RUNNING, SUCCEEDED
from hrc_drake.nodes.objects import OBJECT_ID
from hrc_drake.nodes.person import HOLDERS, PersonCommandNode, grasp_of
from hrc_drake.nodes.stacks import on_top_of_what_lies_there
from hrc_drake.tree_types import Pose
from hrc_drake.wiring import HUMAN, WORKPIECES
from hrc_drake.workpieces import messages as wp

TABLE_HEIGHT = 0.5
"""Targets below this height are picked or placed with the floor clips (a squat)."""


class ObjectGone(Exception):
    """The object an action is to take is not in the world (any more)."""


class ObjectMoving(ObjectGone):
    """The object a pick is to take rides a belt: the hands, aimed where it was, would
    close where it no longer is (a user's palm went 14.4 cm into a carton the belt carried
    into it)."""


def riding(obj: wp.ObjectStatus) -> str:
    """Why a pick of `obj` is refused while a belt carries it ("" while it stands still,
    falls or is held), and what the user can do instead."""
    speed = float(np.linalg.norm(obj.velocity.translational()))
    if obj.holder is not None or obj.support is None or speed == 0.0:
        return ""
    below = obj.supporting_object
    on = f"belt '{obj.support}'" if below is None else f"object {below} on a belt"
    moving = f"{obj.type} {obj.id} is moving on {on} at {speed:.2f} m/s"
    if obj.rests_at is not None:
        x, y, z = obj.rests_at.translation()
        return f"{moving}: take it where the belt brings it to rest, at ({x:.2f}, {y:.2f}, {z:.2f})"
    return (
        f"{moving}, which carries it off: take it before it goes on the belt, or have the "
        "belt queue what it carries (at_end: queue) and take it where it comes to rest"
    )


class TargetedAction(PersonCommandNode):
    """Plays `clip()` aimed at `target_point()`; at the clip event `contact_event` it sends
    `object_command(seq)` to the Workpieces system. SUCCESS when both succeeded."""

    commands = (HUMAN, WORKPIECES)
    contact_event = ""
    """Clip event at which the object changes hands ("": the action moves no object)."""

    @abstractmethod
    def clip(self) -> str:
        """The clip to play."""

    @abstractmethod
    def target_point(self) -> tuple[float, float, float]:
        """Where the clip aims the hand(s), in the world."""

    def object_command(self, seq: int):
        """The Workpieces command at the contact event (actions that have one)."""
        raise TypeError(f"{type(self).__name__} moves no object")

    def on_start(self) -> Status:
        """Sends the command; FAILURE at once, saying so, when the object is gone (a belt
        took it away, or someone else did)."""
        self.contact_seq = None
        try:
            self.playing = self.clip()
            return super().on_start()
        except ObjectGone as gone:
            self.failure_reason = str(gone)
            return Status.FAILURE

    def command(self, seq: int):
        target = self.target_point()
        return human.AnimateCommand(
            seq,
            self.playing,
            target=target,
            hold=self.hold(),
            grasp=self.grasp(),
            nearby=self.nearby(target),
        )

    def nearby(self, target) -> tuple[human.Box, ...]:
        """The free objects near `target` (not the one the action takes): the person's arms
        keep out of them."""
        return self.objects_near(target, self.taken_id())

    def grasp(self) -> human.Grasp | None:
        """What the clip takes (None: it takes nothing)."""
        return None

    def on_running(self) -> Status:
        if self.contact_seq is None and self._contact_event_fired():
            try:
                self.contact_seq = self.agent.send(WORKPIECES, self.object_command)
            except ObjectGone as gone:
                return self._gone_at_contact(gone)
        status = super().on_running()
        if status is not Status.SUCCESS or not self.contact_event:
            return status
        if self.contact_seq is None:
            self.failure_reason = f"the {self.playing} clip ended before its '{self.contact_event}'"
            return Status.FAILURE
        return self._contact_result()

    def _gone_at_contact(self, gone: ObjectGone) -> Status:
        """FAILURE, saying so, when the object went away while the hands went to it (the
        robot or a belt took it); the person stops the clip rather than close on nothing."""
        self.failure_reason = f"{gone} at the clip's '{self.contact_event}'"
        self.agent.send(self.actor, self.cancel_command)
        return Status.FAILURE

    def _contact_event_fired(self) -> bool:
        status = self.agent.human
        return (
            bool(self.contact_event)
            and self.outcome() == RUNNING
            and self.contact_event in status.activity_events
        )

    def _contact_result(self) -> Status:
        """The objects' answer to the command at the contact moment (why, when it failed)."""
        status = self.agent.workpieces
        result = status.results_of(self.agent.issuer).result_of(self.contact_seq)
        if result is None or result.outcome == RUNNING:
            return Status.RUNNING
        return Status.SUCCESS if result.outcome == SUCCEEDED else self.failed(result)

    def taken_id(self) -> int | None:
        """The object the action is about (None: it is about none)."""
        names = {port.name for port in self.ports}
        return self.get_input("object_id") if "object_id" in names else None

    def taken(self) -> wp.ObjectStatus:
        obj = self.agent.workpieces.object(self.get_input("object_id"))
        if obj is None:
            raise ObjectGone(f"no object {self.get_input('object_id')} (gone or never made)")
        return obj

    def object_point(self) -> tuple[float, float, float]:
        return tuple(self.taken().pose.translation())

    def taking_grasp(self) -> human.Grasp:
        """Both hands or one, as the port says or (auto) as the object's geometry says."""
        obj = self.taken()
        hands = self.get_input("hand")
        if hands == "auto":
            hands = grasp_hands(obj.size, obj.mass, obj.attributes)
        return grasp_of(obj, hands)

    def holder_and_center(self):
        """The holder that takes the object and where its centre goes in the holder's frame."""
        grasp = self.grasp()
        hold = hold_of(grasp, self._heading())
        return HOLDERS[grasp.hands], object_center_in_holder(hold)


TAKE_OR_GIVE = OneOf(("take", "give"))
HAND_PORT = InputPort(
    "hand",
    str,
    default="auto",
    description="auto (from the object), right or both",
    accepts=OneOf(("auto", *HOLDERS)),
)


class ActorPick(TargetedAction):
    """Picks up an object (table or floor clip by its height) into the hand(s); fails at once
    while the hands hold something."""

    ports = (InputPort("object_id", int, accepts=OBJECT_ID), HAND_PORT)
    contact_event = "grasp"

    def on_start(self) -> Status:
        """FAILURE at once, saying so, when the person's hands already hold something: played
        through, the pick took the hands off what they held (the objects refuse the grasp
        only when the hands close)."""
        held = self.held()
        if held is not None:
            self.failure_reason = f"{held.holder} already holds object {held.id}"
            return Status.FAILURE
        return super().on_start()

    def clip(self) -> str:
        return "pick_table" if self.object_point()[2] >= TABLE_HEIGHT else "pick_floor"

    def taken(self) -> wp.ObjectStatus:
        """The object, refused (ObjectMoving) while a belt carries it: at once when the
        pick starts, at the hands' closing when the belt set it off since."""
        obj = super().taken()
        reason = riding(obj)
        if reason:
            raise ObjectMoving(reason)
        return obj

    def target_point(self):
        return self.object_point()

    def grasp(self) -> human.Grasp:
        return self.taking_grasp()

    def object_command(self, seq: int):
        holder, center = self.holder_and_center()
        return wp.Attach(seq, holder, self.get_input("object_id"), center=center)


class ActorPlace(TargetedAction):
    """Puts what the hands hold down with its centre at a target point (one hand or both,
    as they hold it); it settles on the surface, or on what already lies there."""

    ports = (InputPort("target", Pose, description="where the object's centre goes"),)
    contact_event = "release"

    def clip(self) -> str:
        return "place_table" if self.target_point()[2] >= TABLE_HEIGHT else "place_floor"

    def target_point(self):
        point = self.agent.transform(self.get_input("target")).translation()
        held = self.held()
        if held is None or self.agent.workpieces is None:
            return tuple(point)
        return tuple(on_top_of_what_lies_there(point, held, self.agent.workpieces.objects))

    def object_command(self, seq: int):
        held = self.held()
        return wp.Detach(seq, held.holder if held is not None else wp.BOTH_HANDS)


class ActorReach(TargetedAction):
    """Reaches one arm to a point in front (into a workspace, to straighten a part); with
    `object_id` and `place`, the hand squares that object up there when it is on it."""

    ports = (
        InputPort("target", Pose, description="point to reach"),
        InputPort(
            "object_id", int, default=None, description="an object to square up", accepts=OBJECT_ID
        ),
        InputPort("place", Pose, default=None, description="where that object is set down"),
    )

    @property
    def contact_event(self) -> str:
        return "reached" if self.get_input("object_id") is not None else ""

    def clip(self) -> str:
        return "reach"

    def target_point(self):
        return tuple(self.agent.transform(self.get_input("target")).translation())

    def taken_id(self) -> int | None:
        """None: the hand moves the object where it stands (it is not taken)."""
        return None

    def object_command(self, seq: int):
        place = self.agent.transform(self.get_input("place"))
        return wp.Move(seq, self.get_input("object_id"), place)


class ActorHandOver(TargetedAction):
    """Hand-over with the robot: extends the hands to the object at the hand-over point
    and takes it (`take`: the palms close on its faces, the robot lets go once they hold
    it) or gives what the hands hold to the robot's cup (`give`)."""

    ports = (
        InputPort("object_id", int, accepts=OBJECT_ID),
        InputPort(
            "direction", str, default="take", description="take or give", accepts=TAKE_OR_GIVE
        ),
        HAND_PORT,
    )
    contact_event = "extended"

    def clip(self) -> str:
        return "hand_over"

    def target_point(self):
        return self.object_point()

    def takes(self) -> bool:
        return self.get_input("direction") == "take"

    def grasp(self) -> human.Grasp | None:
        return self.taking_grasp() if self.takes() else None

    def nearby(self, target) -> tuple[human.Box, ...]:
        """As any targeted action's, but the hands go to the robot's cup."""
        return self.objects_near(target, self.taken_id(), robot=False)

    def object_command(self, seq: int):
        if not self.takes():
            return wp.Transfer(seq, self.get_input("object_id"), wp.ROBOT_HOLDER)
        holder, center = self.holder_and_center()
        return wp.Transfer(seq, self.get_input("object_id"), holder, center=center)


NODES = (ActorPick, ActorPlace, ActorReach, ActorHandOver)
