"""Robot nodes: RobotMove and SetRobotVelocity (the thesis system's, docs/thesis-system.md), and the
moves, grip and stop the scenarios need. Asynchronous nodes send their command when they start, stay
RUNNING until RobotMotion reports *their* sequence number finished, and send Stop when they are
halted."""

import math

from pydrake.math import RigidTransform, RotationMatrix

from hrc_drake.bt import InputPort, Range, Status, SyncActionNode
from hrc_drake.motion import messages as robot
from hrc_drake.nodes.command import CommandNode
from hrc_drake.tree_types import Pose
from hrc_drake.wiring import ROBOT

TOOL_DOWN = RotationMatrix.MakeXRotation(math.pi)
"""Orientation of a target given without one: the tool axis pointing at the floor."""


class RobotCommandNode(CommandNode):
    """A command to RobotMotion; halting a move stops the robot on its path."""

    actor = ROBOT
    commands = (ROBOT,)
    cancel_command = robot.Stop

    def tool_target(self, port: str) -> tuple[RigidTransform, bool]:
        """The target pose, and whether the rotation about the tool axis is free."""
        return tool_pose(self.agent.resolve_pose(self.get_input(port)))


def tool_pose(pose: Pose) -> tuple[RigidTransform, bool]:
    """The tool's target for a (resolved) pose, and whether the rotation about the tool axis
    is left free: a pose without orientation points the tool down."""
    if pose.quaternion is not None:
        return pose.to_transform(), False
    return RigidTransform(TOOL_DOWN, pose.position), True


class RobotMove(RobotCommandNode):
    """Moves the tool to `target` on a collision-free path, the part it holds kept as clear
    of the cell as the tool (lift a part off what it rests on with RobotMoveLinear first);
    SUCCESS when the whole motion is done (speed changes on the way do not fail it)."""

    ports = (InputPort("target", Pose, description="tool pose, x;y;z[;qw;qx;qy;qz] or name"),)

    def command(self, seq: int):
        pose, free = self.tool_target("target")
        return robot.MoveTo(seq, pose, free_tool_rotation=free)


class RobotMoveLinear(RobotCommandNode):
    """Moves the tool along a straight line to `target` (approach and retreat, a held part
    taken off or set down on what it rests on); a target without orientation keeps the
    tool's present orientation."""

    ports = (InputPort("target", Pose, description="tool pose, x;y;z[;qw;qx;qy;qz] or name"),)

    def command(self, seq: int):
        pose: Pose = self.agent.resolve_pose(self.get_input("target"))
        status = self.agent.robot
        if pose.quaternion is not None or status is None:
            return robot.MoveLinear(seq, self.tool_target("target")[0])
        return robot.MoveLinear(seq, RigidTransform(status.tool_pose.rotation(), pose.position))


class RobotMoveJoints(RobotCommandNode):
    """Moves to a named joint configuration of the scenario (home, ready, ...)."""

    ports = (InputPort("configuration", str, description="configuration name"),)

    def command(self, seq: int):
        return robot.MoveJoints(seq, configuration=self.get_input("configuration"))


class RobotGrip(RobotCommandNode):
    """Switches the vacuum on: FAILURE when no object is at the cup or it is too heavy."""

    cancel_command = None

    def command(self, seq: int):
        return robot.Grip(seq)


class RobotRelease(RobotCommandNode):
    """Switches the vacuum off: the held object drops onto what is below it."""

    cancel_command = None

    def command(self, seq: int):
        return robot.Release(seq)


class RobotStop(RobotCommandNode):
    """Stops the running motion on its path; SUCCESS once the robot is at rest."""

    cancel_command = None

    def command(self, seq: int):
        return robot.Stop(seq)


class SetRobotVelocity(SyncActionNode):
    """Sets the robot's speed as a fraction of its planned speed; a running move slows or
    speeds up on the same path without failing. Always SUCCESS."""

    ports = (
        InputPort(
            "velocity", float, description="fraction of full speed, 0..1", accepts=Range(0, 1)
        ),
    )
    commands = (ROBOT,)

    def tick(self) -> Status:
        fraction = self.get_input("velocity")
        self.agent.send(ROBOT, lambda seq: robot.SetSpeed(seq, fraction))
        return Status.SUCCESS


NODES = (
    RobotMove,
    RobotMoveLinear,
    RobotMoveJoints,
    RobotGrip,
    RobotRelease,
    RobotStop,
    SetRobotVelocity,
)
