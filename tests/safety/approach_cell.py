"""Helpers for safety test cells: a person (kinematic human model) walking straight at the
robot, waiting and walking away, and models posed kinematically in a SceneGraph by
MultibodyPositionToGeometryPose."""

import math

import numpy as np
from pydrake.geometry import CollisionFilterDeclaration, GeometrySet
from pydrake.multibody.plant import MultibodyPlant
from pydrake.systems.rendering import MultibodyPositionToGeometryPose
from pydrake.trajectories import PiecewisePolynomial

from hrc_drake.human.body import human_body


def walk(
    stand: float,
    arrive: float,
    leave: float,
    bearing: float,
    speed=1.0,
    start: float = 3.0,
    away: float = 4.0,
):
    """Person positions: walk straight at the robot's base from `start` metres away along
    the `bearing` (rad from +x) to `stand` metres away, wait, walk back out to `away`."""
    body = human_body()
    q = body.standing_pose()
    q[body.index("base_yaw")] = bearing + math.pi  # face the robot's base
    travel = (start - stand) / speed
    back = (away - stand) / speed
    times = [0.0, arrive - travel, arrive, leave, leave + back, leave + back + 1.0]
    radii = [start, start, stand, stand, away, away]
    columns = []
    for radius in radii:
        q[body.index("base_x")] = radius * math.cos(bearing)
        q[body.index("base_y")] = radius * math.sin(bearing)
        columns.append(body.plant_positions(q))
    return PiecewisePolynomial.FirstOrderHold(times, np.array(columns).T)


def keep_person_out_of_contact(scene_graph) -> None:
    """A dynamic plant sharing the SceneGraph must not see the kinematic person's geometry
    in contact (the monitor's pair queries ignore this filter)."""
    inspector = scene_graph.model_inspector()
    person = GeometrySet(
        [g for g in inspector.GetAllGeometryIds() if inspector.GetName(g).startswith("human::")]
    )
    everything = GeometrySet(inspector.GetAllGeometryIds())
    scene_graph.collision_filter_manager().Apply(
        CollisionFilterDeclaration().ExcludeBetween(person, everything)
    )


def kinematic(builder, scene_graph, add_models):
    """A never-stepped plant whose geometry is posed from a position input."""
    plant = MultibodyPlant(0.0)
    plant.RegisterAsSourceForSceneGraph(scene_graph)
    instance = add_models(plant)
    plant.Finalize()
    to_pose = builder.AddSystem(MultibodyPositionToGeometryPose(plant))
    builder.Connect(
        to_pose.get_output_port(), scene_graph.get_source_pose_port(plant.get_source_id())
    )
    return plant, instance, to_pose
