"""Geometry of workpieces: upright solids, their footprints, convex overlaps, rigid motion.

Free objects stand upright (only their yaw is kept), so what they rest on is decided in the
floor plane: the convex outline of an object's footprint against the convex outlines of
surfaces and of other objects' top faces, with separating-axis tests.
"""

import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np
from pydrake.common.eigen_geometry import AngleAxis
from pydrake.geometry import Box, Cylinder, Shape
from pydrake.math import RigidTransform, RollPitchYaw, RotationMatrix
from pydrake.multibody.math import SpatialVelocity

from hrc_drake.workpieces.config import BOX, ObjectType

CIRCLE_SIDES = 16
"""Cylinders' outlines are regular polygons with this many sides (circumscribed)."""
OVERLAP_MARGIN = 1e-6
"""m: outlines that merely touch (side by side objects) do not overlap."""
THINNEST = 1e-3
"""m: the least size `Solid.shrunk` leaves (a shape needs some thickness)."""


@dataclass(frozen=True)
class Solid:
    """An object's shape centred on its frame: a box (size x, y, z) or a cylinder along z."""

    shape: str
    size: tuple[float, ...]

    @staticmethod
    def of(object_type: ObjectType) -> "Solid":
        return Solid(object_type.shape, tuple(object_type.size))

    @property
    def height(self) -> float:
        return self.size[2] if self.shape == BOX else self.size[1]

    def drake_shape(self) -> Shape:
        return Box(*self.size) if self.shape == BOX else Cylinder(*self.size)

    def shrunk(self, by: float) -> "Solid":
        """The solid with every face moved `by` inwards (no thinner than THINNEST): padded by
        `by` again, as a collision check pads, it is the solid itself (rounded at its edges)."""
        if self.shape == BOX:
            return Solid(BOX, tuple(max(s - 2 * by, THINNEST) for s in self.size))
        radius, length = self.size
        return Solid(self.shape, (max(radius - by, THINNEST), max(length - 2 * by, THINNEST)))

    def outline(self) -> np.ndarray:
        """The footprint (= top face) in the object's x-y plane, counter-clockwise, (n, 2),
        read-only: made once per solid, as every moved piece's footprint starts from it."""
        return self._outline

    @cached_property
    def _outline(self) -> np.ndarray:
        if self.shape == BOX:
            x, y = self.size[0] / 2, self.size[1] / 2
            outline = np.array([[-x, -y], [x, -y], [x, y], [-x, y]])
        else:
            radius = self.size[0] / math.cos(math.pi / CIRCLE_SIDES)
            angles = np.arange(CIRCLE_SIDES) * 2 * math.pi / CIRCLE_SIDES
            outline = radius * np.stack([np.cos(angles), np.sin(angles)], axis=1)
        outline.setflags(write=False)
        return outline

    def distance_to(self, p_O: np.ndarray) -> float:
        """Distance from a point (object frame) to the solid; zero inside."""
        return max(self.signed_distance_to(p_O), 0.0)

    def signed_distance_to(self, p_O: np.ndarray) -> float:
        """Distance from a point (object frame) to the solid's surface, negative inside."""
        if self.shape == BOX:
            beyond = np.abs(p_O) - np.asarray(self.size) / 2
        else:
            radial = math.hypot(p_O[0], p_O[1]) - self.size[0]
            beyond = np.array([radial, abs(p_O[2]) - self.size[1] / 2])
        outside = float(np.linalg.norm(np.maximum(beyond, 0.0)))
        return outside + min(float(beyond.max()), 0.0)

    def on_top_face(self, p_O: np.ndarray, tolerance: float) -> bool:
        """Whether a point (object frame) lies on the top face, within `tolerance` of it."""
        if abs(p_O[2] - self.height / 2) > tolerance:
            return False
        if self.shape == BOX:
            return abs(p_O[0]) <= self.size[0] / 2 and abs(p_O[1]) <= self.size[1] / 2
        return math.hypot(p_O[0], p_O[1]) <= self.size[0]


