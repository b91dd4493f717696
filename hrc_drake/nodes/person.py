"""Person nodes: the thesis system's ActorAnimation, ActorMovement, IsCalled and SetCalledTo,
and ActorCarry; the base of every command to the person, which tells the person what the
hands hold, so they carry it in the carry posture. The targeted actions (pick, place,
reach, hand over) are in hrc_drake.nodes.targeted.
"""

import numpy as np

from hrc_drake.bt import ConditionNode, InputPort, Range, Status, SyncActionNode
from hrc_drake.human import messages as human
from hrc_drake.human.grasp import hold_of
from hrc_drake.human.in_the_way import robot_boxes
from hrc_drake.nodes.command import CommandNode
from hrc_drake.tree_types import Pose
from hrc_drake.wiring import HUMAN
from hrc_drake.workpieces import messages as wp
from hrc_drake.workpieces.geometry import yaw_of

NEARBY = 0.8
"""m: objects closer than this (floor distance) to a target are ones the arms may touch."""
STILL = 0.01
"""m/s: an object the robot holds is one the arms keep out of while it is this still (the
robot stopped with it over where the person works: a forearm went 14.9 cm through a carton
hanging from a stopped gripper, a user's palletizing cell); moving, it will be elsewhere by
the time the arms get there."""
HOLDERS = {human.ONE_HAND: wp.RIGHT_HAND, human.BOTH_HANDS: wp.BOTH_HANDS}
HANDS_OF = {holder: hands for hands, holder in HOLDERS.items()}


class PersonCommandNode(CommandNode):
    """A command to the HumanActor; halting it cancels the running action."""

    actor = HUMAN
    commands = (HUMAN,)
    cancel_command = human.CancelCommand

    def held(self) -> wp.ObjectStatus | None:
        """The object in the person's hands, if any."""
        status = self.agent.workpieces
        if status is None:
            return None
        return next((o for o in status.objects if o.holder in HANDS_OF), None)

    def hold(self) -> human.Hold | None:
        """What the person's hands hold, as the person needs to know it."""
        obj = self.held()
        if obj is None:
            return None
        return hold_of(grasp_of(obj, HANDS_OF[obj.holder]), self._heading())

    def objects_near(
        self, point, taken: int | None = None, robot: bool = True
    ) -> tuple[human.Box, ...]:
        """The objects within NEARBY of `point` on the floor (not `taken`) that are free or
        held still by the robot, and the robot while it stands still (`robot`): what the
        person's arms, and what the hands hold, keep out of there."""
        status = self.agent.workpieces
        objects = status.objects if status is not None else ()
        boxes = [
            human.Box(*_way_of(obj), name=_named(obj))
            for obj in objects
            if _in_the_way(obj) and obj.id != taken
        ]
        if robot:
            boxes += self.robot_at_rest()
        return tuple(b for b in boxes if np.hypot(*np.subtract(b.center[:2], point[:2])) <= NEARBY)

    def robot_at_rest(self) -> list[human.Box]:
        """The robot's parts, while it stands still, as boxes (a hand went 3.7 cm into a
        stopped gripper picking a part beside it, a user's machine-tending cell; walking
        past an arm stopped stretched out over the floor, the chest went 16.8 cm into it)."""
        return robot_boxes(*self.agent.safety.robot_parts) if self._robot_still() else []

    def _robot_still(self) -> bool:
        status = self.agent.safety
        return status is not None and status.robot_speed < STILL and len(status.robot_parts) > 0

    def _heading(self) -> float:
        status = self.agent.human
        return status.base_pose[2] if status is not None else 0.0

    def _position(self) -> tuple[float, float]:
        """Where the person stands: the objects near there are what an animation's arms
        keep out of (inspecting at a work table with three kits stacked on it, a hand went
        14.1 cm into one, a kitting cell of our own)."""
        status = self.agent.human
        return tuple(status.base_pose[:2]) if status is not None else (0.0, 0.0)


def grasp_of(obj: wp.ObjectStatus, hands: str) -> human.Grasp:
    """How `hands` take `obj` (a cylinder is taken like the box around it)."""
    return human.Grasp(hands, *box_of(obj))


def box_of(obj: wp.ObjectStatus):
    """An object's centre, heading and box extents (a cylinder: the box around it)."""
    return box_at(obj.pose, obj.shape, obj.size)


def _way_of(obj: wp.ObjectStatus):
    """`box_of` the object, stretched on to where a belt brings it to rest: the arms keep
    out of where it will be (a hand went 1.0 cm into a carton that came to rest behind the
    one taken off a queueing belt's end after the pick had been planned, a user's
    palletizing cell)."""
    center, yaw, size = box_of(obj)
    if obj.rests_at is None:
        return center, yaw, size
    shift = obj.rests_at.translation() - obj.pose.translation()
    axes = obj.pose.rotation().matrix()[:, :2].T
    grown = (size[0] + abs(shift @ axes[0]), size[1] + abs(shift @ axes[1]), size[2])
    return tuple(np.add(center, shift / 2)), yaw, grown


def box_at(pose, shape: str, size):
    """The centre, heading and box extents of an object of `shape` and `size` at `pose`."""
    size = size if shape == "box" else (2 * size[0], 2 * size[0], size[1])
    return tuple(pose.translation()), yaw_of(pose.rotation()), tuple(size)


class ActorAnimation(PersonCommandNode):
    """Plays an animation in place; SUCCESS when it completed, FAILURE when it was
    cancelled or rejected (e.g. an unknown animation name)."""

    ports = (
        InputPort("animation_name", str),
        InputPort(
            "animation_speed",
            float,
            default=1.0,
            description="2 = twice as fast",
            accepts=Range(0, above=True),
        ),
    )

    def command(self, seq: int):
        return human.AnimateCommand(
            seq,
            self.get_input("animation_name"),
            self.get_input("animation_speed"),
            hold=self.hold(),
            nearby=self.objects_near(self._position()),
        )


