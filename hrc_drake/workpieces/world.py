"""The workpieces world as plain Python: objects, holders, commands, carrying and settling.

`Workcell` holds what does not change during a run (types, slots, surfaces, belts, areas,
tolerances, seed); `World` is the state at one update time and is immutable, so Drake can
keep it as abstract state without copying. `Workcell.update` maps (world, time, commands,
holder poses) to the next world:

1. free objects move on with the velocity planned at the previous update;
2. held objects follow their holder's grasp frame with the offset they had when grasped;
3. each issuer's new command is carried out (in the order of the issuers);
4. objects past the end of a removing belt leave;
5. free objects find what they rest on (the highest support under their footprint and
   below their top: a surface, a belt, another object, the floor) and plan their motion
   for the next period: resting on a surface they stay, on a belt they move with it (queueing),
   on an object they move with it, otherwise they fall with gravity and land exactly on the
   support; an object found below its support's top is lifted onto it (never sinks).

Between updates every object moves with its planned velocity (`pose_at`), so outputs are
smooth without reading inputs (no direct feedthrough).
"""

import dataclasses
import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np
from pydrake.math import RigidTransform, RotationMatrix
from pydrake.multibody.math import SpatialVelocity

from hrc_drake.areas import Area
from hrc_drake.messages import (
    FAILED,
    REJECTED,
    SUCCEEDED,
    CommandResult,
    ResultLog,
    newer_commands,
)
from hrc_drake.workpieces.config import WorkpiecesConfig, problems
from hrc_drake.workpieces.conveyors import Belt
from hrc_drake.workpieces.geometry import (
    Drift,
    Solid,
    footprint,
    moved,
    twist_between,
    upright,
    velocity_at,
    with_height,
)
from hrc_drake.workpieces.layouts import Placement, initial_placements
from hrc_drake.workpieces.messages import (
    BOTH_HANDS,
    GRASPABLE,
    HOLDERS,
    LEFT_HAND,
    PERSON_HOLDERS,
    RIGHT_HAND,
    ROBOT_HOLDER,
    Attach,
    Attributes,
    Despawn,
    Detach,
    HandPoses,
    ObjectStatus,
    Spawn,
    Transfer,
    WorkpiecesCommand,
    WorkpiecesStatus,
    object_id_of_support,
    object_support,
)
from hrc_drake.workpieces.surfaces import Supports, Surface
from hrc_drake.yaml_check import field_path

GRAVITY = 9.81
REST_TOLERANCE = 1e-6
"""m: an object this close above its support rests on it."""
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

    @property
    def bottom(self) -> float:
        return self.pose.translation()[2] - self.solid.height / 2

    @cached_property
    def footprint(self) -> np.ndarray:
        return footprint(self.solid, self.pose)

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


def holder_frames(
    tool: RigidTransform | None, hands: HandPoses | tuple | None
) -> dict[str, Sampled]:
    """Grasp frame of every present holder. The person's frames are level (objects in the
    hands stay upright): one hand's at its grasp point facing the person's heading, both
    hands' at their midpoint, facing away from the body (x), y from the right hand to the
    left, z up. `hands` is empty or None while the person has none. The poses are copied:
    an input port's value may be overwritten in place when it is evaluated again."""
    frames = {} if tool is None else {ROBOT_HOLDER: (RigidTransform(tool), None)}
    if hands:
        facing = RotationMatrix.MakeZRotation(hands.heading)
        left, right = (RigidTransform(facing, X.translation()) for X in (hands.left, hands.right))
        both = _between(left, right)
        frames |= {
            h: (X, hands.time) for h, X in zip(PERSON_HOLDERS, (left, right, both), strict=True)
        }
    return frames


