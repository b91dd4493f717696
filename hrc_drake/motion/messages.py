"""Robot command and status messages (abstract-valued ports of RobotMotion).

The robot's BehaviorTreeSystem holds its recent commands on its `robot_command` output;
RobotMotion (input `robot_tree_command`) acts on every command whose `seq` is newer than the
last one it saw. Every command's outcome uses the
shared vocabulary of `hrc_drake.messages` (running, succeeded, failed, rejected, cancelled).

Poses are `RigidTransform`s of the tool's `tcp` frame (the suction cup face, z out of the
cup) in the world frame.
"""

from dataclasses import dataclass

from pydrake.math import RigidTransform

from hrc_drake.messages import ResultLog

IDLE = "idle"
PLANNING = "planning"
MOVING = "moving"
STOPPING = "stopping"
STOPPED = "stopped"
MODES = (IDLE, PLANNING, MOVING, STOPPING, STOPPED)
"""RobotMotion's state: `stopped` is a paused move (speed scale 0); `idle` holds still."""


@dataclass(frozen=True)
class MoveTo:
    """Move the tool to `pose` along a collision-free joint-space path.

    With `free_tool_rotation`, only the tool axis (z) must match: the rotation about it is
    left to the planner, which picks the one nearest the robot's posture.
    """

    seq: int
    pose: RigidTransform
    free_tool_rotation: bool = False


@dataclass(frozen=True)
class MoveJoints:
    """Move to joint positions `q` (radians, A1..A6) or to a named configuration of the
    scenario (`home` or one of `robot.configurations_deg`)."""

    seq: int
    q: tuple[float, ...] | None = None
    configuration: str | None = None


@dataclass(frozen=True)
class MoveLinear:
    """Move the tool to `pose` along a straight Cartesian line (approach and retreat)."""

    seq: int
    pose: RigidTransform


@dataclass(frozen=True)
class Stop:
    """Cancel the running move: decelerate on its path and hold. Succeeds at rest."""

    seq: int


@dataclass(frozen=True)
class Grip:
    """Switch the vacuum on: attach the object whose grasp surface is at the suction cup.

    The workpieces system decides (within its vacuum tolerance, up to the robot's payload);
    the status's `held_object` is then that object's id."""

    seq: int


@dataclass(frozen=True)
class Release:
    """Switch the vacuum off: hand the held object back to the workpieces system."""

    seq: int


@dataclass(frozen=True)
class SetSpeed:
    """Speed override, a fraction in [0, 1] of the planned speed; applies to running moves."""

    seq: int
    fraction: float


RobotCommand = MoveTo | MoveJoints | MoveLinear | Stop | Grip | Release | SetSpeed
MOTION_COMMANDS = (MoveTo, MoveJoints, MoveLinear)


@dataclass(frozen=True)
class RobotStatus:
    """What RobotMotion reports, computed at its last update.

    `results` holds the outcomes of the most recent commands, so that a move's outcome stays
    visible after a later SetSpeed or a rejected command: a behavior tree node looks up its
    own command with `results.outcome_of(seq)`. `speed_fraction` is the SetSpeed override,
    `safety_scale` the safety monitor's scale, `speed_scale` the effective scale the path is
    traversed at (it follows their product with bounded acceleration).
    """

    mode: str
    results: ResultLog
    tool_pose: RigidTransform
    tool_speed: float
    speed_fraction: float
    safety_scale: float
    speed_scale: float
    held_object: int | None = None
