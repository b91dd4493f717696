"""The skeleton of a person of a given height and mass, from published anthropometry.

Every length comes from the Drillis & Contini fractions of body height H and every mass from
Dempster's fractions of body mass (docs/human-body.md); girths scale with build (mass per
height). Joint limits are the typical adult range of motion. The bodies follow the
conventions of `hrc_drake.human.skeleton` (zero configuration upright facing +x, left and
right joints mirror images).
"""

from dataclasses import dataclass
from math import radians, sqrt

from hrc_drake.human.skeleton import (
    SIDES,
    Body,
    Collision,
    Dof,
    Frame,
    Shape,
    Skeleton,
    Visual,
    mirror_axis,
)

DEFAULT_HEIGHT = 1.75
DEFAULT_MASS = 75.0
HEIGHT_RANGE = (1.45, 1.95)
"""m: from below a 1st-percentile woman to a 99th-percentile man of ANSUR II"""
WRIST_RADIUS = 0.028
"""m: the forearm's slim end, round the wrist's girth (about 17.5 cm for men, 15.3 cm for
women in ANSUR II; docs/human-body.md): as thick as below the elbow (0.036) to the wrist, the
wrist of a palm flat on a box's side went 1 cm into it (a kit taken off another, squatting)."""
TAPER = 0.6
"""Where along the forearm, from the elbow, it has thinned to the wrist's girth."""


def _rev(name, axis, lower, upper) -> Dof:
    return Dof(name, "revolute", axis, lower, upper)


def _cylinder_inertia(mass, radius, length) -> tuple[float, float, float]:
    """Principal moments of a solid cylinder along z: good enough for a never-simulated body."""
    across = mass * (3 * radius**2 + length**2) / 12
    return (across, across, mass * radius**2 / 2)


def _capsule_between(top_z, bottom_z, radius, x=0.0, y=0.0) -> Shape:
    """Vertical capsule whose cylinder runs from bottom_z to top_z (body frame)."""
    return Shape("capsule", (radius, top_z - bottom_z), (x, y, (top_z + bottom_z) / 2))


def _lateral_capsule(half_width, radius, xyz) -> Shape:
    """Capsule along y (across the body)."""
    return Shape("capsule", (radius, 2 * half_width), xyz, (radians(90), 0.0, 0.0))


@dataclass(frozen=True)
class _Dimensions:
    """Lengths (m) derived from height H and girths scaled by build (mass per height)."""

    H: float
    girth: float

    def length(self, fraction: float) -> float:
        return fraction * self.H

    def radius(self, at_default: float) -> float:
        """A segment radius measured on the default adult, scaled to this person's size."""
        return at_default * self.H / DEFAULT_HEIGHT * self.girth


def _dimensions(height: float, mass: float) -> _Dimensions:
    build = (mass / DEFAULT_MASS) / (height / DEFAULT_HEIGHT) ** 3
    return _Dimensions(H=height, girth=sqrt(build))


def build_skeleton(height: float = DEFAULT_HEIGHT, mass: float = DEFAULT_MASS) -> Skeleton:
    """The skeleton of a person `height` metres tall weighing `mass` kg."""
    if not HEIGHT_RANGE[0] <= height <= HEIGHT_RANGE[1]:
        raise ValueError(f"body height {height} m outside {HEIGHT_RANGE[0]}-{HEIGHT_RANGE[1]} m")
    d = _dimensions(height, mass)
    L = d.length
    sizes = {
        "hip_height": L(0.530),
        "knee_height": L(0.285),
        "ankle_height": L(0.039),
        "shoulder_height": L(0.818),
        "upper_arm": L(0.186),
        "forearm": L(0.146),
        "hand": L(0.108),
        "thigh": L(0.245),
        "shank": L(0.246),
        "foot": L(0.152),
        "hip_half_width": L(0.191) * 0.275,
        "shoulder_half_width": L(0.259) * 0.41,
        "heel_back": L(0.152) * 0.25,
    }
    bodies = [*_base_bodies(), *_trunk_bodies(d, sizes, mass)]
    for side in SIDES:
        bodies += _arm_bodies(side, d, sizes, mass)
        bodies += _leg_bodies(side, d, sizes, mass)
    frames = _frames(d, sizes)
    return Skeleton(height, mass, tuple(bodies), frames, sizes)


