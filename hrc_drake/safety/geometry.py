"""Which geometries the monitor watches, and a cheap broad phase for their distances.

Every watched geometry is wrapped in a bounding capsule (a segment plus a radius) in its
SceneGraph frame. Segment-to-segment distances (`kernels.segment_distances`) minus the
radii are lower bounds of the true signed distances (exact for capsule pairs), so the
monitor asks SceneGraph for exact distances only for the few pairs that can still be the
closest or touching.
"""

from dataclasses import dataclass

import numpy as np
from pydrake.geometry import Box, Capsule, Cylinder, Ellipsoid, GeometryId, Sphere

from hrc_drake.human.sdf import REGION_SEPARATOR
from hrc_drake.human.skeleton import REGIONS


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
