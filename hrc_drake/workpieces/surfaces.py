"""Horizontal support surfaces: from the cell's static collision geometry and the scenario.

A surface is a convex outline in the floor plane at a height. The cell's are the top faces
of collision boxes (with one axis vertical) and of vertical cylinders on anchored bodies of
the plant, named after their model instance (`work_table`, `conveyor`, `euro_pallet`, ...).
The floor (z = 0, unbounded) is always there.
"""

import heapq
import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np
from pydrake.geometry import Box, Cylinder, SceneGraph
from pydrake.math import RigidTransform
from pydrake.multibody.plant import MultibodyPlant

from hrc_drake.scene_geometry import anchored_collision_shapes
from hrc_drake.workpieces.config import SurfaceConfig
from hrc_drake.workpieces.geometry import CIRCLE_SIDES, edge_normals, overlaps

FLOOR = "floor"
VERTICAL = 1.0 - 1e-9
"""|cos| of the angle between an axis and world z above which the axis counts as vertical."""
TIE_TOLERANCE = 1e-4
"""m: supports this close in height count as level."""


@dataclass(frozen=True)
class Surface:
    """A horizontal face at `height`; `outline` is convex (n, 2), None for the whole plane."""

    name: str
    height: float
    outline: np.ndarray | None

    @cached_property
    def bounds(self) -> tuple[np.ndarray, np.ndarray] | None:
        """Lower and upper corner of the outline's bounding box (None: unbounded)."""
        if self.outline is None:
            return None
        return self.outline.min(axis=0), self.outline.max(axis=0)

    @cached_property
    def normals(self) -> np.ndarray | None:
        """The outline's edge normals (for `overlaps`), None for the whole plane."""
        return None if self.outline is None else edge_normals(self.outline)

    def may_overlap(self, low: np.ndarray, high: np.ndarray) -> bool:
        """A cheap test before the exact one: do the bounding boxes overlap?"""
        if self.bounds is None:
            return True
        own_low, own_high = self.bounds
        return bool((own_high > low).all() and (own_low < high).all())


FLOOR_SURFACE = Surface(FLOOR, 0.0, None)


def named_surfaces(surfaces: dict[str, SurfaceConfig]) -> list[Surface]:
    """The scenario's explicit rectangles."""
    return [
        _rectangle(name, config.pose.GetDeterministicValue(), config.size)
        for name, config in surfaces.items()
    ]


def cell_surfaces(plant: MultibodyPlant, scene_graph: SceneGraph) -> list[Surface]:
    """Top faces of the static (anchored) collision geometry of a finalized plant."""
    found = []
    for name, shape, X_WG in anchored_collision_shapes(plant, scene_graph.model_inspector()):
        surface = top_face(name, shape, X_WG)
        if surface is not None:
            found.append(surface)
    return found


def top_face(name: str, shape, X_WG: RigidTransform) -> Surface | None:
    """The upward face of a box with a vertical axis or of a vertical cylinder, else None."""
    R = X_WG.rotation().matrix()
    vertical = [axis for axis in range(3) if abs(R[2, axis]) >= VERTICAL]
    if not vertical:
        return None
    axis = vertical[0]
    if isinstance(shape, Box):
        size = np.array([shape.width(), shape.depth(), shape.height()])
        half = np.delete(size / 2, axis)
        sides = np.delete(R[:2, :], axis, axis=1) * half
        corners = [(-1, -1), (1, -1), (1, 1), (-1, 1)]
        outline = np.array([X_WG.translation()[:2] + sides @ c for c in corners])
        return Surface(name, X_WG.translation()[2] + size[axis] / 2, outline)
    if isinstance(shape, Cylinder) and axis == 2:
        return _disk(name, X_WG.translation(), shape.radius(), shape.length())
    return None


def _rectangle(name: str, X_WS: RigidTransform, size) -> Surface:
    half = np.asarray(size, dtype=float) / 2
    corners = np.array([[-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0]]) * [*half, 0]
    outline = np.array([(X_WS @ c)[:2] for c in corners])
    return Surface(name, X_WS.translation()[2], outline)


def _disk(name: str, center: np.ndarray, radius: float, length: float) -> Surface:
    angles = np.arange(CIRCLE_SIDES) * 2 * math.pi / CIRCLE_SIDES
    outline = center[:2] + radius * np.stack([np.cos(angles), np.sin(angles)], axis=1)
    return Surface(name, center[2] + length / 2, outline)


class Supports:
    """The fixed supports (highest first) and the search for what an outline rests on."""

    def __init__(self, surfaces: list[Surface], belts: set[str]):
        self.fixed = sorted([FLOOR_SURFACE, *surfaces], key=lambda s: -s.height)
        self.belts = belts
        unbounded = (np.full(2, -np.inf), np.full(2, np.inf))
        lows, highs = zip(*(s.bounds or unbounded for s in self.fixed), strict=True)
        self._lows, self._highs = np.array(lows), np.array(highs)
        self._heights = np.array([s.height for s in self.fixed])

    def _fixed_candidates(self, low: np.ndarray, high: np.ndarray, below: float) -> list:
        """The fixed supports (highest first) at most at `below` whose bounding boxes overlap
        the box from `low` to `high`: what `Surface.may_overlap` would pass, all at once."""
        passing = (
            (self._heights <= below)
            & (self._highs > low).all(axis=1)
            & (self._lows < high).all(axis=1)
        )
        return [self.fixed[k] for k in np.flatnonzero(passing)]

    def under(self, outline: np.ndarray, below: float, others: list[Surface]) -> Surface:
        """The highest support overlapping `outline` with its top at most at `below` (a belt
        wins over level fixed surfaces); the floor when nothing is below. Supports too high
        or whose bounding boxes miss the outline's are left out before the exact tests, and
        the outline's edge normals are worked out only for a bounded one."""
        low, high = outline.min(axis=0), outline.max(axis=0)
        candidates = self._fixed_candidates(low, high, below)
        movable = [s for s in others if s.height <= below and s.may_overlap(low, high)]
        if movable:
            movable.sort(key=lambda s: -s.height)
            candidates = heapq.merge(candidates, movable, key=lambda s: -s.height)
        own_normals = None
        level: list[Surface] = []
        for surface in candidates:
            if level and surface.height < level[0].height - TIE_TOLERANCE:
                break
            if surface.outline is not None and own_normals is None:
                own_normals = edge_normals(outline)
            if overlaps(outline, surface.outline, normals=(own_normals, surface.normals)):
                level.append(surface)
        if not level:
            return FLOOR_SURFACE
        return next((s for s in level if s.name in self.belts), level[0])
