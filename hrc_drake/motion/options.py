"""Tunable settings of robot motion: the `robot.motion` part of a scenario."""

from dataclasses import dataclass


@dataclass
class MotionOptions:
    """How RobotMotion plans and executes; the defaults suit every iisy variant.

    period: seconds between RobotMotion updates (commands, planning, speed changes).
    ik_attempts: inverse-kinematics starts one MoveTo may try (the current posture, home,
        then random postures) before its target counts as unreachable.
    search_nodes: nodes the collision-free path search may grow (both trees together)
        before a move fails; with `ik_attempts` the planning budget, counted and never timed,
        so plans do not depend on how busy the machine is.
    clearance: minimum distance (m) to the static cell kept by free-space moves.
    linear_tolerance: largest distance (m) of the tool from the line in MoveLinear.
    tool_speed_limit: collaborative Cartesian speed limit (m/s) of the tool centre point.
    settle_tolerance: joint error (rad) below which a finished move counts as arrived.
    settle_timeout: seconds a finished move may take to arrive before it fails.
    gripper_timeout: seconds to wait for the workpieces system to answer Grip/Release.
    avoid_person: plan around the person where they stand when the move is planned (a
        vertical capsule of `person_radius` around them), the "environment perception" the
        thesis system wanted (docs/thesis-system.md); off, the planner sees the static cell
        only.
    """

    period: float = 0.01
    ik_attempts: int = 16
    search_nodes: int = 2500
    clearance: float = 0.01
    linear_tolerance: float = 0.005
    tool_speed_limit: float = 1.0
    settle_tolerance: float = 1e-3
    settle_timeout: float = 2.0
    gripper_timeout: float = 0.5
    avoid_person: bool = False
    person_radius: float = 0.35
