"""The scene's geometry as the station's parts read and share it: the cell's fixed collision
shapes (for the person's navigation and the workpieces' support surfaces), and collision
filters for geometry that is not the dynamic plant's (the person, the workpieces), whose
distances come from pair queries instead."""

from collections.abc import Iterator

from pydrake.geometry import CollisionFilterDeclaration, GeometrySet, Role, SceneGraph
from pydrake.math import RigidTransform
from pydrake.multibody.tree import BodyIndex

OBJECT_DEPTH_LIMIT = 0.01
"""m: the deepest an object may go into the cell's fixed geometry: the realism audit's limit
for a held object (docs/realism.md), and validate's for what the robot puts down."""


def anchored_collision_shapes(plant, inspector) -> Iterator[tuple[str, object, RigidTransform]]:
    """(model instance name, shape, X_WG) of every collision geometry on an anchored body of a
    finalized plant, posed in its default context."""
    context = plant.CreateDefaultContext()
    for index in range(plant.num_bodies()):
        body = plant.get_body(BodyIndex(index))
        if not plant.IsAnchored(body):
            continue
        name = plant.GetModelInstanceName(body.model_instance())
        X_WB = plant.EvalBodyPoseInWorld(context, body)
        for geometry in plant.GetCollisionGeometriesForBody(body):
            yield name, inspector.GetShape(geometry), X_WB @ inspector.GetPoseInFrame(geometry)


def static_geometry(plant, inspector) -> dict:
    """Every collision geometry of the plant's anchored bodies, named after its model."""
    found = {}
    for body_index in range(plant.num_bodies()):
        body = plant.get_body(BodyIndex(body_index))
        if plant.IsAnchored(body):
            for geometry in plant.GetCollisionGeometriesForBody(body):
                found[geometry] = plant.GetModelInstanceName(body.model_instance())
    return found


def collision_geometries(plant) -> list:
    """Every collision geometry of every body of `plant`."""
    return [
        geometry
        for i in range(plant.num_bodies())
        for geometry in plant.GetCollisionGeometriesForBody(plant.get_body(BodyIndex(i)))
    ]


def filter_against(scene_graph: SceneGraph, geometry: GeometrySet, others: GeometrySet) -> None:
    """No contact between `geometry` and `others` nor within `geometry` (distances between
    them are still available through QueryObject's pair queries)."""
    scene_graph.collision_filter_manager().Apply(
        CollisionFilterDeclaration().ExcludeWithin(geometry).ExcludeBetween(geometry, others)
    )


def other_proximity_geometry(scene_graph: SceneGraph, source_id) -> GeometrySet:
    """Every proximity geometry registered so far by sources other than `source_id`."""
    inspector = scene_graph.model_inspector()
    return GeometrySet(
        [
            g
            for g in inspector.GetAllGeometryIds(Role.kProximity)
            if not inspector.BelongsToSource(g, source_id)
        ]
    )