class ActorMovement(PersonCommandNode):
    """Turns towards the target, walks there and turns to its orientation (a target
    without orientation: keep facing the walking direction)."""

    ports = (
        InputPort("animation_name", str, default="walk"),
        InputPort(
            "animation_distance",
            float,
            default=0.0,
            description="ground covered by one walk cycle; 0 = the clip's own",
            accepts=Range(0),
        ),
        InputPort("target", Pose, description="x;y;z[;qw;qx;qy;qz] or location name"),
    )

    def command(self, seq: int):
        target = self.agent.resolve_pose(self.get_input("target"))
        distance = self.get_input("animation_distance")
        hold = self.hold()
        self._seen = self._still_ids()
        return human.MoveCommand(
            seq,
            target_position=target.position,
            target_quaternion=target.quaternion or human.NULL_QUATERNION,
            animation_name=self.get_input("animation_name"),
            animation_distance=distance if distance > 0 else None,
            hold=hold,
            nearby=self._near_the_ends(target.position),
            in_the_way=self._still_over_the_floor(),
        )

    def _near_the_ends(self, target) -> tuple[human.Box, ...]:
        """The objects near where the walk starts and where it ends: the arms keep out of
        them as the person turns there (a hand swung 1.2 cm into a KLT just put down on a
        cart, turning to walk off: a user's hand-over cell), and what the hands hold out of
        them where the walk ends."""
        boxes = (*self.objects_near(self._position()), *self.objects_near(target))
        return tuple(dict.fromkeys(boxes))

    def on_running(self) -> Status:
        """The walk's outcome; meanwhile, when the robot comes to a stop, the person is told
        it and what it holds are in the way (a person walked through a carton hanging from a
        gripper stopped over the walkway, a user's palletizing cell)."""
        still = self._still_ids()
        if still - self._seen:
            boxes = self._still_over_the_floor()
            self.agent.send(self.actor, lambda seq: human.InTheWayCommand(seq, boxes))
        self._seen = still
        return super().on_running()

    def _still_ids(self) -> set:
        """What stands still over the floor, by name: the robot at rest, and by id the
        objects (checked at every tick of a walk, so without building any boxes)."""
        robot = {"robot"} if self._robot_still() else set()
        return robot | {obj.id for obj in self._standing()}

    def _still_over_the_floor(self) -> tuple[human.Box, ...]:
        """What stands still over the floor besides the cell: the robot at rest, what it
        holds still and the objects on the cell. The cell's map knows only the furniture:
        a walk went through a crate on the floor (19.6 cm), and one object standing out
        from its furniture where the body is wider than at the furniture's heights (a KLT
        on a rack's board, at the thighs) is as much in the way as the furniture."""
        boxes = (human.Box(*box_of(obj), name=_named(obj)) for obj in self._standing())
        return (*self.robot_at_rest(), *boxes)

    def _standing(self) -> list[wp.ObjectStatus]:
        """The objects the walk keeps out of: free, or held still by the robot (not what
        the person holds: it goes with them)."""
        status = self.agent.workpieces
        objects = status.objects if status is not None else ()
        return [obj for obj in objects if _in_the_way(obj)]


class ActorCarry(ActorMovement):
    """Walks to the target holding an object with both hands (the carry clip)."""

    ports = (
        InputPort("animation_name", str, default="carry"),
        *ActorMovement.ports[1:],
    )


class IsCalled(ConditionNode):
    """SUCCESS while the person is being called (by the robot)."""

    def tick(self) -> Status:
        return Status.SUCCESS if _called(self.agent) else Status.FAILURE


class SetCalledTo(SyncActionNode):
    """Sets the person's called flag; always SUCCESS."""

    ports = (InputPort("state", bool),)
    commands = (HUMAN,)

    def tick(self) -> Status:
        called = self.get_input("state")
        seq = self.agent.send(HUMAN, lambda seq: human.SetCalledCommand(seq, called))
        self.agent.called_sent = (seq, called, self.agent.now)
        return Status.SUCCESS


def _called(agent) -> bool:
    """The person's called flag, as this tree's own last SetCalledTo left it until the
    person has taken it (a user's loop reset the call and asked IsCalled again in the same
    tick: it read the flag the person last reported, and the person walked to the hand-over
    spot again for nothing), else as the person reports it."""
    status, sent = agent.human, agent.called_sent
    if sent is not None and (status is None or _not_yet_taken(status, sent)):
        return sent[1]
    return status is not None and status.called


def _not_yet_taken(status, sent: tuple[int, bool, float]) -> bool:
    """Whether the person's report predates the SetCalledTo `sent` (seq, flag, time)."""
    seq, _, sent_at = sent
    return status.results.outcome_of(seq) is None and status.time <= sent_at


NODES = (ActorAnimation, ActorMovement, ActorCarry, IsCalled, SetCalledTo)


def _in_the_way(obj: wp.ObjectStatus) -> bool:
    """Whether the person's arms keep out of `obj`: free, or held STILL by the robot."""
    if obj.holder is None:
        return True
    return obj.holder not in HANDS_OF and np.linalg.norm(obj.velocity.translational()) < STILL


def _named(obj: wp.ObjectStatus) -> str:
    """How a refusal names `obj` ('carton 8', 'carton 8 the robot holds')."""
    name = f"{obj.type} {obj.id}"
    return name if obj.holder is None else f"{name} the {obj.holder} holds"
