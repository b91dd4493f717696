"""The collision shapes of the arms and the head against the cell's prisms: how deep an arm
or the head goes into the furniture (the separating-axis test on the prisms' faces and the
hulls of the upper arm and forearm capsules, the hand's box, and the neck, skull and face),
where, and which way is the shortest out. The upper-body check (hrc_drake.human.clearance)
moves the arms and the trunk by these measures."""

from dataclasses import dataclass
from functools import cached_property, lru_cache

import numpy as np
from pydrake.math import RollPitchYaw

from hrc_drake.human.body import HumanBody
from hrc_drake.human.furniture import Furniture

ARM = ("upper_arm", "forearm", "hand")
"""The arm's bodies, from the shoulder out."""
HEAD = "head"
"""The part that is the head and neck (one body: neck, skull and face shapes)."""
ACROSS = 0.7
"""A prism's face whose normal is within 45 degrees of a direction lies across it."""


@dataclass(frozen=True)
class Points:
    """One part's collision shapes (an arm's or the head's): per shape, the body frame it is
    on, the corners of its hull (in that frame) and the radius round them."""

    frames: tuple[str, ...]
    points: tuple[np.ndarray, ...]
    radii: tuple[float, ...]

    @cached_property
    def shapes(self) -> np.ndarray:
        """Each shape's corners (rows of `stacked`), padded to the same count by repeating
        its last one (which changes no shape's extent): shapes × most corners."""
        return padded_shapes([len(p) for p in self.points])

    @cached_property
    def radii_row(self) -> np.ndarray:
        return np.asarray(self.radii)

    @cached_property
    def stacked(self) -> np.ndarray:
        """All the corners, shape by shape (n × 3; read-only: checks hand out its rows)."""
        stacked = np.vstack(self.points)
        stacked.setflags(write=False)
        return stacked

    @cached_property
    def owners(self) -> np.ndarray:
        """Which of the part's shapes each corner (a row of `stacked`) is on."""
        return np.repeat(np.arange(len(self.points)), [len(p) for p in self.points])


def part_bodies(part: str) -> tuple[str, ...]:
    """The bodies of a part: `left` or `right` (that arm) or HEAD."""
    return (HEAD,) if part == HEAD else tuple(f"{part}_{b}" for b in ARM)


@lru_cache(maxsize=16)
def arm_points(body: HumanBody, part: str) -> Points:
    """The shapes of a part (an arm: upper arm, forearm and hand; or the head: neck, skull
    and face) as the corners of their hulls: a capsule's two axis ends and a sphere's centre
    (with their radius), a box's eight corners."""
    frames, points, radii = [], [], []
    for name in part_bodies(part):
        for collision in body.skeleton.body(name).collisions:
            corners, radius = _hull(collision.shape)
            frames.append(name)
            points.append(corners)
            radii.append(radius)
    return Points(tuple(frames), tuple(points), tuple(radii))


