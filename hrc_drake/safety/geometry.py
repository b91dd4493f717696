"""Which geometries the monitor watches, and a cheap numpy broad phase for their distances.

Every watched geometry is wrapped in a bounding capsule (a segment plus a radius) in its
SceneGraph frame. Segment-to-segment distances minus the radii are lower bounds of the
true signed distances (exact for capsule pairs), so the monitor asks SceneGraph for exact
distances only for the few pairs that can still be the closest or touching.
"""

from dataclasses import dataclass

import numpy as np
from pydrake.geometry import Box, Capsule, Cylinder, Ellipsoid, GeometryId, Sphere

from hrc_drake.human.sdf import REGION_SEPARATOR
from hrc_drake.human.skeleton import REGIONS

EPS = 1e-12


@dataclass(frozen=True)
class Part:
    """A watched geometry and the name reports use for it (body region or robot part)."""

    geometry: GeometryId
    name: str


def human_parts(plant, inspector, instance) -> list[Part]:
    """The person's proximity geometries with their ISO/TS 15066 region (from the name)."""
    parts = []
    for body_index in plant.GetBodyIndices(instance):
        for geometry in plant.GetCollisionGeometriesForBody(plant.get_body(body_index)):
            region = inspector.GetName(geometry).split("::")[-1].split(REGION_SEPARATOR)[0]
            if region not in REGIONS:
                raise ValueError(f"human geometry '{inspector.GetName(geometry)}' has no region")
            parts.append(Part(geometry, region))
    return parts


def body_parts(plant, instances) -> list[Part]:
    """The proximity geometries of the given model instances, named after their bodies."""
    return [
        Part(geometry, plant.get_body(body_index).name())
        for instance in instances
        for body_index in plant.GetBodyIndices(instance)
        for geometry in plant.GetCollisionGeometriesForBody(plant.get_body(body_index))
    ]


def bounding_segment(shape) -> tuple[np.ndarray, np.ndarray, float]:
    """Endpoints (in the geometry frame) and radius of a capsule that contains `shape`."""
    if isinstance(shape, Sphere):
        return _segment(np.zeros(3), 0.0, shape.radius())
    if isinstance(shape, Capsule | Cylinder):
        return _segment(np.array([0.0, 0.0, 1.0]), shape.length() / 2, shape.radius())
    if isinstance(shape, Box):
        half = shape.size() / 2
        return _capsule_about_longest_axis(half, np.linalg.norm)
    if isinstance(shape, Ellipsoid):
        radii = np.array([shape.a(), shape.b(), shape.c()])
        return _capsule_about_longest_axis(radii, np.max, shrink=True)
    raise ValueError(f"the safety monitor cannot bound a {type(shape).__name__}")


def _capsule_about_longest_axis(half_sizes: np.ndarray, cross_radius, shrink: bool = False):
    """Segment along the longest axis; radius covers the other two half sizes.

    For an ellipsoid (`shrink`) the segment stops short of the tips by the radius, which
    still contains it (the cap spheres cover the tips).
    """
    axis = int(np.argmax(half_sizes))
    others = np.delete(half_sizes, axis)
    radius = float(cross_radius(others))
    half_length = half_sizes[axis] - radius if shrink else half_sizes[axis]
    direction = np.eye(3)[axis]
    return _segment(direction, max(half_length, 0.0), radius)


def _segment(direction: np.ndarray, half_length: float, radius: float):
    return -half_length * direction, half_length * direction, float(radius)


def segment_distances(a0, a1, b0, b1) -> np.ndarray:
    """Distances between every segment a (n, 3) and every segment b (m, 3): an (n, m) array.

    Ericson, Real-Time Collision Detection, 5.1.9, vectorized.
    """
    d1 = (a1 - a0)[:, None, :]
    d2 = (b1 - b0)[None, :, :]
    r = a0[:, None, :] - b0[None, :, :]
    a = np.sum(d1 * d1, axis=-1)
    e = np.sum(d2 * d2, axis=-1)
    b = np.sum(d1 * d2, axis=-1)
    c = np.sum(d1 * r, axis=-1)
    f = np.sum(d2 * r, axis=-1)
    a_safe = np.where(a > EPS, a, 1.0)
    e_safe = np.where(e > EPS, e, 1.0)
    denom = a * e - b * b
    s = np.where(denom > EPS, np.clip((b * f - c * e) / np.where(denom > EPS, denom, 1.0), 0, 1), 0)
    s_at_t0, s_at_t1 = np.clip(-c / a_safe, 0, 1), np.clip((b - c) / a_safe, 0, 1)
    s = np.where(e > EPS, s, s_at_t0)
    t = np.where(e > EPS, (b * s + f) / e_safe, 0.0)
    s = np.where(t < 0, s_at_t0, np.where(t > 1, s_at_t1, s))
    s = s * (a > EPS)
    t = np.clip(t, 0, 1)
    gap = (a0[:, None, :] + d1 * s[..., None]) - (b0[None, :, :] + d2 * t[..., None])
    return np.linalg.norm(gap, axis=-1)