def _between(left: RigidTransform, right: RigidTransform) -> RigidTransform:
    p_left, p_right = left.translation(), right.translation()
    y = np.array([*(p_left - p_right)[:2], 0.0])
    if np.linalg.norm(y) < 1e-9:
        y = left.rotation().col(1) * [1.0, 1.0, 0.0]
    y /= np.linalg.norm(y)
    x = [y[1] * 1.0 - y[2] * 0.0, y[2] * 0.0 - y[0] * 1.0, y[0] * 0.0 - y[1] * 0.0]  # y × z
    R = RotationMatrix(np.column_stack([x, y, [0.0, 0.0, 1.0]]))
    return RigidTransform(R, (p_left + p_right) / 2)


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
        seed = np.random.SeedSequence(self.seed.entropy, spawn_key=(*self.seed.spawn_key, *key))
        return np.random.default_rng(seed)

    def initial_world(self) -> World:
        """The scenario's initial objects, resting where they fall."""
        step = _Step(self, _empty_world(), 0.0, {})
        for placement in initial_placements(self.config, self.random(LAYOUT_STREAM)):
            if step.create(placement) is None:
                raise ValueError(f"more initial objects of type '{placement.type}' than slots")
        step.settle(instantly=True)
        return step.world()

    def update(
        self,
        world: World,
        now: float,
        commands: dict[str, WorkpiecesCommand | tuple | None],
        holder_frames: dict[str, Sampled],
    ) -> World:
        step = _Step(self, world, now, holder_frames)
        for issuer_index, issuer in enumerate(self.issuers):
            for command in newer_commands(commands.get(issuer), world.seen.get(issuer, -1)):
                step.execute(issuer, issuer_index, command)
        step.remove_past_belt_ends()
        step.settle(instantly=False)
        return step.world()

    def pose_at(self, piece: Piece, world: World, time: float) -> RigidTransform:
        return piece.drift.after(since(world, time))

    def status(self, world: World, time: float, geometry_ids=()) -> WorkpiecesStatus:
        """What the world looks like at `time`; `geometry_ids` are the slots' geometries."""
        objects = tuple(
            ObjectStatus(
                id=p.id,
                type=p.type,
                pose=self.pose_at(p, world, time),
                velocity=p.velocity,
                holder=p.holder,
                support=p.support,
                attributes=p.attributes,
                mass=self.kinds[p.type].mass,
                geometry_id=geometry_ids[p.slot] if geometry_ids else None,
                size=p.solid.size,
                shape=p.solid.shape,
            )
            for p in world.pieces.values()
        )
        used = [p.type for p in world.pieces.values()]
        free = {name: len(kind.slots) - used.count(name) for name, kind in self.kinds.items()}
        return WorkpiecesStatus(time, objects, dict(world.results), free)


def since(world: World, time: float) -> float:
    """How long the world's objects have moved on from their poses at `time` (never back)."""
    return max(time - world.time, 0.0)


def _kinds(config: WorkpiecesConfig) -> dict[str, Kind]:
    kinds, start = {}, 0
    for name, t in config.types.items():
        slots = range(start, start + t.capacity)
        kinds[name] = Kind(name, Solid.of(t), t.mass, dict(t.attributes), slots)
        start += t.capacity
    return kinds


def _empty_world() -> World:
    return World(0.0, {}, 1, {}, {}, {})