def _hull(shape):
    """A shape's hull corners in its body's frame and the radius round them."""
    R = RollPitchYaw(*shape.rpy).ToRotationMatrix().matrix()
    if shape.kind == "capsule":
        radius, length = shape.size
        local = np.array([[0.0, 0.0, -length / 2], [0.0, 0.0, length / 2]])
    elif shape.kind == "sphere":
        radius, local = shape.size[0], np.zeros((1, 3))
    else:  # a box
        radius = 0.0
        half = np.asarray(shape.size) / 2
        local = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)]) * half
    return np.asarray(shape.xyz, dtype=float) + local @ R.T, radius


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
        return self.subset(self.near_masks(np.reshape(xy, (1, 2)), reach)[0])

    def near_masks(self, xy: np.ndarray, reach: float) -> np.ndarray:
        """Which prisms `near` keeps, for each of the floor points `xy` (points × 2):
        points × pieces."""
        count, faces = self.axes.shape[:2]
        along = (xy @ self.axes[:, :, :2].reshape(-1, 2).T).reshape(len(xy), count, faces)
        sideways = self.axes[:, :, 2] == 0.0
        return np.where(sideways, along - self.ahead, -np.inf).max(axis=-1) <= reach

    def subset(self, keep: np.ndarray) -> "Prisms":
        """The prisms flagged in `keep`."""
        return Prisms(self.axes[keep], self.ahead[keep], self.behind[keep])

    def near_mask(self, xy, reach: float) -> np.ndarray:
        """Which prisms `near` keeps (one flag per piece)."""
        point = np.array([xy[0], xy[1], 0.0])
        sideways = self.axes[:, :, 2] == 0.0
        distance = np.where(sideways, self.axes @ point - self.ahead, -np.inf).max(axis=1)
        return distance <= reach

    def overlap(
        self,
        points: np.ndarray,
        radii: np.ndarray,
        shapes: np.ndarray,
        not_down=False,
        not_along=None,
    ):
        """How deep the convex shapes (each the hull of its row of `points` by the indices in
        `shapes`, as `padded_shapes` has them, grown by its radius) go into the prisms: the
        deepest shape and prism by the separating-axis test on the prisms' faces (at least as
        deep as they overlap; negative: apart by at least that much). Returns the depth, the
        shape, the direction that takes it out (the shortest way, or with `not_down` the
        shortest but down under the prism; a unit vector) and the index of the point that
        leads the way out. A sphere (a shape of one corner) gets out away from the prism's
        nearest point (`_away`)."""
        forward, backward, along, depth = self._depths(points, radii, shapes)
        k, shape = np.unravel_index(np.argmax(depth), depth.shape)
        if radii[shape] > 0.0 and np.ptp(points[shapes[shape]], axis=0).max() == 0.0:
            centre = points[shapes[shape][0]]
            return float(depth[k, shape]), int(shape), self._away(k, centre), int(shapes[shape][0])
        choice = along[k, :, shape].copy()
        if not_down:
            choice[self.axes[k, :, 2] < 0.0] = np.inf
        if not_along is not None:
            choice[np.abs(self.axes[k] @ not_along) > ACROSS] = np.inf
        f = int(np.argmin(choice))
        run = points[shapes[shape]] @ self.axes[k, f]
        if forward[k, f, shape] <= backward[k, f, shape]:
            lead, axis = int(np.argmin(run)), self.axes[k, f]
        else:
            lead, axis = int(np.argmax(run)), -self.axes[k, f]
        return float(depth[k, shape]), int(shape), axis, int(shapes[shape][lead])

    def _away(self, k: int, centre: np.ndarray) -> np.ndarray:
        """The way out of prism k for a sphere at `centre`: along the faces whose planes it is
        beyond, each as far as it is beyond it (away from the prism's nearest point where
        the faces meet square, as a shelf board's front and underside do), so that it turns
        smoothly as the sphere passes an edge; from inside, out of the nearest face."""
        beyond = self.axes[k] @ centre - self.ahead[k]
        if (beyond > 0.0).any():
            away = np.where(beyond > 0.0, beyond, 0.0) @ self.axes[k]
            return away / np.linalg.norm(away)
        return self.axes[k][int(np.argmax(beyond))]

    def deepest_near(self, xy, reach: float, corners, radii, shapes) -> np.ndarray:
        """How deep each shape goes into the prisms within `reach` of its pose's floor point
        (`xy`: poses × 2; `corners`: poses × corners × 3): poses × shapes, -inf where no
        prism is near. Only the prisms near some pose are measured."""
        near = self.near_masks(xy, reach)
        some = near.any(axis=0)
        if not some.any():
            return np.full((len(xy), len(shapes)), -np.inf)
        depths = self.subset(some).shape_depths(corners, radii, shapes)
        return np.where(near[:, some, None], depths, -np.inf).max(axis=1)

    def shape_depths(self, points: np.ndarray, radii, shapes) -> np.ndarray:
        """`overlap`'s depth of each shape in each prism, for many sets of shapes at once:
        `points` (sets × corners × 3) -> (sets × prisms × shapes)."""
        return self._depths(points, radii, shapes)[-1]

    def _depths(self, points, radii, shapes):
        """Reaches past each face forward, backward and the lesser (... × prisms × faces ×
        shapes), and per prism and shape the least over the faces (the separating-axis
        depth); `points` corners × 3 or sets of them (... × corners × 3). One product
        projects every shape's padded corners on every axis; the extents are the least and
        greatest over the corners of each shape."""
        count, faces = self.axes.shape[:2]
        projected = points[..., shapes.ravel(), :] @ self.axes.reshape(-1, 3).T
        projected = projected.reshape(*points.shape[:-2], *shapes.shape, count, faces)
        low = np.moveaxis(projected.min(axis=-3), -3, -1) - radii
        high = np.moveaxis(projected.max(axis=-3), -3, -1) + radii
        forward = self.ahead[:, :, None] - low
        backward = high - self.behind[:, :, None]
        along = np.minimum(forward, backward)
        return forward, backward, along, along.min(axis=-2)


