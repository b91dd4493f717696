"""Put the person into a Diagram: kinematic plant, HumanActor, geometry poses, collision filters."""

from dataclasses import replace

from pydrake.geometry import CollisionFilterDeclaration, GeometrySet
from pydrake.multibody.plant import MultibodyPlant
from pydrake.multibody.tree import BodyIndex
from pydrake.systems.rendering import MultibodyPositionToGeometryPose

from hrc_drake.human.anthropometry import DEFAULT_HEIGHT, DEFAULT_MASS
from hrc_drake.human.body import human_body, parse_human
from hrc_drake.human.clip import LENGTH_JOINTS, Clip, load_clips
from hrc_drake.human.navigation import NavigationMap
from hrc_drake.human.sdf import REGION_SEPARATOR
from hrc_drake.systems.human_actor import HumanActor


def scaled_clips(clips: dict[str, Clip], height: float) -> dict[str, Clip]:
    """The clips for a person of another height: every length scales with body height."""
    factor = height / DEFAULT_HEIGHT
    if factor == 1.0:
        return clips
    scaled = {}
    for name, clip in clips.items():
        frames = clip.frames.copy()
        for joint in LENGTH_JOINTS:
            frames[:, clip.joint_names.index(joint)] *= factor
        scaled[name] = replace(
            clip, frames=frames, animation_distance=clip.animation_distance * factor
        )
    return scaled


def _collision_geometries(plant: MultibodyPlant) -> list:
    return [
        geometry
        for i in range(plant.num_bodies())
        for geometry in plant.GetCollisionGeometriesForBody(plant.get_body(BodyIndex(i)))
    ]


def add_human(
    builder,
    scene_graph,
    height: float = DEFAULT_HEIGHT,
    mass: float = DEFAULT_MASS,
    name: str = "human",
    start_pose: tuple[float, float, float] = (0.0, 0.0, 0.0),
    dynamic_plant: MultibodyPlant | None = None,
    issuers: tuple[str, ...] = ("human",),
    navigation: NavigationMap | None = None,
    clips: dict[str, Clip] | None = None,
) -> tuple[HumanActor, MultibodyPlant]:
    """Add a person: returns the HumanActor and the person's kinematic plant.

    The plant (time_step 0) is registered with `scene_graph` but is not a system of the
    diagram: it is never stepped. Its geometry is collision-filtered against itself and
    against every collision geometry `dynamic_plant` has at this point (add the person after
    the dynamic plant's models). Connect each issuer's commands to the actor's
    `<issuer>_command` input (default: `human_command`). With a `navigation` map the person
    walks round the cell's geometry. `clips` default to the built-in ones.
    """
    plant = MultibodyPlant(0.0)
    plant.set_name(f"{name}_plant")  # names its geometry source in SceneGraph
    plant.RegisterAsSourceForSceneGraph(scene_graph)
    parse_human(plant, height, mass, name)
    plant.Finalize()
    body = human_body(height, mass)
    actor = builder.AddSystem(
        HumanActor(
            body,
            scaled_clips(clips or load_clips(), height),
            start_pose,
            issuers=issuers,
            navigation=navigation,
        )
    )
    actor.set_name(f"{name}_actor")
    to_pose = builder.AddSystem(MultibodyPositionToGeometryPose(plant))
    to_pose.set_name(f"{name}_geometry")
    builder.Connect(actor.GetOutputPort("human_positions"), to_pose.get_input_port())
    builder.Connect(
        to_pose.get_output_port(), scene_graph.get_source_pose_port(plant.get_source_id())
    )
    human = GeometrySet(_collision_geometries(plant))
    declaration = CollisionFilterDeclaration().ExcludeWithin(human)
    if dynamic_plant is not None:
        declaration.ExcludeBetween(human, GeometrySet(_collision_geometries(dynamic_plant)))
    scene_graph.collision_filter_manager().Apply(declaration)
    actor.human_plant = plant
    return actor, plant


def body_regions(human_plant: MultibodyPlant, scene_graph) -> dict:
    """ISO/TS 15066 body region of every collision geometry of the person, by GeometryId."""
    inspector = scene_graph.model_inspector()
    return {
        geometry: inspector.GetName(geometry).split("::")[-1].split(REGION_SEPARATOR)[0]
        for geometry in _collision_geometries(human_plant)
    }
