"""HumanActor: the simulated person's state machine as a Drake LeafSystem.

Inputs `<issuer>_command` (abstract), one per command issuer (default one, `human_command`):
None, a command (hrc_drake.human.messages) or a tuple of recent commands; each issuer's new
commands are handled in order (the robot's tree may call the person while the person's own
tree directs them).
Outputs, both computed from state only: `human_positions` (the kinematic human plant's q,
for MultibodyPositionToGeometryPose) and `human_status` (HumanStatus). A periodic
unrestricted update (60 Hz by default, above Meshcat's frame rate) runs the protocol and
samples the pose; between updates the pose is held, so the diagram pays for the person only
at that rate.
"""

import numpy as np
from pydrake.common.value import AbstractValue
from pydrake.systems.framework import LeafSystem

from hrc_drake.human.body import HumanBody, human_body
from hrc_drake.human.clip import Clip, load_clips
from hrc_drake.human.messages import HumanStatus
from hrc_drake.human.motion import ActorState, Context, advance, pose_at, status
from hrc_drake.human.navigation import NavigationMap
from hrc_drake.ports import message_value, value_or_none

UPDATE_PERIOD = 1.0 / 60.0
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
        body: HumanBody | None = None,
        clips: dict[str, Clip] | None = None,
        start_pose: tuple[float, float, float] = (0.0, 0.0, 0.0),
        period: float = UPDATE_PERIOD,
        issuers: tuple[str, ...] = ("human",),
        navigation: NavigationMap | None = None,
    ):
        LeafSystem.__init__(self)
        self._ctx = Context(body or human_body(), clips or load_clips(), navigation)
        self.period = period
        self.stride_time = self._ctx.clips[WALK_CLIP].duration
        """One gait cycle of the walk clip (s)."""
        initial = ActorState(start_pose=tuple(float(v) for v in start_pose))
        self._commands = {
            issuer: self.DeclareAbstractInputPort(f"{issuer}_command", message_value())
            for issuer in issuers
        }
        self._actor = self.DeclareAbstractState(AbstractValue.Make(initial))
        self._status = self.DeclareAbstractState(
            AbstractValue.Make(HumanStatus(base_pose=initial.start_pose))  # before its first update
        )
        first_pose = self._ctx.body.plant_positions(pose_at(self._ctx, initial, 0.0))
        self._positions = self.DeclareDiscreteState(first_pose)
        plant = self._ctx.body.plant
        self._reported = tuple(plant.GetFrameByName(name) for name in REPORTED_FRAMES)
        self.DeclarePeriodicUnrestrictedUpdateEvent(period, 0.0, self._update)
        self.DeclareStateOutputPort("human_positions", self._positions)
        self.DeclareStateOutputPort("human_status", self._status)

    @property
    def body(self) -> HumanBody:
        return self._ctx.body

    @property
    def navigation(self) -> NavigationMap | None:
        return self._ctx.navigation

    def _frames(self, positions: np.ndarray) -> tuple[tuple[float, ...], ...]:
        """The hands' and head's poses at the plant's `positions`: one forward kinematics."""
        return tuple(map(_pose_tuple, self._ctx.body.world_poses(self._reported, positions)))

    def _update(self, context, state) -> None:
        t = context.get_time()
        commands = {issuer: value_or_none(port, context) for issuer, port in self._commands.items()}
        actor = advance(self._ctx, context.get_abstract_state(self._actor).get_value(), t, commands)
        state.get_mutable_abstract_state(self._actor).set_value(actor)
        positions = self._ctx.body.plant_positions(actor.pose)
        state.get_mutable_discrete_state(self._positions).set_value(positions)
        message = status(self._ctx, actor, t, self._frames(positions))
        state.get_mutable_abstract_state(self._status).set_value(message)
