"""Port types that trees write as text: poses and areas (BehaviorTree.CPP style strings).

Pose text is `x;y;z`, `x;y;z;qw;qx;qy;qz`, or the name of a scenario location. Area text is the name
of a scenario area or triangles `x1,y1;x2,y2;x3,y3;...` (three points each), as in the thesis system
(docs/thesis-system.md). Names are kept as names here and resolved by the running agent's context
against its scenario, so one tree file serves every scenario that names the same places."""

import math
import re
from dataclasses import dataclass

import numpy as np
from pydrake.common.eigen_geometry import Quaternion
from pydrake.math import RigidTransform

from hrc_drake.areas import Area
from hrc_drake.bt import register_type

_NAME = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*$")


@dataclass(frozen=True)
class Pose:
    """A position with an optional orientation (quaternion w, x, y, z), or a location name.

    A pose without orientation leaves it to its user: the robot keeps its tool pointing
    down, the person faces the walking direction (the thesis system's null quaternion).
    """

    position: tuple[float, float, float] = (0.0, 0.0, 0.0)
    quaternion: tuple[float, float, float, float] | None = None
    name: str = ""

    @staticmethod
    def from_string(text: str) -> "Pose":
        text = text.strip()
        if _NAME.match(text):
            return Pose(name=text)
        values = [float(v) for v in text.split(";")]
        if len(values) == 3:
            return Pose(tuple(values))
        if len(values) == 7:
            quaternion = tuple(values[3:])
            return Pose(tuple(values[:3]), None if not any(quaternion) else quaternion)
        raise ValueError("a pose is x;y;z, x;y;z;qw;qx;qy;qz or a location name")

    @staticmethod
    def from_transform(transform: RigidTransform) -> "Pose":
        q = transform.rotation().ToQuaternion()
        return Pose(tuple(transform.translation()), (q.w(), q.x(), q.y(), q.z()))

    def to_transform(self) -> RigidTransform:
        """The pose as a RigidTransform (identity rotation when it has no orientation)."""
        if self.name:
            raise ValueError(f"location '{self.name}' must be resolved by the agent first")
        if self.quaternion is None:
            return RigidTransform(np.array(self.position))
        w, x, y, z = self.quaternion
        norm = math.sqrt(w * w + x * x + y * y + z * z)
        return RigidTransform(Quaternion(w / norm, x / norm, y / norm, z / norm), self.position)

    @property
    def xy(self) -> np.ndarray:
        return np.array(self.position[:2])

    def __str__(self) -> str:
        if self.name:
            return self.name
        numbers = self.position + (self.quaternion or ())
        return ";".join(f"{v:g}" for v in numbers)


@dataclass(frozen=True)
class AreaRef:
    """The name of a scenario area, resolved by the agent's context."""

    name: str

    def __str__(self) -> str:
        return self.name


def area_from_string(text: str) -> Area | AreaRef:
    text = text.strip()
    if _NAME.match(text):
        return AreaRef(text)
    points = [[float(v) for v in point.split(",")] for point in text.split(";") if point]
    if len(points) < 3 or len(points) % 3 or any(len(p) != 2 for p in points):
        raise ValueError("an area is a name or triangles x1,y1;x2,y2;x3,y3;... (3 points each)")
    return Area.from_triangles(points)


register_type(Pose, Pose.from_string, "Pose")
register_type(Area, area_from_string, "Area")
