"""Small adapters between the station's systems: each turns one system's output into what
another reads, with no state and no logic of its own.

- TcpPose: the world pose of the robot's tool frame, from the plant's body poses, for the
  workpieces the vacuum cup carries;
- HumanHands: the person's hand grasp frames (HandPoses), from HumanActor's status, for the
  workpieces the hands carry.
"""

import numpy as np
from pydrake.common.eigen_geometry import Quaternion
from pydrake.common.value import AbstractValue
from pydrake.math import RigidTransform
from pydrake.multibody.plant import MultibodyPlant
from pydrake.multibody.tree import Frame
from pydrake.systems.framework import Context, LeafSystem

from hrc_drake.human.messages import HumanStatus
from hrc_drake.ports import message_value
from hrc_drake.wiring import HUMAN, HUMAN_HANDS, TOOL_POSE, status_port
from hrc_drake.workpieces.messages import HandPoses


class TcpPose(LeafSystem):
    """The pose of one plant frame in the world, from the plant's `body_poses` output."""

    def __init__(self, plant: MultibodyPlant, frame: Frame):
        super().__init__()
        self._body_index = int(frame.body().index())
        self._X_BF = frame.GetFixedPoseInBodyFrame()
        model = plant.get_body_poses_output_port().Allocate()
        self.DeclareAbstractInputPort("body_poses", model)
        self.DeclareAbstractOutputPort(
            "tool_pose", lambda: AbstractValue.Make(RigidTransform()), self._calc
        )

    def _calc(self, context: Context, output: AbstractValue) -> None:
        X_WB = self.get_input_port().Eval(context)[self._body_index]
        output.set_value(X_WB @ self._X_BF)


def hand_poses(status: HumanStatus | None) -> HandPoses | None:
    """The person's grasp frames at the time of the status (HumanStatus gives them as
    (x, y, z, qw, qx, qy, qz)); None before the person's first update."""
    if status is None or not status.left_hand or not status.right_hand:
        return None
    left, right = _pose(status.left_hand), _pose(status.right_hand)
    return HandPoses(left, right, status.time, status.base_pose[2])


def _pose(values: tuple[float, ...]) -> RigidTransform:
    """The pose; its position as an array: pybind11 takes a list for a vector 5x slower."""
    x, y, z, qw, qx, qy, qz = values
    return RigidTransform(Quaternion(qw, qx, qy, qz), np.array([x, y, z]))


class HumanHands(LeafSystem):
    """The person's hand grasp frames (HandPoses) from HumanActor's `human_status`; an empty
    tuple before the person's first update (ports cannot carry None). The same HandPoses
    object while the status is the same one (the person updates at 60 Hz, this is read at
    100 Hz), so that Workpieces can tell a new pose of the person by its identity."""

    def __init__(self):
        super().__init__()
        self._status = self.DeclareAbstractInputPort(status_port(HUMAN), message_value())
        self._last = (None, ())
        """The status last turned into hands (kept, so its identity is never reused), and
        its hands."""
        self.DeclareAbstractOutputPort("human_hands", message_value, self._calc)

    def _calc(self, context: Context, output: AbstractValue) -> None:
        status = self._status.Eval(context)
        if status is not self._last[0]:
            self._last = (status, hand_poses(status) or ())
        output.set_value(self._last[1])


def add_tool_pose(builder, tool_frame: Frame):
    """Adds TcpPose of `tool_frame`, fed from the body poses of the frame's own plant;
    returns its `tool_pose` output."""
    plant = tool_frame.GetParentPlant()
    tcp = builder.AddNamedSystem(TOOL_POSE, TcpPose(plant, tool_frame))
    builder.Connect(plant.get_body_poses_output_port(), tcp.get_input_port())
    return tcp.get_output_port()


def add_human_hands(builder, human):
    """Adds HumanHands fed from `human`'s status; returns its `human_hands` output."""
    hands = builder.AddNamedSystem(HUMAN_HANDS, HumanHands())
    builder.Connect(human.GetOutputPort(status_port(HUMAN)), hands.get_input_port())
    return hands.get_output_port()
