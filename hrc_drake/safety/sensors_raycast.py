"""Where a sensor's beams end: rays cast against the scene's proximity shapes (boxes,
spheres, ellipsoids, cylinders, capsules: every shape the cell, the robot, the person and
the objects are made of), in closed form and in numpy, all pairs of a ray and a shape of a
kind at once.

Drake's QueryObject has no ray cast, so each ray is taken into each shape's frame and met
with the shape's own surface: slabs for a box, a quadric for a sphere or ellipsoid, the
side and the caps (flat for a cylinder, round for a capsule). A ray starting inside a shape
ends where it starts. Only shapes whose bounding capsule (hrc_drake.safety.geometry)
reaches the beams' heights and range are met at all: a scan plane 0.3 m up crosses the
person's shanks and the furniture's legs, not the rest, and each beam only the shapes it
passes near.
"""

from dataclasses import dataclass

import numpy as np
from pydrake.geometry import Box, Capsule, Cylinder, Ellipsoid, Sphere

from hrc_drake.safety.geometry import bounding_segment

MISS = np.inf
TINY = 1e-12
KINDS = (Box, Sphere, Ellipsoid, Cylinder, Capsule)


@dataclass(frozen=True, eq=False)
class Solids:
    """Shapes as rays meet them, stacked: per shape its kind (index in KINDS), its sizes
    in its frame (a box's half sizes, a sphere's radius, an ellipsoid's radii, a cylinder's
    or capsule's radius and half length along z; unused ones 0), and its bounding capsule
    (segment ends, 3 × 2 in its frame, and radius)."""

    kinds: np.ndarray
    sizes: np.ndarray
    ends: np.ndarray
    radii: np.ndarray

    def __len__(self) -> int:
        return len(self.kinds)

    def subset(self, chosen: np.ndarray) -> "Solids":
        """The chosen shapes (indices or a mask), in their order."""
        return Solids(self.kinds[chosen], self.sizes[chosen], self.ends[chosen], self.radii[chosen])


def solids(shapes: list) -> Solids:
    """The shapes (Drake's) as rays meet them (ValueError for one they cannot meet)."""
    kinds, sizes, ends, radii = [], [], [], []
    for shape in shapes:
        if not isinstance(shape, KINDS):
            raise ValueError(f"a safety sensor's beams cannot meet a {type(shape).__name__}")
        kinds.append(next(k for k, kind in enumerate(KINDS) if isinstance(shape, kind)))
        sizes.append(np.pad(_sizes(shape), (0, 3 - len(_sizes(shape)))))
        p0, p1, radius = bounding_segment(shape)
        ends.append(np.column_stack([p0, p1]))
        radii.append(radius)
    return Solids(
        np.array(kinds, dtype=int),
        np.array(sizes).reshape(-1, 3),
        np.array(ends).reshape(-1, 3, 2),
        np.array(radii),
    )


def _sizes(shape) -> np.ndarray:
    if isinstance(shape, Box):
        return shape.size() / 2
    if isinstance(shape, Sphere):
        return np.array([shape.radius()])
    if isinstance(shape, Ellipsoid):
        return np.array([shape.a(), shape.b(), shape.c()])
    return np.array([shape.radius(), shape.length() / 2])


def cast(
    origins: np.ndarray,
    directions: np.ndarray,
    length: float,
    shapes: Solids,
    poses: np.ndarray,
    fan: np.ndarray | None = None,
) -> tuple[np.ndarray, np.ndarray]:
    """For rays `origins` + t `directions` (rays × 3, unit directions), 0 ≤ t ≤ `length`:
    the distance t at which each ray first meets one of `shapes` posed at `poses` (shapes ×
    3 × 4, world), MISS where none; and the index of the shape it meets (-1 where none).

    Only the (shape, ray) pairs whose ray passes the sphere round the shape's bounding
    capsule are met: a scanner's beam meets a few shapes, not all. `fan`: the rays are a
    scanner's, from one origin in a horizontal plane, and these are their yaws (rad,
    increasing), which finds each shape's rays by their angle."""
    best = np.full(len(origins), MISS)
    which = np.full(len(origins), -1)
    pairs = _fan_pairs if fan is not None else _pairs
    shape, ray = pairs(origins, directions, length, shapes, poses, fan)
    rotations = poses[shape, :, :3]
    # each pair's ray in its shape's frame: R^T (p - p_WG), R^T d
    o = ((origins[ray] - poses[shape, :, 3])[:, :, None] * rotations).sum(axis=1)
    d = (directions[ray][:, :, None] * rotations).sum(axis=1)
    kinds = shapes.kinds[shape]
    distances = np.full(len(shape), MISS)
    for kind, meet in enumerate(_MEET):
        chosen = np.flatnonzero(kinds == kind)
        if len(chosen):
            distances[chosen] = meet(o[chosen], d[chosen], shapes.sizes[shape[chosen]])
    np.minimum.at(best, ray, distances)
    first = np.isfinite(distances) & (distances == best[ray])
    which[ray[first]] = shape[first]
    beyond = best > length
    best[beyond], which[beyond] = MISS, -1
    return best, which


