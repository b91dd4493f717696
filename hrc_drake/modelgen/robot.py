"""SDFormat models of the LBR iisy variants from the published kinematic table.

Each link frame is its joint frame (SDFormat `relative_to`), so the joint origins are the
published parent-to-child transforms verbatim. The shape is derived from the kinematics:
a capsule runs from each joint to the next (first along the link's z axis, then across),
each joint from A2 on has a housing around its axis, the base is a column on a dark foot.
Masses: the published total, spread with one density over all links' collision shapes.
"""

import math
from dataclasses import dataclass

import numpy as np
from pydrake.geometry import Capsule, Cylinder
from pydrake.math import RigidTransform, RollPitchYaw, RotationMatrix

from hrc_drake.iisy import FLANGE_FRAME, JOINT_NAMES, LINK_NAMES, RobotVariant
from hrc_drake.modelgen.sdf import (
    DARK,
    Part,
    add_frame,
    add_link,
    add_pose,
    element,
    new_model,
    num,
    to_text,
    volume,
)

PI = math.pi
HOUSING_SCALE = 1.15
"""Joint housings are this much thicker than the link tubes."""
JOINT_DAMPING = 0.05
"""N*m*s/rad: a little viscous friction; the real gear friction is unknown."""
MIN_SEGMENT = 1e-3
"""m: shorter steps between joints get no tube of their own."""
LINK_RADII = (0.075, 0.065, 0.058, 0.052, 0.045, 0.042, 0.038)
"""m, base_link..link_6 of the 3 R760; larger variants scale it by `Kinematics.size`."""


@dataclass(frozen=True)
class Joint:
    """Published joint origin (parent -> child); the axis is z of the joint frame."""

    xyz: tuple[float, float, float]
    rpy: tuple[float, float, float] = (0.0, 0.0, 0.0)
    axis_sign: float = 1.0

    @property
    def pose(self) -> RigidTransform:
        return RigidTransform(RollPitchYaw(self.rpy), self.xyz)


@dataclass(frozen=True)
class Kinematics:
    """Published kinematics of one variant plus the two shape parameters we chose."""

    joints: tuple[Joint, ...]
    flange_xyz: tuple[float, float, float]
    base_height: float
    size: float

    def radius(self, link: int) -> float:
        return LINK_RADII[link] * self.size


KINEMATICS = {
    "lbr_iisy3_r760": Kinematics(
        joints=(
            Joint((0, 0, 0.1264), axis_sign=-1.0),
            Joint((0, 0, 0.0886), (-PI / 2, 0, 0)),
            Joint((0.3, 0, 0), (0, 0, -PI / 2)),
            Joint((0, 0, 0), (PI / 2, 0, 0)),
            Joint((0, 0, -0.3), (-PI / 2, 0, 0)),
            Joint((0, 0, 0), (PI / 2, 0, 0)),
        ),
        flange_xyz=(0, 0, -0.1605),
        base_height=0.1264,
        size=1.0,
    ),
    "lbr_iisy11_r1300": Kinematics(
        joints=(
            Joint((0, 0, 0.1845), (PI, 0, 0)),
            Joint((0, 0.1011, -0.1155), (PI / 2, 0, 0)),
            Joint((0.59, 0, 0.0237)),
            Joint((0.1139, 0, 0.0774), (PI / 2, 0, -PI / 2)),
            Joint((0, 0.0507, -0.4181), (0, PI / 2, PI / 2)),
            Joint((0.0837, 0, -0.0507), (PI / 2, 0, -PI / 2)),
        ),
        flange_xyz=(0, 0, -0.0943),
        base_height=0.1845,
        size=1.4,
    ),
    "lbr_iisy15_r930": Kinematics(
        joints=(
            Joint((0, 0, 0), (-PI, 0, 0)),
            Joint((0, 0, -0.3), (PI / 2, 0, 0)),
            Joint((0.385, 0, 0), (0, 0, -PI / 2)),
            Joint((0, 0, 0), (PI / 2, 0, 0)),
            Joint((0, 0, -0.367), (-PI / 2, 0, 0)),
            Joint((0, 0, 0), (PI / 2, 0, 0)),
        ),
        flange_xyz=(0, 0, -0.178),
        base_height=0.10,
        size=1.4,
    ),
}


def tube(name: str, start: np.ndarray, end: np.ndarray, radius: float) -> Part:
    """Capsule whose axis runs from `start` to `end`."""
    axis = end - start
    rotation = RotationMatrix.MakeFromOneVector(axis, 2)
    center = (start + end) / 2
    shape = Capsule(radius, float(np.linalg.norm(axis)))
    return Part(name, shape, RigidTransform(rotation, center))


