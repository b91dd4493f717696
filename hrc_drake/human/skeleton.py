"""The human skeleton: what it is made of (bodies, joints and their limits, frames, and
geometry tagged with ISO/TS 15066 body regions) and the conventions every joint vector
follows. `hrc_drake.human.anthropometry` builds one for a person of a given height and mass.

The zero configuration stands upright, arms hanging, facing +x (x forward, y left, z up) with
the pelvis origin (midpoint of the hip joints) on the floor, so that the `pelvis_height`
coordinate *is* the height of the hip joints above the floor.

Left and right joints share a name after `left_`/`right_` and are mirror images: their axes
map by (ax, ay, az) -> (-ax, ay, -az), so equal angles give mirrored poses.
"""

from dataclasses import dataclass, field
from math import radians

SIDES = ("left", "right")

REGIONS = (
    "skull_forehead",
    "face",
    "neck",
    "back_shoulders",
    "chest",
    "abdomen",
    "pelvis",
    "upper_arm",
    "lower_arm",
    "hand",
    "thigh",
    "lower_leg",
)
"""ISO/TS 15066 body regions (safety.md table order); feet count as lower leg."""

COLORS = {
    "skin": (0.87, 0.69, 0.56, 1.0),
    "shirt": (0.16, 0.36, 0.62, 1.0),
    "trousers": (0.20, 0.22, 0.28, 1.0),
    "shoes": (0.10, 0.08, 0.07, 1.0),
    "hair": (0.24, 0.15, 0.09, 1.0),
    "eyes": (0.05, 0.05, 0.06, 1.0),
}

LATERAL_CENTRAL_JOINTS = (
    "base_y",
    "base_yaw",
    "pelvis_list",
    "lumbar_bending",
    "thorax_rotation",
    "neck_rotation",
)
"""Joints on the body's midline whose value changes sign in a left/right mirror image."""


@dataclass(frozen=True)
class Shape:
    """One primitive: kind in (capsule, sphere, box, ellipsoid); size as SDF expects it.

    capsule: (radius, length) along the local z axis; sphere: (radius,); box: (x, y, z);
    ellipsoid: (a, b, c). `rpy` rotates the shape (radians) about its centre `xyz`.
    """

    kind: str
    size: tuple[float, ...]
    xyz: tuple[float, float, float]
    rpy: tuple[float, float, float] = (0.0, 0.0, 0.0)


@dataclass(frozen=True)
class Collision:
    """Proximity geometry tagged with the ISO/TS 15066 region it stands for."""

    region: str
    shape: Shape


@dataclass(frozen=True)
class Visual:
    """Illustration geometry with one of the COLORS."""

    color: str
    shape: Shape


@dataclass(frozen=True)
class Dof:
    """One joint coordinate: revolute (angle, limits in degrees) or prismatic (metres)."""

    name: str
    kind: str
    axis: tuple[float, float, float]
    lower: float
    upper: float

    @property
    def limits(self) -> tuple[float, float]:
        """Limits in SI units (radians for revolute joints)."""
        if self.kind == "revolute":
            return radians(self.lower), radians(self.upper)
        return self.lower, self.upper


@dataclass(frozen=True)
class Body:
    """A segment: its joint origin in the parent body frame, the DoFs from parent to it."""

    name: str
    parent: str
    origin: tuple[float, float, float]
    dofs: tuple[Dof, ...]
    mass: float
    com: tuple[float, float, float]
    inertia: tuple[float, float, float]
    collisions: tuple[Collision, ...] = ()
    visuals: tuple[Visual, ...] = ()


@dataclass(frozen=True)
class Frame:
    """A named frame fixed to a body (grasp points, gaze, soles)."""

    name: str
    body: str
    xyz: tuple[float, float, float]


@dataclass(frozen=True)
class Skeleton:
    """All bodies (parents first) and named frames of one person of a given height and mass."""

    height: float
    mass: float
    bodies: tuple[Body, ...]
    frames: tuple[Frame, ...]
    dimensions: dict = field(default_factory=dict)

    @property
    def dofs(self) -> tuple[Dof, ...]:
        return tuple(dof for body in self.bodies for dof in body.dofs)

    @property
    def joint_names(self) -> tuple[str, ...]:
        return tuple(dof.name for dof in self.dofs)

    def body(self, name: str) -> Body:
        return next(body for body in self.bodies if body.name == name)


def mirror_axis(axis: tuple[float, float, float]) -> tuple[float, float, float]:
    """Axis of the right-side twin of a left-side joint (reflection through the x-z plane)."""
    return (-axis[0], axis[1], -axis[2])


def mirror_xyz(xyz: tuple[float, float, float]) -> tuple[float, float, float]:
    return (xyz[0], -xyz[1], xyz[2])
