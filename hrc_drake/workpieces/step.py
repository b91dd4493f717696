"""One update of the workpieces world in progress: a working copy of the World that the
commands (hrc_drake.workpieces.commands) and settling (hrc_drake.workpieces.settling) change,
made into the next World at the end. On creation held pieces already follow their holders
and free pieces have moved on as planned (steps 1 and 2 of an update)."""

import dataclasses

from pydrake.math import RigidTransform
from pydrake.multibody.math import SpatialVelocity

from hrc_drake.workpieces.geometry import moved, upright, velocity_at
from hrc_drake.workpieces.layouts import Placement
from hrc_drake.workpieces.world import HolderSample, Piece, Sampled, Workcell, World

PAUSE = 1.5
"""Update periods after which the world's last update counts as a pause (updates left out
while everything rested): the holders' samples from before it say nothing of how they move
now, so a holder's first sample after it has no velocity (a grasp then takes the object at
rest for one period, not at the holder's average speed over the pause)."""


class Step:
    """One update in progress: a working copy of the world that commands and motion change."""

    def __init__(self, cell: Workcell, world: World, now: float, frames: dict[str, Sampled]):
        self.cell = cell
        self.before = world
        self.config = cell.config
        self.now = now
        self.next_id = world.next_id
        self.seen = dict(world.seen)
        self.results = dict(world.results)
        paused = now - world.time > PAUSE * self.config.period
        self.samples = {
            h: _sample(None if paused else world.holders.get(h), X, now if t is None else t)
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
            if not piece.moving:
                return piece
            return dataclasses.replace(piece, pose=moved(piece.pose, piece.velocity, dt))
        X_WH = self.holder_pose(piece.holder)
        if X_WH is None:  # the holder's pose input has no value any more: wait where it was
            return dataclasses.replace(piece, velocity=SpatialVelocity.Zero())
        X_WO = X_WH @ piece.grip
        V = velocity_at(self.samples[piece.holder].velocity, X_WH.translation(), X_WO.translation())
        return dataclasses.replace(piece, pose=X_WO, velocity=V)

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


def _sample(previous: HolderSample | None, pose: RigidTransform, time: float) -> HolderSample:
    """A new sample after the previous one (kept while no newer sample came)."""
    if previous is None:
        return HolderSample(pose, time)
    if time <= previous.time:
        return previous
    return HolderSample(pose, time, (previous.pose, previous.time))
