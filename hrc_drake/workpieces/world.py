"""The workpieces world as plain Python: the fixed rules of a run and the state at one time.

`Workcell` holds what does not change during a run (object types and their SceneGraph
slots, surfaces, belts, areas, tolerances, the issuers in the order their commands are
carried out, the seed every random stream comes from) and says what the world looks like at
any time (`status`). `World` is the state at one update time (live pieces, each holder's
last grasp-frame samples, each issuer's last command and results) and is immutable, so
Drake keeps it as abstract state without copying; between updates every piece moves on with
the velocity planned for it (`Piece.drift`, `since`), so outputs are smooth without reading
inputs (no direct feedthrough). How an update changes the world: hrc_drake.workpieces.update.
`holder_frames` and `person_frames` turn the robot's tool pose and the person's hands into
the grasp frames the holders carry by.
"""

import dataclasses
import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np
from pydrake.math import RigidTransform, RotationMatrix
from pydrake.multibody.math import SpatialVelocity

from hrc_drake.areas import Area
from hrc_drake.messages import ResultLog
from hrc_drake.seeding import substream
from hrc_drake.workpieces.config import WorkpiecesConfig, problems
from hrc_drake.workpieces.conveyors import Belt
from hrc_drake.workpieces.geometry import Drift, Solid, footprint, twist_between
from hrc_drake.workpieces.messages import (
    PERSON_HOLDERS,
    ROBOT_HOLDER,
    Attributes,
    HandPoses,
    ObjectStatus,
    WorkpiecesStatus,
    object_support,
)
from hrc_drake.workpieces.surfaces import Supports, Surface
from hrc_drake.yaml_check import field_path

LAYOUT_STREAM, SPAWN_STREAM = 0, 1
"""Spawn keys of the random streams below the workpieces' seed."""


@dataclass(frozen=True)
class Kind:
    """An object type as the world uses it, with the SceneGraph slots reserved for it."""

    name: str
    solid: Solid
    mass: float
    attributes: Attributes
    slots: range


@dataclass(frozen=True)
class Piece:
    """A live object. `pose` is at the world's time, `velocity` is planned for the interval
    after it; `grip` is the object's pose in its holder's grasp frame while held. A piece
    never changes (changes make new pieces), so its footprint is computed once."""

    id: int
    type: str
    solid: Solid
    slot: int
    pose: RigidTransform
    velocity: SpatialVelocity
    holder: str | None
    grip: RigidTransform | None
    support: str | None
    attributes: Attributes
    waits_for: tuple[str, ...] = ()
    """The person's palms that let go of it: set down on a running belt, it stays where
    it is until they are out of its way (hrc_drake.workpieces.settling.palms_let_go)."""

    @cached_property
    def bottom(self) -> float:
        return self.pose.translation()[2] - self.solid.height / 2

    def in_place(self, **changes) -> "Piece":
        """The piece with `changes` that leave its place on the floor plane as it is (its
        height, support or velocity): the new piece keeps this one's footprint, if made
        (settling changes a conveyed piece three times an update)."""
        piece = dataclasses.replace(self, **changes)
        if "footprint" in self.__dict__:  # where cached_property keeps it
            piece.__dict__["footprint"] = self.footprint
        return piece

    @cached_property
    def footprint(self) -> np.ndarray:
        return footprint(self.solid, self.pose)

    @cached_property
    def moving(self) -> bool:
        """Whether the piece has a velocity planned (asked at every update and evaluation)."""
        return bool(self.velocity.get_coeffs().any())

    @cached_property
    def drift(self) -> Drift:
        """The piece moving on from its pose at the world's time (see `since`)."""
        return Drift(self.pose, self.velocity)

    @cached_property
    def top(self) -> Surface:
        """The piece's top face as a support for others."""
        return Surface(object_support(self.id), self.bottom + self.solid.height, self.footprint)


@dataclass(frozen=True)
class HolderSample:
    """A holder's grasp frame as last received: its pose at `time` (when it was sampled),
    and the sample before it (pose, time), whose difference gives the velocity that
    extrapolates between samples. The velocity is worked out only when something uses it
    (a held object, a grasp): most updates none does."""

    pose: RigidTransform
    time: float
    before: tuple[RigidTransform, float] | None = None
    """The previous sample's pose and time; None for a holder's first sample."""

    @cached_property
    def velocity(self) -> SpatialVelocity:
        if self.before is None:
            return SpatialVelocity.Zero()
        pose, time = self.before
        return twist_between(pose, self.pose, self.time - time)


