"""The cell's fixed collision geometry, as the person's navigation and the workpieces'
support surfaces both read it."""

from collections.abc import Iterator

from pydrake.math import RigidTransform
from pydrake.multibody.tree import BodyIndex


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