def tubes(name: str, start: np.ndarray, end: np.ndarray, radius: float) -> list[Part]:
    """Tubes from `start` to `end`: first along the link's z axis, then across."""
    corner = np.array([start[0], start[1], end[2]])
    legs = ((start, corner), (corner, end))
    return [
        tube(f"{name}_{i}", a, b, radius)
        for i, (a, b) in enumerate(legs)
        if np.linalg.norm(b - a) > MIN_SEGMENT
    ]


def housing(radius: float) -> list[Part]:
    """Joint housing around the link's z axis: a flat cylinder shown, a capsule colliding."""
    length = 2.2 * radius
    return [
        Part("housing", Cylinder(radius, length), RigidTransform(), collision=False),
        Part("housing", Capsule(radius, length - 2 * radius), RigidTransform(), visual=False),
    ]


def base_parts(kin: Kinematics) -> list[Part]:
    radius = kin.radius(0)
    foot = Cylinder(1.2 * radius, 0.012)
    column = Cylinder(radius, kin.base_height)
    return [
        Part("foot", foot, RigidTransform([0, 0, 0.006]), DARK, collision=False),
        Part("column", column, RigidTransform([0, 0, kin.base_height / 2])),
    ]


def link_start(kin: Kinematics, link: int) -> np.ndarray:
    """Where link's tube begins: its origin, or for link_1 the top of the base column."""
    if link > 1:
        return np.zeros(3)
    return kin.joints[0].pose.inverse() @ np.array([0.0, 0.0, kin.base_height])


def link_end(kin: Kinematics, link: int) -> np.ndarray:
    """Next joint's origin; for link_6 a tube radius short of the flange so its cap ends there."""
    if link < 6:
        return np.array(kin.joints[link].xyz, dtype=float)
    flange = np.array(kin.flange_xyz, dtype=float)
    return flange - kin.radius(6) * flange / np.linalg.norm(flange)


def flange_pose(kin: Kinematics) -> RigidTransform:
    """Flange on the A6 axis, z pointing out of the flange (away from the wrist).

    The published flange frames differ between variants (x out for two, z in for one); all
    three flanges lie on -z of link_6, so one orientation serves all tools.
    """
    return RigidTransform(RollPitchYaw(PI, 0, 0), kin.flange_xyz)


def link_parts(kin: Kinematics, link: int) -> list[Part]:
    if link == 0:
        return base_parts(kin)
    radius = kin.radius(link)
    parts = housing(HOUSING_SCALE * radius) if link > 1 else []
    parts += tubes("tube", link_start(kin, link), link_end(kin, link), radius)
    if link == 6:
        disc = Cylinder(0.8 * radius, 0.006)
        X_disc = flange_pose(kin) @ RigidTransform([0, 0, -0.003])
        parts.append(Part("flange", disc, X_disc, DARK, collision=False))
    return parts


def add_joint(model, variant: RobotVariant, kin: Kinematics, index: int) -> None:
    joint = kin.joints[index]
    node = element(model, "joint", name=JOINT_NAMES[index], type="revolute")
    add_pose(node, joint.pose, relative_to=LINK_NAMES[index])
    element(node, "parent", LINK_NAMES[index])
    element(node, "child", LINK_NAMES[index + 1])
    axis = element(node, "axis")
    element(axis, "xyz", f"0 0 {num(joint.axis_sign)}")
    limit = element(axis, "limit")
    element(limit, "lower", num(variant.position_lower[index]))
    element(limit, "upper", num(variant.position_upper[index]))
    element(limit, "effort", num(variant.effort_limits[index]))
    element(limit, "velocity", num(variant.velocity_limits[index]))
    element(limit, "drake:acceleration", num(variant.acceleration_limits[index]))
    element(element(axis, "dynamics"), "damping", num(JOINT_DAMPING))


def add_neighbour_filters(model) -> None:
    """No contact between links at most two joints apart: their housings overlap by design."""
    for first in range(len(LINK_NAMES) - 2):
        name = f"neighbours_{first}"
        group = element(model, "drake:collision_filter_group", name=name)
        for link in LINK_NAMES[first : first + 3]:
            element(group, "drake:member", link)
        element(group, "drake:ignored_collision_filter_group", name)


def robot_sdf(variant: RobotVariant) -> str:
    kin = KINEMATICS[variant.name]
    parts = [link_parts(kin, link) for link in range(len(LINK_NAMES))]
    density = variant.total_mass / sum(volume(p) for p in parts)
    root, model = new_model(variant.name)
    for link, name in enumerate(LINK_NAMES):
        pose = (RigidTransform(), JOINT_NAMES[link - 1]) if link else None
        add_link(model, name, parts[link], density * volume(parts[link]), pose)
        if link:
            add_joint(model, variant, kin, link - 1)
    add_frame(model, FLANGE_FRAME, LINK_NAMES[-1], flange_pose(kin))
    add_neighbour_filters(model)
    return to_text(root)