Sampled = tuple[RigidTransform, float | None]
"""A holder's pose and the time it was sampled (None: now)."""


@dataclass(frozen=True)
class World:
    """Everything that changes: live objects, holders' last samples, issuers' last commands."""

    time: float
    pieces: dict[int, Piece]
    next_id: int
    holders: dict[str, HolderSample]
    seen: dict[str, int]
    results: dict[str, ResultLog]

    def __deepcopy__(self, memo):
        """Never modified after construction, so copies can share it (Drake clones state)."""
        return self

    @cached_property
    def at_rest(self) -> bool:
        """Whether every object rests on something, free and without a planned velocity (a
        belt's queue included) and with no palms to wait for (they go at any update): found
        once per world, which lasts many updates."""
        return all(
            piece.holder is None
            and piece.support is not None
            and not piece.moving
            and not piece.waits_for
            for piece in self.pieces.values()
        )


def since(world: World, time: float) -> float:
    """How long the world's objects have moved on from their poses at `time` (never back)."""
    return max(time - world.time, 0.0)


class Workcell:
    """The fixed rules of the workpieces world of one run."""

    def __init__(
        self,
        config: WorkpiecesConfig,
        surfaces: list[Surface],
        seed: np.random.SeedSequence,
        issuers: tuple[str, ...] = (),
        areas: dict[str, Area] | None = None,
    ):
        found = problems(config)
        if found:
            (path, message), *_ = found
            raise ValueError(f"{field_path(('workpieces', *path))}: {message}")
        self.config = config
        self.issuers = tuple(issuers)
        self.areas = dict(areas or {})
        self.seed = seed
        self.kinds = _kinds(config)
        self.belts = {name: Belt.of(name, c) for name, c in config.conveyors.items()}
        belts = [belt.surface for belt in self.belts.values()]
        self.supports = Supports([*surfaces, *belts], belts=set(self.belts))

    def solids(self) -> dict[str, Solid]:
        """Each object type's shape, by type name."""
        return {name: kind.solid for name, kind in self.kinds.items()}

    def random(self, *key: int) -> np.random.Generator:
        """A Generator of its own for `key` below the workpieces' seed."""
        return np.random.default_rng(substream(self.seed, *key))

    def pose_at(self, piece: Piece, world: World, time: float) -> RigidTransform:
        return piece.drift.after(since(world, time))

    def status(self, world: World, time: float, geometry_ids=()) -> WorkpiecesStatus:
        """What the world looks like at `time`; `geometry_ids` are the slots' geometries."""
        return StatusOfWorld(self, world, geometry_ids).at(time)

    def rest_places(self, world: World, moving: list[Piece]) -> dict[int, RigidTransform]:
        """Where each of the `moving` pieces that rides a queueing belt comes to rest
        (`ObjectStatus.rests_at`): only those belts are planned (the world changes at every
        update while anything is carried)."""
        places, pieces = {}, world.pieces.values()
        for name in {p.support for p in moving} & self.belts.keys():
            belt = self.belts[name]
            advances = belt.rest_places(belt.riders(pieces), belt.held_over(pieces))
            for piece in moving:
                if piece.id in advances and piece.support == name:
                    shift = np.array([*(advances[piece.id] * belt.axis), 0.0])
                    pose = piece.pose
                    places[piece.id] = RigidTransform(pose.rotation(), pose.translation() + shift)
        return places

    def object_status(
        self, piece: Piece, world: World, time: float, geometry_ids, rests_at=None
    ) -> ObjectStatus:
        return ObjectStatus(
            id=piece.id,
            type=piece.type,
            pose=self.pose_at(piece, world, time),
            velocity=piece.velocity,
            holder=piece.holder,
            support=piece.support,
            attributes=piece.attributes,
            mass=self.kinds[piece.type].mass,
            geometry_id=geometry_ids[piece.slot] if geometry_ids else None,
            size=piece.solid.size,
            shape=piece.solid.shape,
            rests_at=rests_at,
        )


