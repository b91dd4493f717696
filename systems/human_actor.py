"""HumanActor: the simulated person's state machine as a Drake LeafSystem.

Inputs `<issuer>_command` (abstract), one per command issuer (by default the trees that may
command the person, hrc_drake.wiring): None, a command (hrc_drake.human.messages) or a tuple
of recent commands; each issuer's new commands are handled in order (the robot's tree may
call the person while the person's own tree directs them).
Outputs, both computed from state only: `human_positions` (the kinematic human plant's q,
for MultibodyPositionToGeometryPose) and `human_status` (HumanStatus). A periodic
unrestricted update (60 Hz by default, above Meshcat's frame rate) runs the protocol
(hrc_drake.human.protocol, plain Python) and samples the pose; between updates the pose is
held, so the diagram pays for the person only at that rate.
"""

import numpy as np
from pydrake.common.value import AbstractValue
from pydrake.geometry import GeometrySet
from pydrake.multibody.plant import MultibodyPlant
from pydrake.systems.framework import LeafSystem
from pydrake.systems.rendering import MultibodyPositionToGeometryPose

from hrc_drake.human.anthropometry import DEFAULT_HEIGHT, DEFAULT_MASS
from hrc_drake.human.body import HumanBody, parse_human
from hrc_drake.human.clip import Clip, load_clips
from hrc_drake.human.messages import HumanStatus
from hrc_drake.human.navigation import NavigationMap
from hrc_drake.human.performer import Performer, sized_performer
from hrc_drake.human.protocol import UPDATE_PERIOD, ActorState, advance, pose_at, status
from hrc_drake.ports import message_value, value_or_none
from hrc_drake.scene_geometry import collision_geometries, filter_against
from hrc_drake.wiring import (
    HUMAN,
    HUMAN_ACTOR,
    HUMAN_GEOMETRY,
    HUMAN_MODEL,
    command_input,
    issuers_of,
)

WALK_CLIP = "walk"
REPORTED_FRAMES = ("left_hand_grasp", "right_hand_grasp", "head_gaze")
"""The frames whose world poses the status reports (hands, then head)."""


def _pose_tuple(X) -> tuple[float, ...]:
    """(x, y, z, qw, qx, qy, qz) of a RigidTransform, in as few calls into Drake as it takes."""
    return (*X.translation().tolist(), *X.rotation().ToQuaternion().wxyz().tolist())


class HumanActor(LeafSystem):
    """Plays clips, walks and aims the person according to the commands it receives."""

    def __init__(
        self,
        performer: Performer,
        start_pose: tuple[float, float, float] = (0.0, 0.0, 0.0),
        period: float = UPDATE_PERIOD,
        issuers: tuple[str, ...] = issuers_of(HUMAN),
    ):
        LeafSystem.__init__(self)
        self._performer = performer
        self.period = period
        self.stride_time = self._performer.clips[WALK_CLIP].duration
        """One gait cycle of the walk clip (s)."""
        initial = ActorState(start_pose=tuple(float(v) for v in start_pose))
        self._commands = {
            issuer: self.DeclareAbstractInputPort(command_input(issuer), message_value())
            for issuer in issuers
        }
        self._actor = self.DeclareAbstractState(AbstractValue.Make(initial))
        self._status = self.DeclareAbstractState(
            AbstractValue.Make(HumanStatus(base_pose=initial.start_pose))  # before its first update
        )
        first_pose = self._performer.body.plant_positions(pose_at(self._performer, initial, 0.0))
        self._positions = self.DeclareDiscreteState(first_pose)
        plant = self._performer.body.plant
        self._reported = tuple(plant.GetFrameByName(name) for name in REPORTED_FRAMES)
        self.DeclarePeriodicUnrestrictedUpdateEvent(period, 0.0, self._update)
        self.DeclareStateOutputPort("human_positions", self._positions)
        self.DeclareStateOutputPort("human_status", self._status)

    @property
    def body(self) -> HumanBody:
        return self._performer.body

    @property
    def navigation(self) -> NavigationMap | None:
        return self._performer.navigation

    def _frames(self, positions: np.ndarray) -> tuple[tuple[float, ...], ...]:
        """The hands' and head's poses at the plant's `positions`: one forward kinematics."""
        return tuple(map(_pose_tuple, self._performer.body.world_poses(self._reported, positions)))

    def _update(self, context, state) -> None:
        t = context.get_time()
        commands = {issuer: value_or_none(port, context) for issuer, port in self._commands.items()}
        previous = context.get_abstract_state(self._actor).get_value()
        actor = advance(self._performer, previous, t, commands)
        state.get_mutable_abstract_state(self._actor).set_value(actor)
        positions = self._performer.body.plant_positions(actor.pose)
        state.get_mutable_discrete_state(self._positions).set_value(positions)
        message = status(self._performer, actor, t, self._frames(positions))
        state.get_mutable_abstract_state(self._status).set_value(message)


def add_human(
    builder,
    scene_graph,
    height: float = DEFAULT_HEIGHT,
    mass: float = DEFAULT_MASS,
    start_pose: tuple[float, float, float] = (0.0, 0.0, 0.0),
    issuers: tuple[str, ...] = issuers_of(HUMAN),
    navigation: NavigationMap | None = None,
    clips: dict[str, Clip] | None = None,
    period: float = UPDATE_PERIOD,
) -> tuple[HumanActor, MultibodyPlant]:
    """Adds a person as HUMAN_ACTOR: returns the actor and the person's kinematic plant.

    The plant (time_step 0) is registered with `scene_graph` but is not a system of the
    diagram: it is never stepped; HUMAN_GEOMETRY poses its geometry from the actor's joint
    positions. Its geometry is collision-filtered within itself (the plant has no contact
    to compute). Connect each issuer's commands to the actor's `<issuer>_command` input.
    With a `navigation` map the person walks round the cell's geometry. `clips` default to
    the built-in ones, scaled to the person's height.
    """
    plant = MultibodyPlant(0.0)
    plant.set_name(f"{HUMAN_MODEL}_plant")  # names its geometry source in SceneGraph
    plant.RegisterAsSourceForSceneGraph(scene_graph)
    parse_human(plant, height, mass, HUMAN_MODEL)
    plant.Finalize()
    actor = builder.AddNamedSystem(
        HUMAN_ACTOR,
        HumanActor(
            sized_performer(height, mass, clips or load_clips(), navigation),
            start_pose,
            period,
            issuers=issuers,
        ),
    )
    to_pose = builder.AddNamedSystem(HUMAN_GEOMETRY, MultibodyPositionToGeometryPose(plant))
    builder.Connect(actor.GetOutputPort("human_positions"), to_pose.get_input_port())
    builder.Connect(
        to_pose.get_output_port(), scene_graph.get_source_pose_port(plant.get_source_id())
    )
    filter_against(scene_graph, GeometrySet(collision_geometries(plant)), GeometrySet())
    return actor, plant
