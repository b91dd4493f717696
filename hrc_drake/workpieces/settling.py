"""How free workpieces move between updates: what each rests on (the highest support under
its footprint: a surface, a belt, another piece, the floor), and the velocity it keeps until
the next update: its support's (a belt's speed as the belt queues its riders), or falling
with gravity to land exactly on the support. A piece found below its support's top is
lifted onto it (never sinks); pieces past the end of a removing belt leave. What the
person's palms set down on a belt stays until they are out of its way."""

import numpy as np
from pydrake.multibody.math import SpatialVelocity

from hrc_drake.workpieces.conveyors import Belt
from hrc_drake.workpieces.geometry import with_height
from hrc_drake.workpieces.messages import object_id_of_support
from hrc_drake.workpieces.step import Step
from hrc_drake.workpieces.surfaces import Surface
from hrc_drake.workpieces.world import Piece

GRAVITY = 9.81
"""m/s²: free pieces fall with it until they land."""
REST_TOLERANCE = 1e-6
"""m: an object this close above its support rests on it."""


def remove_past_belt_ends(step: Step) -> None:
    """Pieces carried past the end of a belt that removes them (rather than queueing them)
    leave the world."""
    for piece in list(step.pieces.values()):
        belt = step.cell.belts.get(piece.support)
        if belt is not None and not belt.queues and belt.past_end(piece.pose.translation()):
            del step.pieces[piece.id]
            step.changed = True


def settle(step: Step, instantly: bool) -> None:
    """Find the supports of the free pieces that may move and plan their motion (or, at
    the start, drop every piece onto its support at once).

    Only commands and removals change what rests on what; otherwise a piece at rest on
    something fixed stays put, and so does a belt rider at rest: the belt's end or riders
    at rest ahead of it hold it back (one ahead that moved would leave it room), and a
    piece landing on the belt can only hold it back more. So only moving pieces are
    looked at; every rider still counts in its belt's plan. What is held just over a belt
    holds its riders back as a rider does, but it may go at any update: while it is there,
    and at the update after, its belt's riders are looked at too; so is a piece the person
    let go of until the palms are out of its way (`_let_go_of`)."""
    _let_go_of(step)
    free = [p for p in step.pieces.values() if p.holder is None]
    held_back = _belts_held_back(step)
    active = (
        free
        if instantly or step.changed
        else [p for p in free if _moving(p) or p.waits_for or p.support in held_back]
    )
    if not active:
        return
    active.sort(key=lambda p: (p.bottom, p.id))
    active_ids = {p.id for p in active}
    tops = [p.top for p in free if p.id not in active_ids]
    supports = {}
    for piece in active:
        supports[piece.id] = _support(step, step.pieces[piece.id], tops, instantly)
        tops.append(step.pieces[piece.id].top)
    belt_speeds = _belt_speeds(step)
    for piece in active:
        _plan(step, step.pieces[piece.id], supports[piece.id], belt_speeds)


def _let_go_of(step: Step) -> None:
    """Pieces the person let go of wait no more once they rest off a belt, or the palms
    that let go of them are out of their way on it (`Belt.in_the_way`); then every rider
    is planned again (those behind a piece that set off may follow it)."""
    for piece in [p for p in step.pieces.values() if p.waits_for and p.support is not None]:
        belt = step.cell.belts.get(piece.support)
        if belt is None or not _palms_in_the_way(step, piece, belt):
            step.pieces[piece.id] = piece.in_place(waits_for=())
            step.changed |= belt is not None


def _palms_in_the_way(step: Step, piece: Piece, belt: Belt) -> bool:
    poses = [step.holder_pose(palm) for palm in piece.waits_for]
    top = piece.bottom + piece.solid.height
    return any(
        X is not None and belt.in_the_way(piece.footprint, top, X.translation()) for X in poses
    )


def _moving(piece: Piece) -> bool:
    return piece.support is None or piece.moving


def _support(step: Step, piece: Piece, others: list[Surface], instantly: bool) -> Surface:
    """What is under the piece: the highest support up to its top face, so that a piece
    resting on it or sunk into it is put on top of it. `others` are the tops of the
    pieces at rest and of those below this one (a piece placed into another of the same
    height lands on the older one)."""
    top = piece.bottom + piece.solid.height + REST_TOLERANCE
    support = step.cell.supports.under(piece.footprint, top, others)
    if instantly or piece.bottom <= support.height + REST_TOLERANCE:
        pose = with_height(piece.pose, support.height + piece.solid.height / 2)
        step.pieces[piece.id] = piece.in_place(pose=pose, support=support.name)
    else:
        step.pieces[piece.id] = piece.in_place(support=None)
    return support


def _belts_held_back(step: Step) -> set[str]:
    """The belts with something held just over them now or at the last update."""
    now, before = step.pieces.values(), step.before.pieces.values()
    return {
        name
        for name, belt in step.cell.belts.items()
        if belt.held_over(now) or belt.held_over(before)
    }


def _belt_speeds(step: Step) -> dict[int, float]:
    """Each rider's speed: the pieces the person let go of on a belt stay where they are
    while the palms are in their way. A person setting a carton down on a running belt
    keeps the palms on its faces until the hands have opened and come away, and the belt
    slides under it meanwhile (set off at once, a carton ran 5.2 cm into the palm ahead of
    it, a user's palletizing cell)."""
    speeds, pieces = {}, step.pieces.values()
    waiting = {p.id for p in pieces if p.waits_for}
    for belt in step.cell.belts.values():
        riders, blockers = belt.riders(pieces), belt.held_over(pieces)
        speeds |= belt.plan(riders, step.config.period, blockers, waiting & riders.keys())
    return speeds


def _plan(step: Step, piece: Piece, support: Surface, belt_speeds: dict[int, float]) -> None:
    """The piece's velocity until the next update: its support's, or falling onto it."""
    below = _support_velocity(step, support, belt_speeds, piece.id)
    if piece.support is not None:
        v = below
    else:
        dt = step.config.period
        landing = support.height + below[2] * dt
        accelerated = piece.velocity.translational()[2] - GRAVITY * dt
        v = np.array([0.0, 0.0, max(accelerated, (landing - piece.bottom) / dt)])
    velocity = SpatialVelocity(np.zeros(3), v)
    step.pieces[piece.id] = piece.in_place(velocity=velocity)


def _support_velocity(step: Step, support: Surface, belt_speeds: dict, piece_id: int) -> np.ndarray:
    belt = step.cell.belts.get(support.name)
    if belt is not None:
        return belt.velocity(belt_speeds.get(piece_id, 0.0))
    below = step.pieces.get(object_id_of_support(support.name))
    return below.velocity.translational() if below is not None else np.zeros(3)
