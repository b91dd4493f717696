"""Workpieces command and status messages (abstract-valued ports of the Workpieces system).

Several issuers (the robot's and the person's behavior trees, the robot's vacuum gripper,
hrc_drake.wiring) each hold their recent commands on their own input port. Workpieces acts on
a command whose `seq` is newer than the last one it saw from that issuer; every command
finishes within one update, so its outcome is `succeeded`, `failed` (sound, but not possible
now: capacity, unknown id, too far, too heavy) or `rejected` (meaningless: unknown type,
holder or area), from the shared vocabulary of `hrc_drake.messages`.

Holders are the robot's vacuum cup (grasp frame: the tool's `tcp`, z out of the cup) and the
person's hands: one hand holds in a level frame at its grasp point turned with the person,
both hands in a frame at their grasp points' midpoint, y from the right hand to the left
(rolling with the hands' line), x level. An object's frame is at its centre; the cup's
grasp surface is its top face.
"""

import math
from dataclasses import dataclass, field

from pydrake.geometry import GeometryId
from pydrake.math import RigidTransform
from pydrake.multibody.math import SpatialVelocity

from hrc_drake.messages import ResultLog

FIRST_ID = 1
"""The id of the first object: the scenario's `workpieces.objects` in their order, then
what the trees make."""

ROBOT_HOLDER = "robot"
"""The robot's vacuum cup as a holder of objects."""
LEFT_HAND = "left_hand"
RIGHT_HAND = "right_hand"
BOTH_HANDS = "both_hands"
PERSON_HOLDERS = (LEFT_HAND, RIGHT_HAND, BOTH_HANDS)
HOLDERS = (ROBOT_HOLDER, *PERSON_HOLDERS)

GRASPABLE = "graspable"
"""Attribute: an object whose `graspable` attribute is false cannot be attached."""

COUPLING = "coupling"
"""Attribute: how well hands hold an object of this type, one of COUPLINGS (NIOSH's coupling;
the person's ergonomic scores use it)."""
COUPLINGS = ("good", "fair", "poor")

Attributes = dict[str, float | bool | str]


@dataclass(frozen=True)
class HandPoses:
    """The person's hand grasp frames in the world, when they were sampled (None: now) and
    which way the person faces (yaw, rad).

    A person updated at a lower rate than Workpieces gives its sample time, so that held
    objects are extrapolated from the right instant instead of moving in steps."""

    left: RigidTransform
    right: RigidTransform
    time: float | None = None
    heading: float = 0.0


@dataclass(frozen=True)
class Spawn:
    """Create an object of `type` at `pose`, or at a random place in the scenario area `area`.

    The object settles onto the highest surface below it; `attributes` override the type's.
    The new object's id is the command result's `object_id`.
    """

    seq: int
    type: str
    pose: RigidTransform | None = None
    area: str = ""
    attributes: Attributes = field(default_factory=dict)


@dataclass(frozen=True)
class Despawn:
    """Remove object `object_id` from the simulation (wherever it is, even when held)."""

    seq: int
    object_id: int


@dataclass(frozen=True)
class Attach:
    """`holder` grasps an object: `object_id`, or with None the graspable object at its grasp
    frame (for the vacuum cup: whose top face is at the cup). Fails when the object is out of
    reach, held by someone else, or heavier than `max_mass` (kg)."""

    seq: int
    holder: str
    object_id: int | None = None
    max_mass: float = math.inf
    center: tuple[float, float, float] | None = None
    """Where the object's centre goes in the holder's frame (None: where it is now)."""


@dataclass(frozen=True)
class Detach:
    """`holder` lets go of `object_id` (None: whatever it holds); the object drops and settles."""

    seq: int
    holder: str
    object_id: int | None = None


@dataclass(frozen=True)
class Transfer:
    """Hand-over of a held object between the robot and the person, to `to_holder`.

    Allowed only while both parties' grasp frames are within the hand-over tolerance of the
    object; `max_mass` limits what the receiver takes (the robot's payload).
    """

    seq: int
    object_id: int
    to_holder: str
    max_mass: float = math.inf
    center: tuple[float, float, float] | None = None
    """Where the object's centre goes in the receiver's frame (None: where it is now)."""


@dataclass(frozen=True)
class Move:
    """Sets free object `object_id` down at `pose` (upright; it settles on what is below): a
    box squared up in its place, or knocked askew by a grip that slipped."""

    seq: int
    object_id: int
    pose: RigidTransform


WorkpiecesCommand = Spawn | Despawn | Attach | Detach | Transfer | Move


@dataclass(frozen=True)
class ObjectStatus:
    """One live object. `velocity` is spatial (angular, linear) in the world frame at the
    object's origin; `holder` is None when the object is free; `support` names what a free
    object rests on (a surface or model name, a conveyor, or `object:<id>`), None while it
    is held or falling. `geometry_id` is its SceneGraph geometry (for distance queries, e.g.
    a carried object as part of its holder's body) and `mass` its mass in kg."""

    id: int
    type: str
    pose: RigidTransform
    velocity: SpatialVelocity
    holder: str | None
    support: str | None
    attributes: Attributes
    mass: float = 0.0
    geometry_id: GeometryId | None = None
    size: tuple[float, ...] = ()
    """Box extents (x, y, z) or cylinder (radius, length), as the object type gives them."""
    shape: str = "box"
    rests_at: RigidTransform | None = None
    """Where a queueing belt brings the object to rest, while it moves on it (None: at rest,
    held, falling, or on a belt that carries it off)."""

    @property
    def supporting_object(self) -> int | None:
        return object_id_of_support(self.support)


@dataclass(frozen=True)
class HeldObject:
    """An object in the person's hands as a run's record keeps it (what ergonomics needs:
    its load and how it is held); `coupling` is the type's `coupling` attribute, "" if it
    has none."""

    id: int
    type: str
    mass: float
    holder: str
    coupling: str = ""


@dataclass(frozen=True)
class WorkpiecesStatus:
    """Every live object (by increasing id), each issuer's recent command results, and how
    many more objects of each type can be spawned."""

    time: float
    objects: tuple[ObjectStatus, ...]
    results: dict[str, ResultLog]
    """Per issuer its recent command results (the objects answer each issuer apart)."""
    free_slots: dict[str, int]

    def object(self, object_id: int) -> ObjectStatus | None:
        return next((o for o in self.objects if o.id == object_id), None)

    def held_by(self, holder: str) -> ObjectStatus | None:
        return next((o for o in self.objects if o.holder == holder), None)

    @property
    def person_holds(self) -> tuple[HeldObject, ...]:
        return tuple(
            HeldObject(o.id, o.type, o.mass, o.holder, str(o.attributes.get(COUPLING, "")))
            for o in self.objects
            if o.holder in PERSON_HOLDERS
        )

    def results_of(self, issuer: str) -> ResultLog:
        return self.results.get(issuer, ResultLog())


OBJECT_SUPPORT_PREFIX = "object:"


def object_support(object_id: int) -> str:
    return f"{OBJECT_SUPPORT_PREFIX}{object_id}"


def object_id_of_support(support: str | None) -> int | None:
    if support is None or not support.startswith(OBJECT_SUPPORT_PREFIX):
        return None
    return int(support[len(OBJECT_SUPPORT_PREFIX) :])