def _base_bodies() -> list[Body]:
    """World -> pelvis: planar base (x, y, yaw), pelvis height, tilt and list; massless links."""
    chain = [
        Dof("base_x", "prismatic", (1, 0, 0), -1e3, 1e3),
        Dof("base_y", "prismatic", (0, 1, 0), -1e3, 1e3),
        _rev("base_yaw", (0, 0, 1), -36000, 36000),
        Dof("pelvis_height", "prismatic", (0, 0, 1), 0.2, 1.3),
        _rev("pelvis_tilt", (0, 1, 0), -30, 90),
    ]
    bodies, parent = [], "world"
    for dof in chain:
        name = f"{dof.name}_link"
        bodies.append(Body(name, parent, (0, 0, 0), (dof,), 0.0, (0, 0, 0), (0, 0, 0)))
        parent = name
    return bodies


def _trunk_bodies(d: _Dimensions, s: dict, mass: float) -> list[Body]:
    """Pelvis, abdomen (lumbar joint), chest (thoracic joint) and head (neck joint)."""
    L, R = d.length, d.radius
    lumbar = (-L(0.02), 0.0, L(0.06))
    thoracic_above_lumbar = L(0.10)
    neck_above_thoracic = L(0.83) - L(0.53) - L(0.06) - thoracic_above_lumbar
    shoulder_above_thoracic = s["shoulder_height"] - L(0.53) - L(0.06) - thoracic_above_lumbar
    sw = s["shoulder_half_width"]
    pelvis = Body(
        "pelvis",
        "pelvis_tilt_link",
        (0, 0, 0),
        (_rev("pelvis_list", (1, 0, 0), -20, 20),),
        0.142 * mass,
        (-L(0.01), 0, L(0.03)),
        _cylinder_inertia(0.142 * mass, R(0.12), L(0.1)),
        (Collision("pelvis", _lateral_capsule(R(0.085), R(0.10), (-L(0.01), 0, L(0.025)))),),
        (
            Visual(
                "trousers", Shape("ellipsoid", (R(0.12), R(0.175), R(0.12)), (-L(0.01), 0, L(0.03)))
            ),
        ),
    )
    abdomen = Body(
        "abdomen",
        "pelvis",
        lumbar,
        (
            _rev("lumbar_flexion", (0, 1, 0), -20, 50),
            _rev("lumbar_bending", (-1, 0, 0), -35, 35),
        ),
        0.139 * mass,
        (L(0.015), 0, L(0.05)),
        _cylinder_inertia(0.139 * mass, R(0.12), thoracic_above_lumbar),
        (Collision("abdomen", _lateral_capsule(R(0.06), R(0.105), (L(0.02), 0, L(0.05)))),),
        (Visual("shirt", Shape("ellipsoid", (R(0.12), R(0.16), R(0.11)), (L(0.02), 0, L(0.05)))),),
    )
    chest = Body(
        "chest",
        "abdomen",
        (0, 0, thoracic_above_lumbar),
        (
            _rev("thorax_flexion", (0, 1, 0), -5, 30),
            _rev("thorax_rotation", (0, 0, 1), -40, 40),
        ),
        0.216 * mass,
        (L(0.02), 0, L(0.06)),
        _cylinder_inertia(0.216 * mass, R(0.14), neck_above_thoracic),
        (
            Collision("chest", _lateral_capsule(R(0.08), R(0.115), (L(0.025), 0, L(0.055)))),
            Collision(
                "back_shoulders",
                _lateral_capsule(sw - R(0.03), R(0.065), (-L(0.005), 0, shoulder_above_thoracic)),
            ),
        ),
        (
            Visual(
                "shirt", Shape("ellipsoid", (R(0.125), R(0.175), R(0.15)), (L(0.02), 0, L(0.06)))
            ),
            Visual(
                "shirt",
                _lateral_capsule(sw - R(0.02), R(0.065), (-L(0.005), 0, shoulder_above_thoracic)),
            ),
        ),
    )
    head = _head_body(d, (L(0.005), 0.0, neck_above_thoracic), mass)
    return [pelvis, abdomen, chest, head]