def _pairs(origins, directions, length, shapes: Solids, poses: np.ndarray, _fan=None):
    """(shape, ray) index pairs whose ray passes within the sphere round the shape's
    bounding capsule, at most `length` along it."""
    segments = poses[:, :, :3] @ shapes.ends + poses[:, :, 3:]
    near = np.flatnonzero(_near(origins, directions, length, segments, shapes.radii))
    segments = segments[near]
    centres = segments.mean(axis=2)
    reach = np.linalg.norm(segments[:, :, 1] - segments[:, :, 0], axis=1) / 2
    r = (reach + shapes.radii[near])[:, None]
    apart = centres[:, None, :] - origins[None]
    along = (apart * directions[None]).sum(axis=2)
    aside = (apart * apart).sum(axis=2) - along * along
    meets = (aside <= r * r) & (along >= -r) & (along <= length + r)
    shape, ray = np.nonzero(meets)
    return near[shape], ray


def _fan_pairs(origins, directions, length, shapes: Solids, poses: np.ndarray, fan):
    """`_pairs` for a scanner's fan of rays: the yaws, seen from the origin, of each shape's
    box on the floor (all of them round a box that holds the origin)."""
    segments = poses[:, :, :3] @ shapes.ends + poses[:, :, 3:]
    near = np.flatnonzero(_near(origins, directions, length, segments, shapes.radii))
    low, high = _footprints(shapes, poses, segments, near)
    origin = origins[0, :2]
    inside = np.all((low <= origin) & (origin <= high), axis=1)
    corners = (
        np.stack(
            [
                low,
                high,
                np.column_stack([low[:, 0], high[:, 1]]),
                np.column_stack([high[:, 0], low[:, 1]]),
            ],
            axis=1,
        )
        - origin
    )
    middle = np.arctan2(*((low + high) / 2 - origin)[:, ::-1].T)
    turns = np.arctan2(corners[:, :, 1], corners[:, :, 0]) - middle[:, None]
    turns = np.mod(turns + np.pi, 2.0 * np.pi) - np.pi
    middle = fan[0] + np.mod(middle - fan[0], 2.0 * np.pi)  # on or after the first yaw
    starts, stops = [], []
    for wrap in (-2.0 * np.pi, 0.0):
        starts.append(np.searchsorted(fan, middle + turns.min(axis=1) + wrap, side="left"))
        stops.append(np.searchsorted(fan, middle + turns.max(axis=1) + wrap, side="right"))
    starts[1] = np.where(inside, 0, starts[1])
    stops[1] = np.where(inside, len(fan), stops[1])
    stops[0] = np.where(inside, 0, stops[0])
    ray, owner = _ranges(np.concatenate(starts), np.concatenate(stops))
    return np.concatenate([near, near])[owner], ray


def _footprints(shapes: Solids, poses, segments, near) -> tuple[np.ndarray, np.ndarray]:
    """Floor boxes (lows and highs, near shapes × 2) that hold the shapes: a box's from its
    corners, another shape's from its bounding capsule."""
    radii = shapes.radii[near, None]
    low = segments[near, :2].min(axis=2) - radii
    high = segments[near, :2].max(axis=2) + radii
    boxes = np.flatnonzero(shapes.kinds[near] == KINDS.index(Box))
    if len(boxes):
        signs = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)])
        chosen = near[boxes]
        local = signs[None] * shapes.sizes[chosen][:, None, :]
        corners = local @ poses[chosen, :, :3].transpose(0, 2, 1) + poses[chosen, None, :, 3]
        low[boxes] = corners[:, :, :2].min(axis=1)
        high[boxes] = corners[:, :, :2].max(axis=1)
    return low, high


