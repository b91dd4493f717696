"""The arms' collision shapes against the cell's prisms: how deep an arm goes into the
furniture (the separating-axis test on the prisms' faces and the hulls of the upper arm and
forearm capsules and the hand's box), where, and which way is the shortest out. The arm
check (hrc_drake.human.clearance) moves the arms by these measures."""

from dataclasses import dataclass
from functools import cached_property, lru_cache

import numpy as np
from pydrake.math import RollPitchYaw

from hrc_drake.human.body import HumanBody
from hrc_drake.human.furniture import Furniture

ARM = ("upper_arm", "forearm", "hand")
"""The arm's bodies, from the shoulder out."""


@dataclass(frozen=True)
class Points:
    """One arm's collision shapes: per body of the arm, the corners of its shape's hull (in
    the body's frame) and the radius round them."""

    frames: tuple[str, ...]
    points: tuple[np.ndarray, ...]
    radii: tuple[float, ...]

    @cached_property
    def starts(self) -> np.ndarray:
        """Where each shape's corners start among all of them."""
        return np.cumsum([0, *(len(p) for p in self.points[:-1])])

    @cached_property
    def radii_column(self) -> np.ndarray:
        return np.asarray(self.radii)[None, None, :]

    @cached_property
    def stacked(self) -> np.ndarray:
        """All the corners, shape by shape (n × 3; read-only: checks hand out its rows)."""
        stacked = np.vstack(self.points)
        stacked.setflags(write=False)
        return stacked


@lru_cache(maxsize=16)
def arm_points(body: HumanBody, side: str) -> Points:
    """The shapes of the upper arm, forearm and hand as the corners of their hulls: a
    capsule's two axis ends (with its radius), the hand box's eight corners."""
    frames, points, radii = [], [], []
    for part in ARM:
        name = f"{side}_{part}"
        (collision,) = body.skeleton.body(name).collisions
        shape = collision.shape
        R = RollPitchYaw(*shape.rpy).ToRotationMatrix().matrix()
        if shape.kind == "capsule":
            radius, length = shape.size
            local = np.array([[0.0, 0.0, -length / 2], [0.0, 0.0, length / 2]])
        else:  # the hand's box
            radius = 0.0
            half = np.asarray(shape.size) / 2
            local = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)]) * half
        frames.append(name)
        points.append(np.asarray(shape.xyz, dtype=float) + local @ R.T)
        radii.append(radius)
    return Points(tuple(frames), tuple(points), tuple(radii))


@dataclass(frozen=True)
class Prisms:
    """The furniture's prisms by their faces, for the separating-axis test: per piece, the
    outward normal of each face (its outline's edges, then down and up; padded to the same
    count with axes that never separate) and how far the piece reaches along each normal,
    forward and backward."""

    axes: np.ndarray
    """(pieces, faces, 3)"""
    ahead: np.ndarray
    """(pieces, faces): the largest projection of the piece on each axis."""
    behind: np.ndarray
    """(pieces, faces): the smallest."""

    @classmethod
    def of(cls, furniture: Furniture) -> "Prisms":
        faces = [_faces(piece) for piece in furniture.pieces]
        count = max((len(a) for a, _, _ in faces), default=2)
        axes = np.zeros((len(faces), count, 3))
        ahead = np.full((len(faces), count), np.inf)
        behind = np.full((len(faces), count), -np.inf)
        for k, (a, hi, lo) in enumerate(faces):
            axes[k, : len(a)], ahead[k, : len(a)], behind[k, : len(a)] = a, hi, lo
        return cls(axes, ahead, behind)

    def near(self, xy, reach: float) -> "Prisms":
        """The prisms within `reach` of a floor point (the rest cannot be touched)."""
        point = np.array([xy[0], xy[1], 0.0])
        sideways = self.axes[:, :, 2] == 0.0
        distance = np.where(sideways, self.axes @ point - self.ahead, -np.inf).max(axis=1)
        keep = distance <= reach
        return Prisms(self.axes[keep], self.ahead[keep], self.behind[keep])

    def overlap(self, points: np.ndarray, radii: np.ndarray, starts: np.ndarray, not_down=False):
        """How deep the convex shapes (each the hull of its run of `points`, from `starts`,
        grown by its radius) go into the prisms: the deepest shape and prism by the
        separating-axis test on the prisms' faces (at least as deep as they overlap;
        negative: apart by at least that much). Returns the depth, the shape, the direction
        that takes it out (the shortest way, or with `not_down` the shortest but down under
        the prism; a unit vector) and the index of the point that leads the way out."""
        projections, forward, backward, along, depth = self._depths(points, radii, starts)
        k, shape = np.unravel_index(np.argmax(depth), depth.shape)
        choice = along[k, :, shape].copy()
        if not_down:
            choice[self.axes[k, :, 2] < 0.0] = np.inf
        f = int(np.argmin(choice))
        stop = starts[shape + 1] if shape + 1 < len(starts) else len(points)
        run = projections[k, f, starts[shape] : stop]
        if forward[k, f, shape] <= backward[k, f, shape]:
            lead, axis = int(np.argmin(run)), self.axes[k, f]
        else:
            lead, axis = int(np.argmax(run)), -self.axes[k, f]
        return float(depth[k, shape]), int(shape), axis, starts[shape] + lead

    def deepest(self, points: np.ndarray, arm: Points) -> float:
        """`overlap`'s depth alone, of an arm's hull corners at `points`."""
        return float(self._depths(points, arm.radii_column, arm.starts)[-1].max())

    def _depths(self, points, radii, starts):
        """Projections on the axes, reaches past each face forward, backward and the lesser,
        and per prism and shape the least over the faces (the separating-axis depth)."""
        projections = np.einsum("kfj,nj->kfn", self.axes, points)
        low = np.minimum.reduceat(projections, starts, axis=2) - radii
        high = np.maximum.reduceat(projections, starts, axis=2) + radii
        forward = self.ahead[:, :, None] - low
        backward = high - self.behind[:, :, None]
        along = np.minimum(forward, backward)
        return projections, forward, backward, along, along.min(axis=1)


