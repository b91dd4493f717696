"""The objects present at the start: the explicit list and the grid layouts (loaded pallets).

Random choices (which grid places are occupied, the boolean attributes) come from one numpy
Generator derived from the run's seed, drawn in a fixed order (grid by grid, layer, row,
column; attributes by name; then the objects that carry the counted attributes), so the same
seed gives the same layout.
"""

from dataclasses import dataclass

import numpy as np
from pydrake.math import RigidTransform

from hrc_drake.workpieces.config import BOX, GridLayout, ObjectType, WorkpiecesConfig
from hrc_drake.workpieces.geometry import Solid
from hrc_drake.workpieces.messages import Attributes


@dataclass(frozen=True)
class Placement:
    """An object to create: its type, where, and its own attributes (over the type's)."""

    type: str
    pose: RigidTransform
    attributes: Attributes


def initial_placements(config: WorkpiecesConfig, rng: np.random.Generator) -> list[Placement]:
    explicit = [
        Placement(o.type, o.pose.GetDeterministicValue(), dict(o.attributes))
        for o in config.objects
    ]
    grids = [p for g in config.grids for p in grid_placements(g, config.types[g.type], rng)]
    return explicit + grids


def grid_placements(
    grid: GridLayout, object_type: ObjectType, rng: np.random.Generator
) -> list[Placement]:
    """The occupied places of a grid, bottom layer first, each object resting on the one below."""
    dx, dy = grid.spacing or _footprint_size(object_type)
    height = Solid.of(object_type).height
    X_WG = grid.origin.GetDeterministicValue()
    occupied = []
    for layer in range(grid.layers):
        for row in range(grid.rows):
            for column in range(grid.columns):
                is_occupied = rng.random() < grid.occupancy
                attributes = dict(grid.attributes) | _draw(grid.attribute_probabilities, rng)
                if not is_occupied:
                    continue
                offset = [
                    (column - (grid.columns - 1) / 2) * dx,
                    (row - (grid.rows - 1) / 2) * dy,
                    (layer + 0.5) * height,
                ]
                occupied.append((X_WG @ RigidTransform(offset), attributes))
    counted = _deal(grid.attribute_counts, len(occupied), rng)
    return [
        Placement(grid.type, pose, attributes | extra)
        for (pose, attributes), extra in zip(occupied, counted, strict=True)
    ]


def _footprint_size(object_type: ObjectType) -> tuple[float, float]:
    if object_type.shape == BOX:
        return object_type.size[0], object_type.size[1]
    return 2 * object_type.size[0], 2 * object_type.size[0]


def _deal(counts: dict[str, int], n: int, rng: np.random.Generator) -> list[Attributes]:
    """For each of `n` objects, the counted attributes: each true on its count of objects,
    dealt in turn (by name) along one shuffle, so that no object gets two of them (with fewer
    objects than counts, the last names run short)."""
    if not counts:
        return [{}] * n
    names = [name for name in sorted(counts) for _ in range(counts[name])]
    dealt = dict(zip(rng.permutation(n).tolist(), names, strict=False))
    return [{name: dealt.get(i) == name for name in counts} for i in range(n)]


def _draw(probabilities: dict[str, float], rng: np.random.Generator) -> Attributes:
    return {name: bool(rng.random() < probabilities[name]) for name in sorted(probabilities)}