class StatusOfWorld:
    """One world's status at any time: only the moving objects are made again at each time
    (the status port is evaluated at many times), and the objects at rest only when their
    piece changed since the `before` world's (while an object is carried, the world changes
    at every update, the others stay the same pieces)."""

    def __init__(self, cell: Workcell, world: World, geometry_ids=(), before=None):
        self.world = world
        self._cell, self._geometry_ids = cell, geometry_ids
        made = before._resting if before is not None else {}
        self._resting = {}
        """piece id: (the piece, its status) for every piece at rest"""
        self._objects, self._moving = [], []
        for k, piece in enumerate(world.pieces.values()):
            if piece.moving:
                self._moving.append((k, piece))
                self._objects.append(None)
                continue
            known, status = made.get(piece.id, (None, None))
            if known is not piece:
                status = cell.object_status(piece, world, world.time, geometry_ids)
            self._resting[piece.id] = (piece, status)
            self._objects.append(status)
        self._rest_places = cell.rest_places(world, [p for _, p in self._moving])
        self._results = dict(world.results)
        used = [p.type for p in world.pieces.values()]
        self._free = {name: len(kind.slots) - used.count(name) for name, kind in cell.kinds.items()}

    def at(self, time: float) -> WorkpiecesStatus:
        objects = self._objects
        if self._moving:
            objects = list(objects)
            for k, piece in self._moving:
                objects[k] = self._cell.object_status(
                    piece, self.world, time, self._geometry_ids, self._rest_places.get(piece.id)
                )
        return WorkpiecesStatus(time, tuple(objects), self._results, self._free)


def _kinds(config: WorkpiecesConfig) -> dict[str, Kind]:
    kinds, start = {}, 0
    for name, t in config.types.items():
        slots = range(start, start + t.capacity)
        kinds[name] = Kind(name, Solid.of(t), t.mass, dict(t.attributes), slots)
        start += t.capacity
    return kinds


def holder_frames(tool: RigidTransform | None, person: dict[str, Sampled]) -> dict[str, Sampled]:
    """Grasp frame of every present holder: the robot's tool pose, copied (an input port's
    value may be overwritten in place when it is evaluated again), and the person's
    (`person_frames`)."""
    frames = {} if tool is None else {ROBOT_HOLDER: (RigidTransform(tool), None)}
    return frames | person


def person_frames(hands: HandPoses | tuple | None) -> dict[str, Sampled]:
    """The person's grasp frames: one hand's level (an object in one hand stays upright) at
    its grasp point facing the person's heading; both hands' at their midpoint, facing away
    from the body (x, level), y from the right hand to the left (rolled with the hands'
    line, as an object held rigidly between the palms is); none while `hands` is empty or
    None (the person has none)."""
    if not hands:
        return {}
    facing = RotationMatrix.MakeZRotation(hands.heading)
    p_left, p_right = hands.left.translation(), hands.right.translation()
    left, right = RigidTransform(facing, p_left), RigidTransform(facing, p_right)
    both = RigidTransform(_between(p_left, p_right, facing), (p_left + p_right) / 2)
    return {h: (X, hands.time) for h, X in zip(PERSON_HOLDERS, (left, right, both), strict=True)}


def _between(p_left: np.ndarray, p_right: np.ndarray, facing: RotationMatrix):
    """The both-hands frame's rotation: x level and square to the hands' line, y along it
    from the right hand to the left (the facing's y, level, when the hands are one above the
    other), z square to both. Level, a 4 cm tray stayed upright while the hands' line rolled
    4 degrees each stride of a walk, and a palm rose 2.3 cm off it (a user's electronics
    cell). In scalars: this runs at every update that has a new pose of the person."""
    dx, dy, dz = (float(a - b) for a, b in zip(p_left, p_right, strict=True))
    across = math.hypot(dx, dy)
    if across < 1e-9:
        (h0, h1), c, s = facing.col(1)[:2], 1.0, 0.0
    else:
        length = math.hypot(across, dz)
        (h0, h1), c, s = (dx / across, dy / across), across / length, dz / length
    x, y, z = (h1, -h0, 0.0), (c * h0, c * h1, s), (-s * h0, -s * h1, c)  # z = x × y
    return RotationMatrix(np.array([x, y, z]).T)
