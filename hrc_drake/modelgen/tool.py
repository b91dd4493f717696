"""SDFormat model of the vacuum gripper welded to the iisy flange.

The body frame is the mounting face (z along the tool axis, away from the robot), so welding
it to the robot's `flange` frame needs no offset. `tcp` sits on the suction cup face.
"""

from pydrake.geometry import Cylinder
from pydrake.math import RigidTransform

from hrc_drake.iisy import TCP_FRAME, TOOL_BODY
from hrc_drake.modelgen.sdf import DARK, Part, add_frame, add_link, new_model, to_text

MASS = 0.4
"""kg: a small aluminium vacuum gripper with ejector."""
FRICTION = 0.8
"""Rubber cup."""
GREY = (0.6, 0.62, 0.65, 1.0)

# (name, radius, length, color) stacked along z from the mounting face.
SECTIONS = (
    ("adapter", 0.032, 0.012, DARK),
    ("body", 0.024, 0.075, GREY),
    ("cup", 0.02, 0.023, DARK),
)


def stacked_parts() -> tuple[list[Part], float]:
    """Coaxial cylinders, one after the other; returns them and the total length."""
    parts, z = [], 0.0
    for name, radius, length, color in SECTIONS:
        parts.append(
            Part(name, Cylinder(radius, length), RigidTransform([0, 0, z + length / 2]), color)
        )
        z += length
    return parts, z


def vacuum_gripper_sdf() -> str:
    parts, length = stacked_parts()
    root, model = new_model("vacuum_gripper")
    add_link(model, TOOL_BODY, parts, MASS, friction=FRICTION)
    add_frame(model, TCP_FRAME, TOOL_BODY, RigidTransform([0, 0, length]))
    return to_text(root)
