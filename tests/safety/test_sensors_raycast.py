"""The sensors' ray cast (hrc_drake.safety.sensors_raycast) against Drake's own geometry: a
beam's end lies on the surface of the shape it met (QueryObject.ComputeSignedDistanceToPoint
is 0 there), and every point of the beam before its end, and of a beam that met nothing, is
outside every shape (distance > 0). Every kind of shape the scenes are made of, posed at
random, with beams from outside and from inside them."""

from dataclasses import dataclass

import numpy as np
import pytest
from pydrake.geometry import (
    Box,
    Capsule,
    Cylinder,
    Ellipsoid,
    GeometryInstance,
    ProximityProperties,
    SceneGraph,
    Sphere,
)
from pydrake.math import RigidTransform, RollPitchYaw

from hrc_drake.safety.sensors_raycast import KINDS, MISS, Solids, cast, solids

SHAPES = {
    "box": Box(0.3, 0.2, 0.5),
    "sphere": Sphere(0.15),
    "ellipsoid": Ellipsoid(0.1, 0.25, 0.15),
    "cylinder": Cylinder(0.12, 0.4),
    "capsule": Capsule(0.08, 0.35),
}
LENGTH = 3.0
SURFACE = 1e-6
"""m: how far from the surface Drake may find a beam's end"""
SAMPLES = 200
"""points checked along each beam"""


@dataclass
class Posed:
    """The shapes' geometries in the scene, as rays meet them, and their world poses."""

    geometries: list
    shapes: Solids
    poses: np.ndarray

    def kind(self, k: int) -> type:
        return KINDS[self.shapes.kinds[k]]


def scene(shapes: list, seed: int):
    """The shapes at random poses in a 1 m cube about the origin: their QueryObject, and
    the shapes as posed."""
    rng = np.random.default_rng(seed)
    scene_graph = SceneGraph()
    source = scene_graph.RegisterSource("shapes")
    geometries, poses = [], []
    for k, shape in enumerate(shapes):
        pose = RigidTransform(
            RollPitchYaw(rng.uniform(-np.pi, np.pi, 3)), rng.uniform(-0.5, 0.5, 3)
        )
        instance = GeometryInstance(pose, shape, f"shape_{k}")
        instance.set_proximity_properties(ProximityProperties())
        geometries.append(scene_graph.RegisterAnchoredGeometry(source, instance))
        poses.append(pose.GetAsMatrix34())
    context = scene_graph.CreateDefaultContext()
    query = scene_graph.get_query_output_port().Eval(context)
    _KEEP.append((scene_graph, context))  # the QueryObject reads them
    return query, Posed(geometries, solids(shapes), np.array(poses))


_KEEP = []


def rays(seed: int, count: int, poses=None):
    """Beams from 1.5 m away aimed within 0.2 m of the shapes' centres (`poses`), or from
    points inside the cube."""
    rng = np.random.default_rng(seed + 1000)
    directions = rng.normal(size=(count, 3))
    directions /= np.linalg.norm(directions, axis=1, keepdims=True)
    if poses is None:
        return rng.uniform(-0.5, 0.5, (count, 3)), directions
    centres = np.array([pose[:, 3] for pose in poses])
    targets = centres[rng.integers(len(centres), size=count)] + rng.uniform(-0.2, 0.2, (count, 3))
    return targets - 1.5 * directions, directions


def distances(query, point) -> dict:
    return {r.id_G: r.distance for r in query.ComputeSignedDistanceToPoint(point, 10.0)}


def off_surface(posed: Posed, k: int, point, query) -> float:
    """How far `point` lies from shape k's surface (outside positive), by Drake; for an
    ellipsoid (whose point distance Drake finds by iterating, tens of µm off) how far
    (p / radii)² sums from 1, times the least radius."""
    if posed.kind(k) is not Ellipsoid:
        return distances(query, point)[posed.geometries[k]]
    pose, radii = posed.poses[k], posed.shapes.sizes[k]
    p_G = (point - pose[:, 3]) @ pose[:, :3]
    return (np.sum((p_G / radii) ** 2) - 1.0) * radii.min()


