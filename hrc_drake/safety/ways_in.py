"""Where a person can walk into a scanner-guarded cell unseen (for the ISO 13855 field
check, hrc_drake.safety.sensors_checks): the floor they can walk to within a distance of
the robot's reach round the cell's furniture, the parts of a scanner's fan that the cell's
fixed geometry hides from it (ray-cast on its scan plane), and, of a gap no field covers
where its scanner sees, the pieces that are a way in and where they lie, in words."""

import math
from functools import lru_cache

import numpy as np
from shapely.geometry import Polygon
from shapely.ops import nearest_points, unary_union

from hrc_drake.safety.sensors import LaserScanner
from hrc_drake.safety.sensors_cell import Cell
from hrc_drake.safety.sensors_raycast import cast
from hrc_drake.safety.sensors_reading import beams

WAVE_STEP = 0.05
"""m: the walking distance from the reach grows in steps of this (round the furniture)"""
EDGE = 0.1
"""m: a gap this close to the walk's edge at S is a way in from beyond S"""
SEAM = 0.01
"""m: furniture is grown by this much, so that where two pieces meet (two fence panels end
to end) no hairline gap lets the walk through"""


def ways_in(hazard, distance: float, obstacles: tuple, covered, drawn, scanner: LaserScanner):
    """The places within walking distance `distance` of `hazard` that no field covers where
    its scanner sees, wide enough for the detection capability, that are a way in: outside
    every field `drawn`, or reaching the walk's edge at `distance` (a blind pocket that the
    seen field encloses cannot be entered unseen: who stands in it is a run's to show)."""
    required, edge = _walkable_within(hazard, distance, obstacles)
    gap = required.difference(covered).buffer(-scanner.detection_capability / 2)
    pieces = getattr(gap, "geoms", [gap])
    return unary_union(
        [p for p in pieces if not p.is_empty and (p.intersects(edge) or not p.within(drawn))]
    )


def shadows(scanner: LaserScanner, cell: Cell) -> dict[str, Polygon]:
    """The floor of the scanner's scan plane within its angles and range that the cell's
    fixed geometry hides from it (beyond where its beams stop: a field drawn behind a fence
    watches nothing there), by the name of what stops the beams."""
    origins, directions, length = beams(scanner)
    angles = scanner.beam_angles()
    ranges, which = cast(origins, directions, length, cell.shapes, cell.poses, angles)
    shadow = _fan(scanner, np.full_like(ranges, length)).difference(_fan(scanner, ranges))
    names = np.array(cell.names + [""])[which]
    return {
        name: shadow.intersection(_sectors(scanner, angles[names == name]))
        for name in sorted(set(names) - {""})
    }


def _fan(scanner: LaserScanner, ranges: np.ndarray) -> Polygon:
    """The floor the scanner's beams cover out to `ranges` (per beam, at most its range)."""
    origin = scanner.origin()[:2]
    ends = origin + np.minimum(ranges, scanner.range)[:, None] * scanner.beam_directions()[:, :2]
    low, high = scanner.angles_deg
    return Polygon(ends if high - low >= 360.0 else np.vstack([origin, ends])).buffer(0)


def _sectors(scanner: LaserScanner, angles: np.ndarray) -> Polygon:
    """The scanner's beams at `angles` (rad), each widened to half the way to the next."""
    origin = scanner.origin()[:2]
    half = math.radians(scanner.resolution_deg) / 2
    far = 2.0 * scanner.range
    return unary_union(
        [
            Polygon([origin, *(origin + far * np.array([math.cos(a), math.sin(a)]) for a in ends)])
            for ends in zip(angles - half, angles + half, strict=True)
        ]
    )


def unseen_places(gap, hazard, drawn, fields: dict, shadows: dict) -> str:
    """Where a person walks in unseen: the place of `gap` nearest the reach outside every
    field (`drawn`), and in each scanner's field the nearest that each piece of the cell
    hides."""
    places = [(gap.difference(drawn), "in no protective field")]
    for name, by_blocker in shadows.items():
        if fields[name] is None:
            continue
        places += [
            (
                gap.intersection(fields[name]).intersection(shadow),
                f"in the protective field of '{name}', where the cell's {blocker} hides them "
                "from the scanner",
            )
            for blocker, shadow in by_blocker.items()
        ]
    said = []
    for part, why in sorted(
        ((part, why) for part, why in places if not part.is_empty),
        key=lambda place: place[0].distance(hazard),
    ):
        point, _ = nearest_points(part, hazard)
        where = f"[{point.x:.2f}, {point.y:.2f}], {point.distance(hazard):.2f} m from the reach"
        said.append(f"a person at {where}, is {why}")
    return "; ".join(said) or "a person walks in where no scanner sees them"


@lru_cache(maxsize=16)
def _walkable_within(hazard: Polygon, distance: float, obstacles: tuple[Polygon, ...]):
    """The floor a person can walk to within `distance` of `hazard`, round the obstacles,
    and the part of it they reach in the last EDGE (the walk's edge): a wave from the
    hazard, each step keeping only the pieces that touch the last (a step across a thin
    fence lands in a piece of its own). Kept per process: the wave takes a second or more,
    and a scenario's falsify ranges re-check the same fields once per end."""
    blocked = unary_union(obstacles).buffer(SEAM)
    region = inner = hazard
    steps = max(1, math.ceil(distance / WAVE_STEP))
    edge_steps = math.ceil(EDGE / (distance / steps))
    for step in range(steps):
        if step == steps - edge_steps:
            inner = region
        grown = region.buffer(distance / steps).difference(blocked)
        pieces = getattr(grown, "geoms", [grown])
        region = unary_union([p for p in pieces if p.intersects(region)] + [hazard])
    return region.difference(blocked), region.difference(inner)