def _head_body(d: _Dimensions, origin, mass: float) -> Body:
    """Head and neck in one body, jointed at the base of the neck (height 0.83 H)."""
    L, R = d.length, d.radius
    skull_centre = (R(0.0), 0, L(0.105))
    face_centre = (R(0.075), 0, L(0.07))
    eye_z = L(0.936 - 0.83)
    return Body(
        "head",
        "chest",
        origin,
        (
            _rev("neck_flexion", (0, 1, 0), -60, 50),
            _rev("neck_rotation", (0, 0, 1), -80, 80),
        ),
        0.081 * mass,
        (R(0.02), 0, L(0.08)),
        _cylinder_inertia(0.081 * mass, R(0.09), L(0.17)),
        (
            Collision("neck", _capsule_between(L(0.045), 0.0, R(0.055), x=R(0.005))),
            Collision("skull_forehead", Shape("sphere", (R(0.095),), skull_centre)),
            Collision("face", Shape("box", (R(0.05), R(0.12), L(0.075)), face_centre)),
        ),
        (
            Visual("skin", _capsule_between(L(0.05), 0.0, R(0.055), x=R(0.005))),
            Visual(
                "skin", Shape("ellipsoid", (R(0.1), R(0.078), L(0.065)), (R(0.015), 0, L(0.095)))
            ),
            Visual(
                "hair", Shape("ellipsoid", (R(0.1), R(0.084), L(0.05)), (-R(0.005), 0, L(0.115)))
            ),
            Visual("skin", Shape("sphere", (R(0.016),), (R(0.11), 0, eye_z - L(0.022)))),
            *(
                Visual("eyes", Shape("sphere", (R(0.011),), (R(0.098), side * R(0.032), eye_z)))
                for side in (1, -1)
            ),
        ),
    )


def _sided_dofs(side: str, dofs: tuple[Dof, ...]) -> tuple[Dof, ...]:
    """Name a left-side DoF list for `side`, mirroring the axes for the right side."""
    sided = []
    for dof in dofs:
        axis = dof.axis if side == "left" else mirror_axis(dof.axis)
        sided.append(Dof(f"{side}_{dof.name}", dof.kind, axis, dof.lower, dof.upper))
    return tuple(sided)


def _arm_bodies(side: str, d: _Dimensions, s: dict, mass: float) -> list[Body]:
    L, R = d.length, d.radius
    ua, fa, hand = s["upper_arm"], s["forearm"], s["hand"]
    sign = 1 if side == "left" else -1
    thoracic_above_pelvis = L(0.06) + L(0.10) + L(0.53)
    shoulder = (
        L(0.005),
        sign * s["shoulder_half_width"],
        s["shoulder_height"] - thoracic_above_pelvis,
    )
    upper_arm = Body(
        f"{side}_upper_arm",
        "chest",
        shoulder,
        _sided_dofs(
            side,
            (
                _rev("shoulder_flexion", (0, -1, 0), -60, 180),
                _rev("shoulder_abduction", (1, 0, 0), -30, 180),
                _rev("shoulder_rotation", (0, 0, -1), -90, 70),
            ),
        ),
        0.028 * mass,
        (0, 0, -0.436 * ua),
        _cylinder_inertia(0.028 * mass, R(0.045), ua),
        (Collision("upper_arm", _capsule_between(0.0, -ua, R(0.045))),),
        (
            Visual("shirt", _capsule_between(0.0, -0.6 * ua, R(0.05))),
            Visual("skin", _capsule_between(-0.5 * ua, -ua, R(0.041))),
        ),
    )
    forearm = Body(
        f"{side}_forearm",
        f"{side}_upper_arm",
        (0, 0, -ua),
        _sided_dofs(side, (_rev("elbow_flexion", (0, -1, 0), 0, 150),)),
        0.016 * mass,
        (0, 0, -0.43 * fa),
        _cylinder_inertia(0.016 * mass, R(0.035), fa),
        (
            Collision("lower_arm", _capsule_between(0.0, -TAPER * fa, R(0.036))),
            Collision("lower_arm", _capsule_between(-TAPER * fa, -fa, R(WRIST_RADIUS))),
        ),
        (
            Visual("skin", _capsule_between(0.0, -TAPER * fa, R(0.036))),
            Visual("skin", _capsule_between(-TAPER * fa, -fa, R(WRIST_RADIUS))),
        ),
    )
    hand_body = Body(
        f"{side}_hand",
        f"{side}_forearm",
        (0, 0, -fa),
        _sided_dofs(
            side,
            (
                _rev("wrist_pronation", (0, 0, -1), -80, 80),
                _rev("wrist_flexion", (-1, 0, 0), -70, 80),
                _rev("wrist_deviation", (0, 1, 0), -25, 25),
            ),
        ),
        0.006 * mass,
        (0, 0, -0.4 * hand),
        _cylinder_inertia(0.006 * mass, R(0.03), hand),
        (Collision("hand", Shape("box", (R(0.085), R(0.032), 0.92 * hand), (0, 0, -0.46 * hand))),),
        (
            Visual(
                "skin", Shape("ellipsoid", (R(0.045), R(0.019), 0.5 * hand), (0, 0, -0.48 * hand))
            ),
            Visual(
                "skin",
                Shape(
                    "capsule",
                    (R(0.011), 0.3 * hand),
                    (R(0.04), sign * -R(0.008), -0.3 * hand),
                    (0.0, radians(-25), 0.0),
                ),
            ),
        ),
    )
    return [upper_arm, forearm, hand_body]


