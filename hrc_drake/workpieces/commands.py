"""How the workpieces carry out their commands: Spawn (at a pose, or dropped at random in an
area), Despawn, Attach (the vacuum cup on a top face, hands at the surface), Detach,
Transfer (a hand-over between the robot and the person) and Move (a free object set down
elsewhere). Each changes the Step of the update
it arrives in and leaves a CommandResult in its issuer's ResultLog; a problem (an unknown
holder or object, a busy holder, a piece out of reach or too heavy) is its reason."""

import dataclasses
import math

import numpy as np
from pydrake.math import RigidTransform
from pydrake.multibody.math import SpatialVelocity

from hrc_drake.messages import FAILED, REJECTED, SUCCEEDED, CommandResult, ResultLog
from hrc_drake.workpieces.geometry import upright, velocity_at
from hrc_drake.workpieces.layouts import Placement
from hrc_drake.workpieces.messages import (
    BOTH_HANDS,
    GRASPABLE,
    HOLDERS,
    LEFT_HAND,
    RIGHT_HAND,
    ROBOT_HOLDER,
    Attach,
    Despawn,
    Detach,
    Move,
    Spawn,
    Transfer,
    WorkpiecesCommand,
)
from hrc_drake.workpieces.step import Step
from hrc_drake.workpieces.world import SPAWN_STREAM, Kind, Piece


def execute(step: Step, issuer: str, issuer_index: int, command: WorkpiecesCommand) -> None:
    """Carries out `issuer`'s command and records its result. A Spawn draws from a random
    stream of its own (by issuer and command), so one issuer's spawns never shift another's."""
    handlers = {
        Spawn: lambda c: _spawn(step, c, step.cell.random(SPAWN_STREAM, issuer_index, c.seq)),
        Despawn: lambda c: _despawn(step, c),
        Attach: lambda c: _attach(step, c),
        Detach: lambda c: _detach(step, c),
        Transfer: lambda c: _transfer(step, c),
        Move: lambda c: _move(step, c),
    }
    handler = handlers.get(type(command))
    if handler is None:
        result = _result(command, REJECTED, f"unknown command {type(command).__name__}")
    else:
        result = handler(command)
    step.changed |= result.outcome == SUCCEEDED
    step.seen[issuer] = command.seq
    step.results[issuer] = step.results.get(issuer, ResultLog()).recorded(result)


def _spawn(step: Step, command: Spawn, rng: np.random.Generator) -> CommandResult:
    kind = step.cell.kinds.get(command.type)
    if kind is None:
        reason = f"unknown object type '{command.type}'; known: {', '.join(step.cell.kinds)}"
        return _result(command, REJECTED, reason)
    if command.area and command.area not in step.cell.areas:
        return _result(command, REJECTED, f"unknown area '{command.area}'")
    if command.pose is None and not command.area:
        return _result(command, REJECTED, "Spawn needs a pose or an area")
    pose = command.pose if not command.area else _dropped_in(step, command.area, kind, rng)
    piece = step.create(Placement(command.type, pose, dict(command.attributes)))
    if piece is None:
        reason = f"capacity reached: {len(kind.slots)} objects of type '{kind.name}' exist"
        return _result(command, FAILED, reason)
    return _result(command, SUCCEEDED, object_id=piece.id)


def _dropped_in(step: Step, area: str, kind: Kind, rng: np.random.Generator) -> RigidTransform:
    """A random place in `area`, resting on whatever is highest there."""
    xy = step.cell.areas[area].sample(rng)
    outline = kind.solid.outline() + xy
    tops = [p.top for p in step.pieces.values() if p.holder is None]
    support = step.cell.supports.under(outline, math.inf, tops)
    return RigidTransform([*xy, support.height + kind.solid.height / 2])


def _despawn(step: Step, command: Despawn) -> CommandResult:
    if command.object_id not in step.pieces:
        return _result(command, FAILED, f"no object {command.object_id}")
    del step.pieces[command.object_id]
    return _result(command, SUCCEEDED, object_id=command.object_id)


def _attach(step: Step, command: Attach) -> CommandResult:
    holder = command.holder
    piece = step.pieces.get(command.object_id)
    if piece is not None and holder in step.samples and piece.holder == holder:
        return _result(command, SUCCEEDED, "already held", piece.id)
    problem = _holder_problem(step, holder) or _busy(step, holder)
    if problem:
        outcome = REJECTED if holder not in HOLDERS else FAILED
        return _result(command, outcome, problem, command.object_id)
    if command.object_id is None:
        piece = _graspable_at(step, holder)
        problem = "" if piece else f"nothing graspable at the {holder}'s grasp frame"
    else:
        problem = _attach_problem(step, piece, command.object_id, holder)
    return _grasp(step, command, piece, holder, problem)