def _faces(piece):
    """A prism's face normals and its extents along them (forward, backward)."""
    coords = np.asarray(piece.outline.exterior.coords)[:-1]
    if not piece.outline.exterior.is_ccw:
        coords = coords[::-1]
    edges = np.roll(coords, -1, axis=0) - coords
    normals = np.column_stack([edges[:, 1], -edges[:, 0]])
    normals /= np.linalg.norm(normals, axis=1)[:, None]
    reach = normals @ coords.T
    axes = np.vstack([np.column_stack([normals, np.zeros(len(normals))]), [[0, 0, -1], [0, 0, 1]]])
    ahead = [*reach.max(axis=1), -piece.low, piece.high]
    behind = [*reach.min(axis=1), -piece.high, piece.low]
    return axes, np.array(ahead), np.array(behind)


@dataclass(frozen=True)
class ArmCheck:
    """One arm's points in the world at a pose, and how deep they go into the furniture."""

    depth: float
    frame: str
    point: np.ndarray
    """The deepest point, in its frame."""
    at: np.ndarray
    """The deepest point, in the world."""
    out: np.ndarray
    """Which way it gets out (a unit vector)."""


@lru_cache(maxsize=16)
def arm_frames(body: HumanBody, sides: tuple[str, ...]) -> tuple:
    """The plant frames of the `sides` arms' bodies, side by side (as `arm_points` has them)."""
    return tuple(body.plant.GetFrameByName(f) for s in sides for f in arm_points(body, s).frames)


def arms_in_world(body: HumanBody, q: np.ndarray, sides: tuple[str, ...]) -> dict:
    """The `sides` arms' hull corners in the world at q (n × 3), by one forward kinematics."""
    poses = body.world_poses(arm_frames(body, sides), body.plant_positions(q))
    world = {}
    for k, side in enumerate(sides):
        arm, points = poses[k * len(ARM) : (k + 1) * len(ARM)], arm_points(body, side).points
        world[side] = np.hstack([X @ local.T for X, local in zip(arm, points, strict=True)]).T
    return world


def check_arm(
    body: HumanBody, prisms: Prisms, q: np.ndarray, side: str, not_down: bool = False
) -> ArmCheck:
    """How deep the `side` arm goes into the prisms at q (its deepest shape), where, and how
    it gets out (as `Prisms.overlap`)."""
    arm = arm_points(body, side)
    world = arms_in_world(body, q, (side,))[side]
    depth, shape, out, k = prisms.overlap(world, arm.radii_column, arm.starts, not_down)
    return ArmCheck(depth, arm.frames[shape], arm.stacked[k], world[k], out)
