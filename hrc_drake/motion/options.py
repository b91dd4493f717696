"""Tunable settings of robot motion: the `robot.motion` part of a scenario."""

from dataclasses import dataclass


@dataclass
class MotionOptions:
    """How RobotMotion plans and executes; the defaults suit every iisy variant.

    update_period: seconds between RobotMotion updates (commands, planning, speed changes).
    planning_time_budget: wall-clock seconds one plan may take before it fails.
    clearance: minimum distance (m) to the static cell kept by free-space moves.
    linear_tolerance: largest distance (m) of the tool from the line in MoveLinear.
    tool_speed_limit: collaborative Cartesian speed limit (m/s) of the tool centre point.
    settle_tolerance: joint error (rad) below which a finished move counts as arrived.
    settle_timeout: seconds a finished move may take to arrive before it fails.
    gripper_timeout: seconds to wait for the workpieces system to answer Grip/Release.
    seed: seed of the planner's random sampling (the plan is deterministic).
    avoid_person: plan around the person where they stand when the move is planned (a
        vertical capsule of `person_radius` around them), the "environment perception"
        the original system wanted; off, the planner sees the static cell only.
    """

    update_period: float = 0.01
    planning_time_budget: float = 2.0
    clearance: float = 0.01
    linear_tolerance: float = 0.005
    tool_speed_limit: float = 1.0
    settle_tolerance: float = 1e-3
    settle_timeout: float = 2.0
    gripper_timeout: float = 0.5
    seed: int = 0
    avoid_person: bool = False
    person_radius: float = 0.35