def _ranges(starts: np.ndarray, stops: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Every index of the ranges starts[k]..stops[k] - 1, one after the other, and the k of
    each."""
    counts = np.maximum(stops - starts, 0)
    owner = np.repeat(np.arange(len(starts)), counts)
    first = np.cumsum(counts) - counts
    return np.arange(counts.sum()) - first[owner] + starts[owner], owner


def _near(origins, directions, length, segments: np.ndarray, radii: np.ndarray) -> np.ndarray:
    """Which bounding capsules (their segments, shapes × 3 × 2, world) come within reach of
    the rays at all: within the rays' heights (plus the capsule's radius) and within
    `length` of the origins."""
    ends = origins + length * directions
    z_low = min(origins[:, 2].min(), ends[:, 2].min())
    z_high = max(origins[:, 2].max(), ends[:, 2].max())
    centre = (origins.min(axis=0) + origins.max(axis=0)) / 2
    spread = np.linalg.norm(origins.max(axis=0) - origins.min(axis=0)) / 2 + length
    within = (segments[:, 2].min(axis=1) - radii <= z_high) & (
        segments[:, 2].max(axis=1) + radii >= z_low
    )
    start, span = segments[:, :, 0], segments[:, :, 1] - segments[:, :, 0]
    share = ((centre - start) * span).sum(axis=1) / np.maximum((span * span).sum(axis=1), TINY)
    closest = start + np.clip(share, 0.0, 1.0)[:, None] * span
    return within & (np.linalg.norm(closest - centre, axis=1) - radii <= spread)


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
    enter = np.minimum(t1, t2).max(axis=-1)
    leave = np.maximum(t1, t2).min(axis=-1)
    hit = leave >= np.maximum(enter, 0.0)
    return np.where(hit, np.maximum(enter, 0.0), MISS)


def _sphere(o: np.ndarray, d: np.ndarray, sizes: np.ndarray) -> np.ndarray:
    radius = sizes[..., 0]
    a, b, c = (d * d).sum(axis=-1), (o * d).sum(axis=-1), (o * o).sum(axis=-1) - radius**2
    return _first_root(a, b, c)


def _ellipsoid(o: np.ndarray, d: np.ndarray, radii: np.ndarray) -> np.ndarray:
    """The unit sphere, after scaling each axis by its radius."""
    return _sphere(o / radii, d / radii, np.ones_like(radii))


def _side(o: np.ndarray, d: np.ndarray, radius, half) -> np.ndarray:
    """The round side of a cylinder about z, between z = ±half (from outside it)."""
    a = d[..., 0] ** 2 + d[..., 1] ** 2
    b = o[..., 0] * d[..., 0] + o[..., 1] * d[..., 1]
    c = o[..., 0] ** 2 + o[..., 1] ** 2 - radius**2
    t = _first_root(np.maximum(a, TINY), b, c)
    t = np.where((a > TINY) | (c <= 0.0), t, MISS)
    z = o[..., 2] + np.where(np.isfinite(t), t, 0.0) * d[..., 2]
    return np.where(np.abs(z) <= half, t, MISS)


def _cylinder(o: np.ndarray, d: np.ndarray, sizes: np.ndarray) -> np.ndarray:
    radius, half = sizes[..., 0], sizes[..., 1]
    t = _side(o, d, radius, half)
    dz = np.where(np.abs(d[..., 2]) < TINY, TINY, d[..., 2])
    for cap in (-half, half):
        s = (cap - o[..., 2]) / dz
        x, y = o[..., 0] + s * d[..., 0], o[..., 1] + s * d[..., 1]
        on_cap = (s >= 0.0) & (x * x + y * y <= radius**2)
        t = np.minimum(t, np.where(on_cap, s, MISS))
    inside = (o[..., 0] ** 2 + o[..., 1] ** 2 <= radius**2) & (np.abs(o[..., 2]) <= half)
    return np.where(inside, 0.0, t)


def _capsule(o: np.ndarray, d: np.ndarray, sizes: np.ndarray) -> np.ndarray:
    radius, half = sizes[..., 0], sizes[..., 1]
    t = _side(o, d, radius, half)
    for sign in (-1.0, 1.0):
        shifted = o.copy()
        shifted[..., 2] -= sign * half
        t = np.minimum(t, _sphere(shifted, d, sizes))
    return t


_MEET = (
    lambda o, d, sizes: _box(o, d, sizes[..., :3]),
    _sphere,
    _ellipsoid,
    _cylinder,
    _capsule,
)
"""Per kind (KINDS' order): the distances along rays given in the shapes' frames (pairs ×
3: origins, directions) to the shapes of those sizes (pairs × 3)."""
