"""SDFormat models of the workcell: floor, tables, pedestal, conveyor, pallet, bin, shelf,
fence, parts.

Every model is one link named `body` with z up. Fixtures have their body origin on the floor
(bottom centre), so the builder welds `body` to a floor pose; loose objects (parts, boxes)
have it at their centre. Support surfaces carry a frame at their centre, z up: `top` (for a
bin: its inner floor), `board_<i>` for shelf boards, `infeed`/`outfeed` on the conveyor belt
(which runs along +x). Loose objects also carry `bottom`, and `grasp` on the top face with z
pointing down into the object, so a tool's `tcp` coincides with `grasp` when picking.
"""

import math
from collections.abc import Callable
from dataclasses import dataclass, field

from pydrake.geometry import Box, Cylinder
from pydrake.math import RigidTransform, RollPitchYaw

from hrc_drake.modelgen.sdf import Color, Part, add_frame, add_link, new_model, to_text

BODY = "body"
FRICTION = 0.6
WOOD: Color = (0.78, 0.65, 0.47, 1.0)
STEEL: Color = (0.45, 0.47, 0.5, 1.0)
ALUMINIUM: Color = (0.76, 0.77, 0.79, 1.0)
RUBBER: Color = (0.13, 0.13, 0.14, 1.0)
FLOOR_GREY: Color = (0.66, 0.66, 0.64, 1.0)
BIN_BLUE: Color = (0.2, 0.36, 0.66, 1.0)
GUARD_YELLOW: Color = (0.93, 0.76, 0.12, 1.0)
CARDBOARD: Color = (0.72, 0.55, 0.35, 1.0)
LEG = 0.05
"""m: square legs and uprights."""


@dataclass
class CellObject:
    """One model: its parts, mass (kg) and named frames in the body frame."""

    parts: list[Part]
    mass: float
    frames: dict[str, RigidTransform] = field(default_factory=dict)


def block(name: str, size: tuple[float, float, float], center, color: Color) -> Part:
    return Part(name, Box(*size), RigidTransform(center), color)


def on_surface(height: float, x: float = 0.0) -> RigidTransform:
    return RigidTransform([x, 0.0, height])


def legs(length: float, width: float, height: float, color: Color = STEEL) -> list[Part]:
    """Four legs standing on the floor under the corners of a `length` x `width` top."""
    x, y = (length - LEG) / 2, (width - LEG) / 2
    return [
        block(f"leg_{i}", (LEG, LEG, height), (sx * x, sy * y, height / 2), color)
        for i, (sx, sy) in enumerate(((1, 1), (1, -1), (-1, 1), (-1, -1)))
    ]


def floor() -> CellObject:
    """10 m x 10 m slab whose top face is the body origin (weld it at the world origin)."""
    slab = block("slab", (10.0, 10.0, 0.1), (0, 0, -0.05), FLOOR_GREY)
    return CellObject([slab], 1000.0, {"top": RigidTransform()})


def table(length: float, width: float, height: float, mass: float) -> CellObject:
    """Work table: a 40 mm wooden top on steel legs; `top` at the top face centre."""
    thickness = 0.04
    top = block("top", (length, width, thickness), (0, 0, height - thickness / 2), WOOD)
    return CellObject(
        [top, *legs(length, width, height - thickness)], mass, {"top": on_surface(height)}
    )


def pedestal(side: float, height: float, mass: float) -> CellObject:
    """Steel robot pedestal on a wider base plate; weld the robot's `base_link` to `top`."""
    plate = 0.02
    parts = [
        block("plate", (1.4 * side, 1.4 * side, plate), (0, 0, plate / 2), STEEL),
        block("column", (side, side, height - plate), (0, 0, (height + plate) / 2), ALUMINIUM),
    ]
    return CellObject(parts, mass, {"top": on_surface(height)})


def conveyor(length: float, width: float, height: float, mass: float) -> CellObject:
    """Belt conveyor running along +x between two side rails, rollers at both ends."""
    belt, rail = 0.03, 0.04
    roller = belt / 2
    side = (width + rail) / 2
    roller_pose = RollPitchYaw(math.pi / 2, 0, 0)
    parts = [
        block("belt", (length, width, belt), (0, 0, height - belt / 2), RUBBER),
        block("rail_left", (length, rail, 0.08), (0, side, height - 0.02), ALUMINIUM),
        block("rail_right", (length, rail, 0.08), (0, -side, height - 0.02), ALUMINIUM),
        *legs(length - 0.2, width, height - belt),
    ]
    for name, x in (("roller_in", -length / 2), ("roller_out", length / 2)):
        pose = RigidTransform(roller_pose, [x, 0, height - roller])
        parts.append(Part(name, Cylinder(roller, width), pose, ALUMINIUM))
    end = length / 2 - 0.15
    frames = {
        "top": on_surface(height),
        "infeed": on_surface(height, -end),
        "outfeed": on_surface(height, end),
    }
    return CellObject(parts, mass, frames)


