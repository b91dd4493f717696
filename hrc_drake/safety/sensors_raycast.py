"""Where a sensor's beams end: rays cast against the scene's proximity shapes (boxes,
spheres, ellipsoids, cylinders, capsules: every shape the cell, the robot, the person and
the objects are made of), in closed form and in numpy, every ray against every shape at
once.

Drake's QueryObject has no ray cast, so each ray is taken into each shape's frame and met
with the shape's own surface: slabs for a box, a quadric for a sphere or ellipsoid, the
side and the caps (flat for a cylinder, round for a capsule). A ray starting inside a shape
ends where it starts. Only shapes whose bounding capsule (hrc_drake.safety.geometry)
reaches the beams' heights and range are met at all: a scan plane 0.3 m up crosses the
person's shanks and the furniture's legs, not the rest.
"""

from dataclasses import dataclass

import numpy as np
from pydrake.geometry import Box, Capsule, Cylinder, Ellipsoid, GeometryId, Sphere

from hrc_drake.safety.geometry import bounding_segment

MISS = np.inf
TINY = 1e-12


@dataclass(frozen=True)
class Solid:
    """A shape in its geometry frame: its kind and sizes, and its bounding capsule."""

    geometry: GeometryId
    kind: type
    sizes: np.ndarray
    """box: half sizes; sphere: radius; ellipsoid: radii; cylinder, capsule: radius and
    half length (along z)"""
    ends: np.ndarray
    """the bounding capsule's segment ends (3 × 2), in the geometry frame"""
    radius: float


def solid(geometry: GeometryId, shape) -> Solid:
    """The shape of `geometry` as rays meet it (ValueError for a shape rays cannot meet)."""
    if isinstance(shape, Box):
        sizes = shape.size() / 2
    elif isinstance(shape, Sphere):
        sizes = np.array([shape.radius()])
    elif isinstance(shape, Ellipsoid):
        sizes = np.array([shape.a(), shape.b(), shape.c()])
    elif isinstance(shape, Capsule | Cylinder):
        sizes = np.array([shape.radius(), shape.length() / 2])
    else:
        raise ValueError(f"a safety sensor's beams cannot meet a {type(shape).__name__}")
    p0, p1, radius = bounding_segment(shape)
    return Solid(geometry, type(shape), sizes, np.column_stack([p0, p1]), radius)


def cast(
    origins: np.ndarray,
    directions: np.ndarray,
    length: float,
    solids: list[Solid],
    poses: list[np.ndarray],
) -> tuple[np.ndarray, np.ndarray]:
    """For rays `origins` + t `directions` (rays × 3, unit directions), 0 ≤ t ≤ `length`:
    the distance t at which each ray first meets one of `solids` posed at `poses` (3 × 4
    world poses), MISS where none; and the index of the solid it meets (-1 where none)."""
    best = np.full(len(origins), MISS)
    which = np.full(len(origins), -1)
    candidates = _near(origins, directions, length, solids, poses)
    for k in candidates:
        pose = poses[k]
        rotation, position = pose[:, :3], pose[:, 3]
        o = (origins - position) @ rotation  # into the shape's frame: R^T (p - p_WG)
        d = directions @ rotation
        t = _MEET[solids[k].kind](o, d, solids[k].sizes)
        closer = t < best
        best[closer] = t[closer]
        which[closer] = k
    beyond = best > length
    best[beyond], which[beyond] = MISS, -1
    return best, which


def _near(origins, directions, length, solids, poses) -> list[int]:
    """The solids whose bounding capsule comes within reach of the rays: within their
    heights (plus the capsule's radius) and within `length` of an origin."""
    ends = origins + length * directions
    z_low = min(origins[:, 2].min(), ends[:, 2].min())
    z_high = max(origins[:, 2].max(), ends[:, 2].max())
    centre = (origins.min(axis=0) + origins.max(axis=0)) / 2
    spread = np.linalg.norm(origins.max(axis=0) - origins.min(axis=0)) / 2 + length
    found = []
    for k, (shape, pose) in enumerate(zip(solids, poses, strict=True)):
        segment = pose[:, :3] @ shape.ends + pose[:, 3:]
        if segment[2].min() - shape.radius > z_high or segment[2].max() + shape.radius < z_low:
            continue
        if _point_segment(centre, segment) - shape.radius > spread:
            continue
        found.append(k)
    return found