def _detach(step: Step, command: Detach) -> CommandResult:
    if command.holder not in HOLDERS:
        return _result(command, REJECTED, _unknown_holder(command.holder))
    if command.object_id is None:
        piece = _held_by(step, command.holder)
        if piece is None:
            return _result(command, FAILED, f"{command.holder} holds nothing")
    else:
        piece = step.pieces.get(command.object_id)
        if piece is None:
            return _result(command, FAILED, f"no object {command.object_id}")
        if piece.holder != command.holder:
            held = f"held by {piece.holder}" if piece.holder else "free"
            reason = f"object {piece.id} is not held by {command.holder} (it is {held})"
            return _result(command, FAILED, reason, piece.id)
    step.pieces[piece.id] = dataclasses.replace(
        piece,
        pose=upright(piece.pose),
        velocity=SpatialVelocity.Zero(),
        holder=None,
        grip=None,
        waits_for=PALMS.get(piece.holder, ()),
    )
    return _result(command, SUCCEEDED, object_id=piece.id)


PALMS = {LEFT_HAND: (LEFT_HAND,), RIGHT_HAND: (RIGHT_HAND,), BOTH_HANDS: (LEFT_HAND, RIGHT_HAND)}
"""The palms each of the person's holders lets go with: what an object set down waits for
(the robot's cup lifts straight off its top, out of a belt's way)."""


def _move(step: Step, command: Move) -> CommandResult:
    piece = step.pieces.get(command.object_id)
    if piece is None:
        return _result(command, FAILED, f"no object {command.object_id}")
    if piece.holder is not None:
        reason = f"object {piece.id} is held by {piece.holder}"
        return _result(command, FAILED, reason, piece.id)
    step.pieces[piece.id] = dataclasses.replace(
        piece, pose=upright(command.pose), velocity=SpatialVelocity.Zero(), support=None
    )
    return _result(command, SUCCEEDED, object_id=piece.id)


def _transfer(step: Step, command: Transfer) -> CommandResult:
    to = command.to_holder
    if to not in HOLDERS:
        return _result(command, REJECTED, _unknown_holder(to))
    piece = step.pieces.get(command.object_id)
    problem = _handover_problem(step, piece, command.object_id, to)
    return _grasp(step, command, piece, to, problem)


def _grasp(
    step: Step, command: Attach | Transfer, piece: Piece | None, holder: str, problem: str
) -> CommandResult:
    """The holder takes the piece, unless there is a problem or the piece is too heavy."""
    problem = problem or _mass_problem(step, piece, command.max_mass)
    if problem:
        return _result(command, FAILED, problem, command.object_id)
    _hold(step, piece, holder, command.center)
    return _result(command, SUCCEEDED, object_id=piece.id)


def _holder_problem(step: Step, holder: str) -> str:
    if holder not in HOLDERS:
        return _unknown_holder(holder)
    if holder not in step.samples:
        who = "robot tool" if holder == ROBOT_HOLDER else "person's hands"
        return f"there is no {holder}: the {who} pose is not connected"
    return ""


def _busy(step: Step, holder: str) -> str:
    hands = {LEFT_HAND: (BOTH_HANDS,), RIGHT_HAND: (BOTH_HANDS,)}
    hands[BOTH_HANDS] = (LEFT_HAND, RIGHT_HAND)
    for occupied in (holder, *hands.get(holder, ())):
        piece = _held_by(step, occupied)
        if piece is not None:
            return f"{occupied} already holds object {piece.id}"
    return ""


def _held_by(step: Step, holder: str) -> Piece | None:
    return next((p for p in step.pieces.values() if p.holder == holder), None)


GRASP_POINTS = {
    RIGHT_HAND: "the right palm",
    LEFT_HAND: "the left palm",
    BOTH_HANDS: "the point between the palms",
}
"""How a refused grasp names where the hands closed (a user read "the both_hands's grasp
frame" and could not tell how far off they were)."""