def euro_pallet() -> CellObject:
    """EUR pallet (EN 13698-1): 1.2 x 0.8 x 0.144 m, deck on nine blocks on three runners."""
    board, block_height = 0.022, 0.1
    rows, columns = (-0.35, 0.0, 0.35), (-0.5275, 0.0, 0.5275)
    parts = [block("deck", (1.2, 0.8, board), (0, 0, 0.144 - board / 2), WOOD)]
    for j, y in enumerate(rows):
        parts.append(block(f"runner_{j}", (1.2, 0.1, board), (0, y, board / 2), WOOD))
        for i, x in enumerate(columns):
            center = (x, y, board + block_height / 2)
            parts.append(block(f"block_{j}{i}", (0.145, 0.1, block_height), center, WOOD))
    return CellObject(parts, 25.0, {"top": on_surface(0.144)})


def open_bin(length: float, width: float, height: float, mass: float) -> CellObject:
    """Open plastic container: floor and four walls; `top` on the inner floor, `rim` above."""
    wall = 0.012
    parts = [
        block("floor", (length, width, wall), (0, 0, wall / 2), BIN_BLUE),
        block("wall_front", (length, wall, height), (0, (width - wall) / 2, height / 2), BIN_BLUE),
        block("wall_back", (length, wall, height), (0, -(width - wall) / 2, height / 2), BIN_BLUE),
        block("wall_left", (wall, width, height), ((length - wall) / 2, 0, height / 2), BIN_BLUE),
        block("wall_right", (wall, width, height), (-(length - wall) / 2, 0, height / 2), BIN_BLUE),
    ]
    return CellObject(parts, mass, {"top": on_surface(wall), "rim": on_surface(height)})


def shelf(length: float, width: float, board_heights: tuple[float, ...], mass: float) -> CellObject:
    """Open shelf: boards (frames `board_<i>`, bottom up) between four uprights."""
    thickness = 0.02
    parts = legs(length, width, board_heights[-1])
    frames = {}
    for i, height in enumerate(board_heights):
        center = (0, 0, height - thickness / 2)
        parts.append(block(f"board_{i}", (length, width, thickness), center, STEEL))
        frames[f"board_{i}"] = on_surface(height)
    return CellObject(parts, mass, frames)


def fence(length: float, height: float, mass: float) -> CellObject:
    """A safety fence panel along x from the floor up (its mesh is one thin sheet), on two
    posts at its ends."""
    sheet = 0.02
    parts = [block("panel", (length, sheet, height), (0, 0, height / 2), GUARD_YELLOW)]
    for i, x in enumerate((-(length - LEG) / 2, (length - LEG) / 2)):
        parts.append(block(f"post_{i}", (LEG, LEG, height), (x, 0, height / 2), STEEL))
    return CellObject(parts, mass)


def loose_box(size: tuple[float, float, float], mass: float, color: Color) -> CellObject:
    """A part or carton centred on its body origin, with `bottom`, `top` and `grasp` frames."""
    half = size[2] / 2
    frames = {
        "bottom": on_surface(-half),
        "top": on_surface(half),
        "grasp": RigidTransform(RollPitchYaw(math.pi, 0, 0), [0, 0, half]),
    }
    return CellObject([block("box", size, (0, 0, 0), color)], mass, frames)


CELL_OBJECTS: dict[str, Callable[[], CellObject]] = {
    "floor": floor,
    "work_table": lambda: table(1.2, 0.8, 0.9, 30.0),
    "side_table": lambda: table(0.8, 0.6, 0.75, 15.0),
    "robot_pedestal": lambda: pedestal(0.4, 0.8, 60.0),
    "conveyor": lambda: conveyor(2.0, 0.4, 0.85, 80.0),
    "euro_pallet": euro_pallet,
    "bin": lambda: open_bin(0.6, 0.4, 0.22, 2.0),
    "shelf": lambda: shelf(0.8, 0.4, (0.1, 0.6, 1.1, 1.6), 25.0),
    "fence": lambda: fence(2.0, 1.4, 20.0),
    "part_small": lambda: loose_box((0.06, 0.04, 0.03), 0.1, (0.3, 0.45, 0.72, 1.0)),
    "part_medium": lambda: loose_box((0.12, 0.08, 0.05), 0.4, (0.86, 0.5, 0.12, 1.0)),
    "box_small": lambda: loose_box((0.3, 0.2, 0.2), 1.2, CARDBOARD),
    "box_large": lambda: loose_box((0.4, 0.3, 0.25), 2.5, CARDBOARD),
}


def cell_sdf(name: str) -> str:
    cell_object = CELL_OBJECTS[name]()
    root, model = new_model(name)
    add_link(model, BODY, cell_object.parts, cell_object.mass, friction=FRICTION)
    for frame_name, pose in cell_object.frames.items():
        add_frame(model, frame_name, BODY, pose)
    return to_text(root)