def footprint(solid: Solid, X_WO: RigidTransform) -> np.ndarray:
    """The upright solid's outline placed in the world's x-y plane, (n, 2)."""
    yaw = yaw_of(X_WO.rotation())
    c, s = math.cos(yaw), math.sin(yaw)
    return solid.outline() @ np.array([[c, s], [-s, c]]) + X_WO.translation()[:2]


def yaw_of(R: RotationMatrix) -> float:
    m = R.matrix()
    return math.atan2(m[1, 0], m[0, 0])


def upright(X_WO: RigidTransform) -> RigidTransform:
    """The same position and heading, standing upright (what a dropped object does)."""
    return RigidTransform(RollPitchYaw(0.0, 0.0, yaw_of(X_WO.rotation())), X_WO.translation())


def with_height(X_WO: RigidTransform, z: float) -> RigidTransform:
    p = X_WO.translation().copy()
    p[2] = z
    return RigidTransform(X_WO.rotation(), p)


def overlaps(
    a: np.ndarray,
    b: np.ndarray | None,
    margin: float = OVERLAP_MARGIN,
    normals: tuple[np.ndarray, np.ndarray] | None = None,
) -> bool:
    """Whether two convex outlines overlap by more than `margin` (None is the whole plane):
    no edge normal of either separates their projections. `normals`: both outlines'
    `edge_normals`, when the caller keeps them (a support is tested against many pieces)."""
    if b is None:
        return True
    a_normals, b_normals = normals or (edge_normals(a), edge_normals(b))
    axes = np.concatenate([a_normals, b_normals]).T
    along_a, along_b = a @ axes, b @ axes
    apart = (along_a.max(axis=0) < along_b.min(axis=0) + margin) | (
        along_b.max(axis=0) < along_a.min(axis=0) + margin
    )
    return not apart.any()


def edge_normals(polygon: np.ndarray) -> np.ndarray:
    """Unit normals (n, 2) of a polygon's edges, the edge from vertex i to i + 1 first (of
    each of a stack of polygons (..., n, 2): validate turns a part through many headings)."""
    edges = np.roll(polygon, -1, axis=-2) - polygon
    normals = np.stack([-edges[..., 1], edges[..., 0]], axis=-1)
    return normals / np.linalg.norm(normals, axis=-1, keepdims=True)


def twist_between(X0: RigidTransform, X1: RigidTransform, dt: float) -> SpatialVelocity:
    """The constant spatial velocity (world frame, at the moving origin) taking X0 to X1."""
    if dt <= 0:
        return SpatialVelocity.Zero()
    rotation = AngleAxis((X1.rotation() @ X0.rotation().inverse()).matrix())
    w = rotation.axis() * rotation.angle() / dt
    v = (X1.translation() - X0.translation()) / dt
    return SpatialVelocity(w, v)


def moved(X: RigidTransform, V: SpatialVelocity, dt: float) -> RigidTransform:
    """X after moving with V for dt (rotation about its own origin)."""
    return Drift(X, V).after(dt)


class Drift:
    """X moving with V, taken apart once for evaluation at many dt (every plant step)."""

    def __init__(self, X: RigidTransform, V: SpatialVelocity):
        self._R, self._p = X.rotation(), X.translation()
        self._v, self._w = V.translational(), V.rotational()
        self._rate = math.sqrt(self._w.dot(self._w))  # np.linalg.norm's float, cheaper

    def after(self, dt: float) -> RigidTransform:
        """The pose after dt (rotation about its own origin)."""
        angle = self._rate * dt
        R = self._R
        if angle > 0:
            R = RotationMatrix(AngleAxis(angle, self._w / self._rate)) @ R
        return RigidTransform(R, self._p + self._v * dt)


def velocity_at(V_H: SpatialVelocity, p_WH: np.ndarray, p_WO: np.ndarray) -> SpatialVelocity:
    """The velocity of a point rigidly carried by a holder moving with V_H at p_WH."""
    return SpatialVelocity(V_H.rotational(), V_H.Shift(p_WO - p_WH).translational())