def _leg_bodies(side: str, d: _Dimensions, s: dict, mass: float) -> list[Body]:
    R = d.radius
    thigh_len, shank_len, foot_len = s["thigh"], s["shank"], s["foot"]
    ankle_h, heel_back = s["ankle_height"], s["heel_back"]
    sign = 1 if side == "left" else -1
    thigh = Body(
        f"{side}_thigh",
        "pelvis",
        (0, sign * s["hip_half_width"], 0),
        _sided_dofs(
            side,
            (
                _rev("hip_flexion", (0, -1, 0), -30, 120),
                _rev("hip_abduction", (1, 0, 0), -30, 45),
                _rev("hip_rotation", (0, 0, -1), -45, 45),
            ),
        ),
        0.100 * mass,
        (0, 0, -0.433 * thigh_len),
        _cylinder_inertia(0.100 * mass, R(0.075), thigh_len),
        (Collision("thigh", _capsule_between(-R(0.03), -thigh_len, R(0.075))),),
        (Visual("trousers", _capsule_between(-R(0.03), -thigh_len, R(0.078))),),
    )
    shank = Body(
        f"{side}_shank",
        f"{side}_thigh",
        (0, 0, -thigh_len),
        _sided_dofs(side, (_rev("knee_flexion", (0, 1, 0), 0, 135),)),
        0.0465 * mass,
        (0, 0, -0.433 * shank_len),
        _cylinder_inertia(0.0465 * mass, R(0.05), shank_len),
        (Collision("lower_leg", _capsule_between(0.0, -shank_len + R(0.03), R(0.055))),),
        (Visual("trousers", _capsule_between(0.0, -shank_len + R(0.02), R(0.058))),),
    )
    foot_centre = (foot_len / 2 - heel_back, 0, -ankle_h / 2)
    foot = Body(
        f"{side}_foot",
        f"{side}_shank",
        (0, 0, -shank_len),
        _sided_dofs(side, (_rev("ankle_flexion", (0, -1, 0), -50, 20),)),
        0.0145 * mass,
        (foot_centre[0], 0, foot_centre[2]),
        _cylinder_inertia(0.0145 * mass, R(0.04), foot_len),
        (Collision("lower_leg", Shape("box", (foot_len, R(0.095), ankle_h), foot_centre)),),
        (
            Visual(
                "shoes",
                Shape("ellipsoid", (foot_len / 2, R(0.052), ankle_h * 0.62), foot_centre),
            ),
            Visual(
                "shoes",
                Shape(
                    "box",
                    (foot_len * 0.96, R(0.09), ankle_h * 0.3),
                    (foot_centre[0], 0, -ankle_h * 0.85),
                ),
            ),
        ),
    )
    return [thigh, shank, foot]


def _frames(d: _Dimensions, s: dict) -> tuple[Frame, ...]:
    """Grasp points in the palms, gaze between the eyes, soles under the middle of each foot."""
    L, R = d.length, d.radius
    frames = [Frame("head_gaze", "head", (R(0.1), 0, L(0.936 - 0.83)))]
    for side in SIDES:
        sign = 1 if side == "left" else -1
        frames.append(
            Frame(f"{side}_hand_grasp", f"{side}_hand", (0, -sign * R(0.02), -0.45 * s["hand"]))
        )
        frames.append(
            Frame(
                f"{side}_sole",
                f"{side}_foot",
                (s["foot"] / 2 - s["heel_back"], 0, -s["ankle_height"]),
            )
        )
    return tuple(frames)