def _attach_problem(step: Step, piece: Piece | None, object_id: int, holder: str) -> str:
    if piece is None:
        return f"no object {object_id}"
    if piece.holder is not None:
        return f"object {piece.id} is held by {piece.holder}; hand it over with Transfer"
    if not piece.attributes.get(GRASPABLE, True):
        return f"object {piece.id} is not graspable"
    tolerance = (
        step.config.vacuum_tolerance if holder == ROBOT_HOLDER else step.config.hand_tolerance
    )
    if _grasp_distance(step, piece, holder) is not None:
        return ""
    if holder == ROBOT_HOLDER:
        return f"object {piece.id} is not within {tolerance} m of the {holder}'s grasp frame"
    distance = _distance(step, piece, holder)
    return (
        f"object {piece.id} is {distance:.2f} m from {GRASP_POINTS[holder]} as they close "
        f"({tolerance} m at most)"
    )


def _handover_problem(step: Step, piece: Piece | None, object_id: int, to: str) -> str:
    if piece is None:
        return f"no object {object_id}"
    if piece.holder is None:
        return f"object {piece.id} is not held; grasp it with Attach"
    if (piece.holder == ROBOT_HOLDER) == (to == ROBOT_HOLDER):
        return f"a hand-over is between the robot and the person, not {piece.holder} -> {to}"
    problem = _holder_problem(step, to) or _busy(step, to)
    if problem:
        return problem
    tolerance = step.config.handover_tolerance
    for holder in (piece.holder, to):
        distance = _distance(step, piece, holder)
        if distance > tolerance:
            return (
                f"hand-over refused: {holder} is {distance:.3f} m from object {piece.id} "
                f"(tolerance {tolerance} m)"
            )
    return ""


def _mass_problem(step: Step, piece: Piece, max_mass: float) -> str:
    mass = step.cell.kinds[piece.type].mass
    if mass > max_mass:
        return f"object {piece.id} weighs {mass} kg, more than {max_mass} kg"
    return ""


def _graspable_at(step: Step, holder: str) -> Piece | None:
    """The nearest free graspable piece at the holder's grasp frame."""
    reachable = [
        (distance, p.id)
        for p in step.pieces.values()
        if p.holder is None and p.attributes.get(GRASPABLE, True)
        for distance in [_grasp_distance(step, p, holder)]
        if distance is not None
    ]
    return step.pieces[min(reachable)[1]] if reachable else None


def _grasp_distance(step: Step, piece: Piece, holder: str) -> float | None:
    """How far the holder's grasp is from the piece, if within the holder's tolerance.

    The vacuum cup must lie on the top face, facing it; hands must be near the surface."""
    if holder == ROBOT_HOLDER:
        return _cup_distance(step, piece)
    distance = _distance(step, piece, holder)
    return distance if distance <= step.config.hand_tolerance else None


def _cup_distance(step: Step, piece: Piece) -> float | None:
    solid = step.cell.kinds[piece.type].solid
    X_OT = piece.pose.inverse() @ step.holder_pose(ROBOT_HOLDER)
    facing = -X_OT.rotation().col(2)[2]
    tilt_limit = math.cos(math.radians(step.config.vacuum_max_tilt_deg))
    p_OT = X_OT.translation()
    if facing < tilt_limit or not solid.on_top_face(p_OT, step.config.vacuum_tolerance):
        return None
    return abs(p_OT[2] - solid.height / 2)


def _distance(step: Step, piece: Piece, holder: str) -> float:
    """Distance from the holder's grasp point to the piece. Both hands grasp at their
    midpoint, which is where the person aims them (hands close around a small part
    as much as they span a large box)."""
    solid = step.cell.kinds[piece.type].solid
    return solid.distance_to(piece.pose.inverse() @ step.holder_pose(holder).translation())


def _hold(step: Step, piece: Piece, holder: str, center=None) -> None:
    """The holder takes the piece: it keeps its orientation to the holder's frame from
    now on, its centre where it is or at `center` (holder frame) when given."""
    X_WH = step.holder_pose(holder)
    grip = X_WH.inverse() @ piece.pose
    if center is not None:
        grip = RigidTransform(grip.rotation(), np.asarray(center, dtype=float))
    X_WO = X_WH @ grip
    V = velocity_at(step.samples[holder].velocity, X_WH.translation(), X_WO.translation())
    step.pieces[piece.id] = dataclasses.replace(
        piece, pose=X_WO, holder=holder, grip=grip, support=None, velocity=V
    )


def _result(
    command: WorkpiecesCommand, outcome: str, reason: str = "", object_id: int | None = None
) -> CommandResult:
    return CommandResult(command.seq, outcome, reason, object_id)


def _unknown_holder(holder: str) -> str:
    return f"unknown holder '{holder}'; known: {', '.join(HOLDERS)}"