def padded_shapes(sizes) -> np.ndarray:
    """The corner indices of shapes with `sizes` corners each, one after the other: shapes ×
    the most corners, each row padded with its last corner."""
    starts = np.cumsum([0, *sizes[:-1]])
    most = max(sizes)
    return np.array(
        [
            [start + min(i, size - 1) for i in range(most)]
            for start, size in zip(starts, sizes, strict=True)
        ]
    )


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
    """One part's points in the world at a pose, and how deep they go into the furniture."""

    depth: float
    frame: str
    point: np.ndarray
    """The deepest point, in its frame."""
    at: np.ndarray
    """The deepest point, in the world."""
    out: np.ndarray
    """Which way it gets out (a unit vector)."""


@lru_cache(maxsize=16)
def arm_frames(body: HumanBody, parts: tuple[str, ...]) -> tuple:
    """The plant frames of the `parts`' shapes, part by part (as `arm_points` has them)."""
    return tuple(body.plant.GetFrameByName(f) for p in parts for f in arm_points(body, p).frames)


def arms_in_world(body: HumanBody, q: np.ndarray, parts: tuple[str, ...]) -> dict:
    """The `parts`' hull corners in the world at q (n × 3), by one forward kinematics."""
    corners = corners_in_world(body, [q], parts)[0]
    starts = np.cumsum([0, *(len(arm_points(body, p).stacked) for p in parts)])
    return {part: corners[starts[k] : starts[k + 1]] for k, part in enumerate(parts)}


def corners_in_world(body: HumanBody, poses, parts: tuple[str, ...]) -> np.ndarray:
    """The `parts`' hull corners in the world at each of `poses` (poses × corners × 3, the
    parts' corners one after the other): one forward kinematics per pose, the corners of
    all poses moved at once."""
    frames = arm_frames(body, parts)
    X = np.array(
        [
            [X.GetAsMatrix34() for X in body.world_poses(frames, body.plant_positions(q))]
            for q in poses
        ]
    ).reshape(len(poses), len(frames), 3, 4)
    shapes = [arm_points(body, part) for part in parts]
    first = np.cumsum([0, *(len(p.points) for p in shapes[:-1])])
    owners = np.concatenate([p.owners + k for p, k in zip(shapes, first, strict=True)])
    local = np.vstack([p.stacked for p in shapes])
    placed = X[:, owners]
    return np.einsum("pnij,nj->pni", placed[..., :3], local) + placed[..., 3]


@lru_cache(maxsize=16)
def parts_shapes(body: HumanBody, parts: tuple[str, ...]):
    """The radii and corner indices of the `parts`' shapes (in turn, as `corners_in_world`
    has their corners: `Prisms.shape_depths`' arguments) and where each part's shapes start
    among them."""
    points = [arm_points(body, part) for part in parts]
    sizes = [len(p) for part in points for p in part.points]
    radii = np.concatenate([part.radii_row for part in points])
    starts = np.cumsum([0, *(len(part.radii) for part in points[:-1])])
    return radii, padded_shapes(sizes), starts


def check_arm(
    body: HumanBody,
    prisms: Prisms,
    q: np.ndarray,
    part: str,
    not_down: bool = False,
    not_along=None,
) -> ArmCheck:
    """How deep the `part` (an arm's side or HEAD) goes into the prisms at q (its deepest
    shape), where, and how it gets out (as `Prisms.overlap`)."""
    arm = arm_points(body, part)
    world = arms_in_world(body, q, (part,))[part]
    depth, shape, out, k = prisms.overlap(world, arm.radii_row, arm.shapes, not_down, not_along)
    return ArmCheck(depth, arm.frames[shape], arm.stacked[k], world[k], out)