class _Step:
    """One update in progress: a working copy of the world that commands and motion change."""

    def __init__(self, cell: Workcell, world: World, now: float, frames: dict[str, Sampled]):
        self.cell = cell
        self.config = cell.config
        self.now = now
        self.next_id = world.next_id
        self.seen = dict(world.seen)
        self.results = dict(world.results)
        self.samples = {
            h: _sample(world.holders.get(h), X, now if t is None else t)
            for h, (X, t) in frames.items()
        }
        self._holder_poses = {}
        self.changed = False
        dt = now - world.time
        self.pieces = {i: self._followed(p, dt) for i, p in world.pieces.items()}

    def world(self) -> World:
        return World(self.now, self.pieces, self.next_id, self.samples, self.seen, self.results)

    def holder_pose(self, holder: str) -> RigidTransform | None:
        """The holder's grasp frame now, extrapolated from its last sample (None: the holder
        is not there); worked out when first asked for."""
        if holder not in self._holder_poses:
            sample = self.samples.get(holder)
            self._holder_poses[holder] = (
                None
                if sample is None
                else moved(sample.pose, sample.velocity, self.now - sample.time)
            )
        return self._holder_poses[holder]

    def _followed(self, piece: Piece, dt: float) -> Piece:
        """The piece at `now`: moved on as planned, or carried by its holder."""
        if piece.holder is None:
            if not piece.velocity.get_coeffs().any():
                return piece
            return dataclasses.replace(piece, pose=moved(piece.pose, piece.velocity, dt))
        X_WH = self.holder_pose(piece.holder)
        if X_WH is None:  # the holder's pose input has no value any more: wait where it was
            return dataclasses.replace(piece, velocity=SpatialVelocity.Zero())
        X_WO = X_WH @ piece.grip
        V = velocity_at(self.samples[piece.holder].velocity, X_WH.translation(), X_WO.translation())
        return dataclasses.replace(piece, pose=X_WO, velocity=V)

    # --- commands -------------------------------------------------------------------------

    def execute(self, issuer: str, issuer_index: int, command: WorkpiecesCommand) -> None:
        handlers = {
            Spawn: lambda c: self.spawn(c, self.cell.random(SPAWN_STREAM, issuer_index, c.seq)),
            Despawn: self.despawn,
            Attach: self.attach,
            Detach: self.detach,
            Transfer: self.transfer,
        }
        handler = handlers.get(type(command))
        if handler is None:
            result = _result(command, REJECTED, f"unknown command {type(command).__name__}")
        else:
            result = handler(command)
        self.changed |= result.outcome == SUCCEEDED
        self.seen[issuer] = command.seq
        self.results[issuer] = self.results.get(issuer, ResultLog()).recorded(result)

    def spawn(self, command: Spawn, rng: np.random.Generator) -> CommandResult:
        kind = self.cell.kinds.get(command.type)
        if kind is None:
            reason = f"unknown object type '{command.type}'; known: {', '.join(self.cell.kinds)}"
            return _result(command, REJECTED, reason)
        if command.area and command.area not in self.cell.areas:
            return _result(command, REJECTED, f"unknown area '{command.area}'")
        if command.pose is None and not command.area:
            return _result(command, REJECTED, "Spawn needs a pose or an area")
        pose = command.pose if not command.area else self._dropped_in(command.area, kind, rng)
        piece = self.create(Placement(command.type, pose, dict(command.attributes)))
        if piece is None:
            reason = f"capacity reached: {len(kind.slots)} objects of type '{kind.name}' exist"
            return _result(command, FAILED, reason)
        return _result(command, SUCCEEDED, object_id=piece.id)

    def create(self, placement: Placement) -> Piece | None:
        """A new free piece in a free slot of its type, or None when all slots are taken."""
        kind = self.cell.kinds[placement.type]
        taken = {p.slot for p in self.pieces.values()}
        slot = next((s for s in kind.slots if s not in taken), None)
        if slot is None:
            return None
        piece = Piece(
            id=self.next_id,
            type=kind.name,
            solid=kind.solid,
            slot=slot,
            pose=upright(placement.pose),
            velocity=SpatialVelocity.Zero(),
            holder=None,
            grip=None,
            support=None,
            attributes=kind.attributes | placement.attributes,
        )
        self.pieces[piece.id] = piece
        self.next_id += 1
        return piece

    def _dropped_in(self, area: str, kind: Kind, rng: np.random.Generator) -> RigidTransform:
        """A random place in `area`, resting on whatever is highest there."""
        xy = self.cell.areas[area].sample(rng)
        outline = kind.solid.outline() + xy
        tops = [p.top for p in self.pieces.values() if p.holder is None]
        support = self.cell.supports.under(outline, math.inf, tops)
        return RigidTransform([*xy, support.height + kind.solid.height / 2])

    def despawn(self, command: Despawn) -> CommandResult:
        if command.object_id not in self.pieces:
            return _result(command, FAILED, f"no object {command.object_id}")
        del self.pieces[command.object_id]
        return _result(command, SUCCEEDED, object_id=command.object_id)

    def attach(self, command: Attach) -> CommandResult:
        holder = command.holder
        piece = self.pieces.get(command.object_id)
        if piece is not None and holder in self.samples and piece.holder == holder:
            return _result(command, SUCCEEDED, "already held", piece.id)
        problem = self._holder_problem(holder) or self._busy(holder)
        if problem:
            outcome = REJECTED if holder not in HOLDERS else FAILED
            return _result(command, outcome, problem, command.object_id)
        if command.object_id is None:
            piece = self._graspable_at(holder)
            problem = "" if piece else f"nothing graspable at the {holder}'s grasp frame"
        else:
            problem = self._attach_problem(piece, command.object_id, holder)
        return self._grasp(command, piece, holder, problem)

    def detach(self, command: Detach) -> CommandResult:
        if command.holder not in HOLDERS:
            return _result(command, REJECTED, _unknown_holder(command.holder))
        if command.object_id is None:
            piece = self._held_by(command.holder)
            if piece is None:
                return _result(command, FAILED, f"{command.holder} holds nothing")
        else:
            piece = self.pieces.get(command.object_id)
            if piece is None:
                return _result(command, FAILED, f"no object {command.object_id}")
            if piece.holder != command.holder:
                held = f"held by {piece.holder}" if piece.holder else "free"
                reason = f"object {piece.id} is not held by {command.holder} (it is {held})"
                return _result(command, FAILED, reason, piece.id)
        self.pieces[piece.id] = dataclasses.replace(
            piece, pose=upright(piece.pose), velocity=SpatialVelocity.Zero(), holder=None, grip=None
        )
        return _result(command, SUCCEEDED, object_id=piece.id)

    def transfer(self, command: Transfer) -> CommandResult:
        to = command.to_holder
        if to not in HOLDERS:
            return _result(command, REJECTED, _unknown_holder(to))
        piece = self.pieces.get(command.object_id)
        problem = self._handover_problem(piece, command.object_id, to)
        return self._grasp(command, piece, to, problem)

    def _grasp(
        self, command: Attach | Transfer, piece: Piece | None, holder: str, problem: str
    ) -> CommandResult:
        """The holder takes the piece, unless there is a problem or the piece is too heavy."""
        problem = problem or self._mass_problem(piece, command.max_mass)
        if problem:
            return _result(command, FAILED, problem, command.object_id)
        self._hold(piece, holder, command.center)
        return _result(command, SUCCEEDED, object_id=piece.id)

    def _holder_problem(self, holder: str) -> str:
        if holder not in HOLDERS:
            return _unknown_holder(holder)
        if holder not in self.samples:
            who = "robot tool" if holder == ROBOT_HOLDER else "person's hands"
            return f"there is no {holder}: the {who} pose is not connected"
        return ""

    def _busy(self, holder: str) -> str:
        hands = {LEFT_HAND: (BOTH_HANDS,), RIGHT_HAND: (BOTH_HANDS,)}
        hands[BOTH_HANDS] = (LEFT_HAND, RIGHT_HAND)
        for occupied in (holder, *hands.get(holder, ())):
            piece = self._held_by(occupied)
            if piece is not None:
                return f"{occupied} already holds object {piece.id}"
        return ""

    def _held_by(self, holder: str) -> Piece | None:
        return next((p for p in self.pieces.values() if p.holder == holder), None)

    def _attach_problem(self, piece: Piece | None, object_id: int, holder: str) -> str:
        if piece is None:
            return f"no object {object_id}"
        if piece.holder is not None:
            return f"object {piece.id} is held by {piece.holder}; hand it over with Transfer"
        if not piece.attributes.get(GRASPABLE, True):
            return f"object {piece.id} is not graspable"
        tolerance = (
            self.config.vacuum_tolerance if holder == ROBOT_HOLDER else self.config.hand_tolerance
        )
        if self._grasp_distance(piece, holder) is None:
            return f"object {piece.id} is not within {tolerance} m of the {holder}'s grasp frame"
        return ""

    def _handover_problem(self, piece: Piece | None, object_id: int, to: str) -> str:
        if piece is None:
            return f"no object {object_id}"
        if piece.holder is None:
            return f"object {piece.id} is not held; grasp it with Attach"
        if (piece.holder == ROBOT_HOLDER) == (to == ROBOT_HOLDER):
            return f"a hand-over is between the robot and the person, not {piece.holder} -> {to}"
        problem = self._holder_problem(to) or self._busy(to)
        if problem:
            return problem
        tolerance = self.config.handover_tolerance
        for holder in (piece.holder, to):
            distance = self._distance(piece, holder)
            if distance > tolerance:
                return (
                    f"hand-over refused: {holder} is {distance:.3f} m from object {piece.id} "
                    f"(tolerance {tolerance} m)"
                )
        return ""

    def _mass_problem(self, piece: Piece, max_mass: float) -> str:
        mass = self.cell.kinds[piece.type].mass
        if mass > max_mass:
            return f"object {piece.id} weighs {mass} kg, more than {max_mass} kg"
        return ""

    def _graspable_at(self, holder: str) -> Piece | None:
        """The nearest free graspable piece at the holder's grasp frame."""
        reachable = [
            (distance, p.id)
            for p in self.pieces.values()
            if p.holder is None and p.attributes.get(GRASPABLE, True)
            for distance in [self._grasp_distance(p, holder)]
            if distance is not None
        ]
        return self.pieces[min(reachable)[1]] if reachable else None

    def _grasp_distance(self, piece: Piece, holder: str) -> float | None:
        """How far the holder's grasp is from the piece, if within the holder's tolerance.

        The vacuum cup must lie on the top face, facing it; hands must be near the surface."""
        if holder == ROBOT_HOLDER:
            return self._cup_distance(piece)
        distance = self._distance(piece, holder)
        return distance if distance <= self.config.hand_tolerance else None

    def _cup_distance(self, piece: Piece) -> float | None:
        solid = self.cell.kinds[piece.type].solid
        X_OT = piece.pose.inverse() @ self.holder_pose(ROBOT_HOLDER)
        facing = -X_OT.rotation().col(2)[2]
        tilt_limit = math.cos(math.radians(self.config.vacuum_max_tilt_deg))
        p_OT = X_OT.translation()
        if facing < tilt_limit or not solid.on_top_face(p_OT, self.config.vacuum_tolerance):
            return None
        return abs(p_OT[2] - solid.height / 2)

    def _distance(self, piece: Piece, holder: str) -> float:
        """Distance from the holder's grasp point to the piece. Both hands grasp at their
        midpoint, which is where the person aims them (hands close around a small part
        as much as they span a large box)."""
        solid = self.cell.kinds[piece.type].solid
        return solid.distance_to(piece.pose.inverse() @ self.holder_pose(holder).translation())

    def _hold(self, piece: Piece, holder: str, center=None) -> None:
        """The holder takes the piece: it keeps its orientation to the holder's frame from
        now on, its centre where it is or at `center` (holder frame) when given."""
        X_WH = self.holder_pose(holder)
        grip = X_WH.inverse() @ piece.pose
        if center is not None:
            grip = RigidTransform(grip.rotation(), np.asarray(center, dtype=float))
        X_WO = X_WH @ grip
        V = velocity_at(self.samples[holder].velocity, X_WH.translation(), X_WO.translation())
        self.pieces[piece.id] = dataclasses.replace(
            piece, pose=X_WO, holder=holder, grip=grip, support=None, velocity=V
        )

    # --- motion of free pieces ------------------------------------------------------------

    def remove_past_belt_ends(self) -> None:
        for piece in list(self.pieces.values()):
            belt = self.cell.belts.get(piece.support)
            if belt is not None and not belt.queues and belt.past_end(piece.pose.translation()):
                del self.pieces[piece.id]
                self.changed = True

    def settle(self, instantly: bool) -> None:
        """Find the supports of the free pieces that may move and plan their motion (or, at
        the start, drop every piece onto its support at once).

        Only commands and removals change what rests on what; otherwise a piece at rest on
        something fixed stays put, so only moving pieces and belt riders are looked at."""
        free = [p for p in self.pieces.values() if p.holder is None]
        if instantly or self.changed:
            active = free
        else:
            active = [p for p in free if self._moving(p) or p.support in self.cell.belts]
        if not active:
            return
        active.sort(key=lambda p: (p.bottom, p.id))
        active_ids = {p.id for p in active}
        tops = [p.top for p in free if p.id not in active_ids]
        supports = {}
        for piece in active:
            supports[piece.id] = self._support(self.pieces[piece.id], tops, instantly)
            tops.append(self.pieces[piece.id].top)
        belt_speeds = self._belt_speeds()
        for piece in active:
            self._plan(self.pieces[piece.id], supports[piece.id], belt_speeds)

    @staticmethod
    def _moving(piece: Piece) -> bool:
        return piece.support is None or bool(piece.velocity.get_coeffs().any())

    def _support(self, piece: Piece, others: list[Surface], instantly: bool) -> Surface:
        """What is under the piece: the highest support up to its top face, so that a piece
        resting on it or sunk into it is put on top of it. `others` are the tops of the
        pieces at rest and of those below this one (a piece placed into another of the same
        height lands on the older one)."""
        top = piece.bottom + piece.solid.height + REST_TOLERANCE
        support = self.cell.supports.under(piece.footprint, top, others)
        if instantly or piece.bottom <= support.height + REST_TOLERANCE:
            pose = with_height(piece.pose, support.height + piece.solid.height / 2)
            self.pieces[piece.id] = dataclasses.replace(piece, pose=pose, support=support.name)
        else:
            self.pieces[piece.id] = dataclasses.replace(piece, support=None)
        return support

    def _belt_speeds(self) -> dict[int, float]:
        speeds = {}
        for name, belt in self.cell.belts.items():
            riders = {
                p.id: p.footprint
                for p in self.pieces.values()
                if p.holder is None and p.support == name
            }
            speeds |= belt.plan(riders, self.config.update_period)
        return speeds

    def _plan(self, piece: Piece, support: Surface, belt_speeds: dict[int, float]) -> None:
        """The piece's velocity until the next update: its support's, or falling onto it."""
        below = self._support_velocity(support, belt_speeds, piece.id)
        if piece.support is not None:
            v = below
        else:
            dt = self.config.update_period
            landing = support.height + below[2] * dt
            accelerated = piece.velocity.translational()[2] - GRAVITY * dt
            v = np.array([0.0, 0.0, max(accelerated, (landing - piece.bottom) / dt)])
        velocity = SpatialVelocity(np.zeros(3), v)
        self.pieces[piece.id] = dataclasses.replace(piece, velocity=velocity)

    def _support_velocity(self, support: Surface, belt_speeds: dict, piece_id: int) -> np.ndarray:
        belt = self.cell.belts.get(support.name)
        if belt is not None:
            return belt.velocity(belt_speeds.get(piece_id, 0.0))
        below = self.pieces.get(object_id_of_support(support.name))
        return below.velocity.translational() if below is not None else np.zeros(3)


def _sample(previous: HolderSample | None, pose: RigidTransform, time: float) -> HolderSample:
    """A new sample after the previous one (kept while no newer sample came)."""
    if previous is None:
        return HolderSample(pose, time)
    if time <= previous.time:
        return previous
    return HolderSample(pose, time, (previous.pose, previous.time))


def _result(
    command: WorkpiecesCommand, outcome: str, reason: str = "", object_id: int | None = None
) -> CommandResult:
    return CommandResult(command.seq, outcome, reason, object_id)


def _unknown_holder(holder: str) -> str:
    return f"unknown holder '{holder}'; known: {', '.join(HOLDERS)}"