def check_beams(query, posed: Posed, origins, directions, ranges, which) -> list[str]:
    wrong = []
    for k, (origin, direction, t, hit) in enumerate(
        zip(origins, directions, ranges, which, strict=True)
    ):
        end = min(t, LENGTH)
        before = origin + np.linspace(0.0, end, SAMPLES, endpoint=False)[1:, None] * direction
        for point in before:
            nearest = min(distances(query, point).values())
            if nearest <= 0.0:
                wrong.append(f"beam {k} passes through a shape at {point.round(3)}")
                break
        if hit >= 0:
            on = off_surface(posed, hit, origin + t * direction, query)
            if abs(on) > SURFACE and t > 0.0:
                kind = posed.kind(hit).__name__
                wrong.append(f"beam {k} ends {on:.2e} m from the {kind} it met")
            if t == 0.0 and on > SURFACE:
                wrong.append(f"beam {k} is blocked at its start outside the shape")
    return wrong


@pytest.mark.parametrize("kind", SHAPES)
def test_beams_end_on_the_surface_they_meet(kind):
    query, posed = scene([SHAPES[kind]] * 3, seed=len(kind))
    origins, directions = rays(seed=len(kind), count=60, poses=posed.poses)
    ranges, which = cast(origins, directions, LENGTH, posed.shapes, posed.poses)
    assert (which >= 0).sum() > 20, "too few beams met a shape to tell"
    assert np.all((which >= 0) == np.isfinite(ranges))
    assert not check_beams(query, posed, origins, directions, ranges, which)


def test_beams_meet_the_nearest_of_many_shapes():
    query, posed = scene(list(SHAPES.values()) * 2, seed=7)
    origins, directions = rays(seed=7, count=80, poses=posed.poses)
    ranges, which = cast(origins, directions, LENGTH, posed.shapes, posed.poses)
    assert len(set(which[which >= 0])) >= 5
    assert not check_beams(query, posed, origins, directions, ranges, which)


def test_a_beam_from_inside_a_shape_ends_where_it_starts():
    query, posed = scene(list(SHAPES.values()), seed=11)
    origins, directions = rays(seed=11, count=200)
    ranges, which = cast(origins, directions, LENGTH, posed.shapes, posed.poses)
    inside = [
        k for k, origin in enumerate(origins) if min(distances(query, origin).values()) < -SURFACE
    ]
    assert inside, "no beam started inside a shape"
    assert np.all(ranges[inside] == 0.0)
    outside = [k for k in range(len(origins)) if k not in inside]
    assert np.all(ranges[outside] > 0.0)


def test_beams_end_at_their_length():
    query, posed = scene([SHAPES["box"]], seed=3)
    origins, directions = rays(seed=3, count=40, poses=posed.poses)
    ranges, which = cast(origins, directions, 0.5, posed.shapes, posed.poses)
    assert np.all(np.where(which >= 0, ranges <= 0.5, ranges == MISS))


@pytest.mark.parametrize("first_deg", [-135.0, 100.0])
def test_a_scanners_fan_meets_what_each_of_its_rays_meets(first_deg):
    """A scanner's beams, from one point in a horizontal plane and found by their yaws
    (over ±180° too), end where the same rays cast one by one end."""
    query, posed = scene(list(SHAPES.values()) * 3, seed=5)
    yaws = np.radians(first_deg + 0.5 * np.arange(541))
    directions = np.column_stack([np.cos(yaws), np.sin(yaws), np.zeros_like(yaws)])
    met = 0
    for origin in ([0.0, 0.0, 0.0], [1.2, -0.3, 0.1], [0.05, 0.1, -0.2]):
        origins = np.tile(origin, (len(yaws), 1))
        fan = cast(origins, directions, LENGTH, posed.shapes, posed.poses, yaws)
        each = cast(origins, directions, LENGTH, posed.shapes, posed.poses)
        np.testing.assert_array_equal(fan[0], each[0])
        np.testing.assert_array_equal(fan[1], each[1])
        met += (fan[1] >= 0).sum()
    assert met > 100, "too few beams met a shape to tell"


def test_a_shape_across_the_fans_first_beam_is_met_by_it():
    """A sphere 1 m out just before the fan's first yaw (it stretches past it)."""
    shapes = solids([Sphere(0.15)])
    yaws = np.radians(100.0 + 0.5 * np.arange(541))
    seam = yaws[0] - np.radians(1.0)
    pose = np.hstack([np.eye(3), [[np.cos(seam)], [np.sin(seam)], [0.0]]])[None]
    directions = np.column_stack([np.cos(yaws), np.sin(yaws), np.zeros_like(yaws)])
    origins = np.zeros((len(yaws), 3))
    fan = cast(origins, directions, LENGTH, shapes, pose, yaws)
    each = cast(origins, directions, LENGTH, shapes, pose)
    assert (each[1] >= 0).sum() > 5
    np.testing.assert_array_equal(fan[0], each[0])