def _point_segment(point: np.ndarray, segment: np.ndarray) -> float:
    start, span = segment[:, 0], segment[:, 1] - segment[:, 0]
    share = np.clip((point - start) @ span / max(span @ span, TINY), 0.0, 1.0)
    return float(np.linalg.norm(start + share * span - point))


def _first_root(a: np.ndarray, b: np.ndarray, c: np.ndarray) -> np.ndarray:
    """First t ≥ 0 with a t² + 2 b t + c = 0 (a > 0) for a ray leaving c ≤ 0 (inside):
    0 inside, MISS where the ray passes by or the surface lies behind it."""
    disc = b * b - a * c
    root = np.sqrt(np.maximum(disc, 0.0))
    near = (-b - root) / a
    far = (-b + root) / a
    t = np.where(near >= 0.0, near, np.where(far >= 0.0, 0.0, MISS))
    t = np.where(disc >= 0.0, t, MISS)
    return np.where(c <= 0.0, 0.0, t)


def _box(o: np.ndarray, d: np.ndarray, half: np.ndarray) -> np.ndarray:
    """Slabs: the ray is inside all three between its last entry and its first exit."""
    safe = np.where(np.abs(d) < TINY, TINY, d)
    t1, t2 = (-half - o) / safe, (half - o) / safe
    enter = np.minimum(t1, t2).max(axis=1)
    leave = np.maximum(t1, t2).min(axis=1)
    hit = leave >= np.maximum(enter, 0.0)
    return np.where(hit, np.maximum(enter, 0.0), MISS)


def _sphere(o: np.ndarray, d: np.ndarray, sizes: np.ndarray) -> np.ndarray:
    radius = sizes[0]
    return _first_root((d * d).sum(axis=1), (o * d).sum(axis=1), (o * o).sum(axis=1) - radius**2)


def _ellipsoid(o: np.ndarray, d: np.ndarray, radii: np.ndarray) -> np.ndarray:
    """The unit sphere, after scaling each axis by its radius."""
    return _sphere(o / radii, d / radii, np.ones(1))


def _side(o: np.ndarray, d: np.ndarray, radius: float, half: float) -> np.ndarray:
    """The round side of a cylinder about z, between z = ±half (from outside it)."""
    a = d[:, 0] ** 2 + d[:, 1] ** 2
    b = o[:, 0] * d[:, 0] + o[:, 1] * d[:, 1]
    c = o[:, 0] ** 2 + o[:, 1] ** 2 - radius**2
    t = _first_root(np.maximum(a, TINY), b, c)
    t = np.where((a > TINY) | (c <= 0.0), t, MISS)
    z = o[:, 2] + np.where(np.isfinite(t), t, 0.0) * d[:, 2]
    return np.where(np.abs(z) <= half, t, MISS)


def _cylinder(o: np.ndarray, d: np.ndarray, sizes: np.ndarray) -> np.ndarray:
    radius, half = sizes
    t = _side(o, d, radius, half)
    for cap in (-half, half):
        dz = np.where(np.abs(d[:, 2]) < TINY, TINY, d[:, 2])
        s = (cap - o[:, 2]) / dz
        x, y = o[:, 0] + s * d[:, 0], o[:, 1] + s * d[:, 1]
        on_cap = (s >= 0.0) & (x * x + y * y <= radius**2)
        t = np.minimum(t, np.where(on_cap, s, MISS))
    inside = (o[:, 0] ** 2 + o[:, 1] ** 2 <= radius**2) & (np.abs(o[:, 2]) <= half)
    return np.where(inside, 0.0, t)


def _capsule(o: np.ndarray, d: np.ndarray, sizes: np.ndarray) -> np.ndarray:
    radius, half = sizes
    t = _side(o, d, radius, half)
    for end in (-half, half):
        shifted = o - np.array([0.0, 0.0, end])
        t = np.minimum(t, _sphere(shifted, d, np.array([radius])))
    return t


_MEET = {Box: _box, Sphere: _sphere, Ellipsoid: _ellipsoid, Cylinder: _cylinder, Capsule: _capsule}
