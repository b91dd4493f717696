"""A station's models are the same whichever way they are parsed: the bundled models read
from their text (hrc_drake.station, the fast way) give the plant Drake's own
ProcessModelDirectives gives from the files: the same model instances, bodies (masses,
inertias, poses), joints, frames, geometry (names, shapes, poses, every property of every
role) and the collision filters, for every bundled scenario's cell."""

import pytest
from pydrake.geometry import Role
from pydrake.multibody.parsing import ModelDirectives, ProcessModelDirectives
from pydrake.multibody.plant import AddMultibodyPlant, MultibodyPlantConfig
from pydrake.multibody.tree import BodyIndex, FrameIndex, JointIndex, ModelInstanceIndex
from pydrake.systems.framework import DiagramBuilder

import hrc_drake.iisy
from hrc_drake.scenario import bundled_scenarios, load_scenario
from hrc_drake.station import add_robot, add_station_models, model_parser

ROLES = (Role.kProximity, Role.kIllustration, Role.kPerception)


def drakes_own(plant, parser, spec) -> None:
    """The robot and the cell as Drake's parser reads their files (the cell by its directive
    processing)."""
    add_robot(plant, parser, spec)
    directives = ModelDirectives()
    directives.directives = list(spec.cell)
    ProcessModelDirectives(directives, plant, parser)


def fast(plant, parser, spec) -> None:
    add_station_models(plant, parser, spec)


def described(add, spec) -> list:
    """Everything the plant and its SceneGraph hold of the models, in their order."""
    builder = DiagramBuilder()
    plant, scene_graph = AddMultibodyPlant(MultibodyPlantConfig(time_step=0.001), builder)
    add(plant, model_parser(plant), spec)
    plant.Finalize()
    context = plant.CreateDefaultContext()
    items = [
        plant.GetModelInstanceName(ModelInstanceIndex(i))
        for i in range(plant.num_model_instances())
    ]
    for i in range(1, plant.num_bodies()):  # the world body's mass and inertia are NaN
        body = plant.get_body(BodyIndex(i))
        inertia = body.default_spatial_inertia().CopyToFullMatrix6().tolist()
        pose = plant.EvalBodyPoseInWorld(context, body).GetAsMatrix34().tolist()
        items.append((body.scoped_name().to_string(), body.default_mass(), inertia, pose))
    for i in range(plant.num_frames()):
        frame = plant.get_frame(FrameIndex(i))
        pose = frame.GetFixedPoseInBodyFrame().GetAsMatrix34().tolist()
        items.append((frame.scoped_name().to_string(), pose))
    for i in range(plant.num_joints()):
        joint = plant.get_joint(JointIndex(i))
        limits = (joint.position_lower_limits().tolist(), joint.position_upper_limits().tolist())
        items.append((joint.name(), joint.type_name(), limits))
    inspector = scene_graph.model_inspector()
    for geometry in inspector.GetAllGeometryIds():
        where = (inspector.GetName(geometry), inspector.GetName(inspector.GetFrameId(geometry)))
        shape = (
            repr(inspector.GetShape(geometry)),
            inspector.GetPoseInFrame(geometry).GetAsMatrix34().tolist(),
        )
        items.append(
            (
                *where,
                *shape,
                [_properties(inspector.GetProperties(geometry, role)) for role in ROLES],
            )
        )
    touching = [g for g in inspector.GetAllGeometryIds() if inspector.GetProximityProperties(g)]
    filtered = [
        (a, b) for a in touching for b in touching if a < b and inspector.CollisionFiltered(a, b)
    ]
    items.append([(inspector.GetName(a), inspector.GetName(b)) for a, b in filtered])
    return items


def _properties(properties) -> list | None:
    if properties is None:
        return None
    return sorted(
        (group, name, _value(properties.GetProperty(group, name)))
        for group in properties.GetGroupNames()
        for name in properties.GetPropertiesInGroup(group)
    )


def _value(value):
    if hasattr(value, "static_friction"):
        return value.static_friction(), value.dynamic_friction()
    return repr(value)


def from_file(parser, path, name=None):
    (instance,) = parser.AddModels(str(path))
    return instance


@pytest.mark.parametrize("name", bundled_scenarios())
def test_station_models_read_from_text_are_drakes_own(name, monkeypatch):
    spec = load_scenario(name).station
    read_fast = described(fast, spec)
    monkeypatch.setattr(hrc_drake.iisy, "add_bundled_model", from_file)
    assert read_fast == described(drakes_own, spec)
