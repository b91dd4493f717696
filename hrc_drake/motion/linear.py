"""Straight Cartesian tool motion (MoveLinear): inverse kinematics along the line.

The line is cut into short steps; each step's solution is seeded with the previous one, so
the joints move continuously (a jump means a singularity or a branch change: the move
fails). The joint path through these solutions is then checked against the line.
"""

import numpy as np
from pydrake.math import RigidTransform
from pydrake.trajectories import PiecewisePose

from hrc_drake.motion.errors import PlanningFailed
from hrc_drake.motion.timing import spline_path

STEP_LENGTH = 0.01
"""m of tool travel between inverse-kinematics solutions."""
STEP_ANGLE = np.radians(3.0)
MAX_JOINT_STEP = 0.2
"""rad: a larger joint change between neighbouring solutions means a singularity."""
CHECK_SPACING = 0.005
"""rad of joint-space arc length between the samples that check deviation and contact."""


def linear_waypoints(model, ik, q_start, pose, tolerance: float):
    """Joint waypoints whose spline keeps the tool within `tolerance` of the line."""
    start = model.tool_pose(q_start)
    steps = _step_count(start, pose)
    if steps == 0:
        return [q_start]
    line = PiecewisePose.MakeLinear([0.0, 1.0], [start, pose])
    waypoints = [q_start]
    for i in range(1, steps + 1):
        q = ik.solve_near(line.GetPose(i / steps), waypoints[-1])
        if q is None:
            raise PlanningFailed(f"linear move unreachable at {100 * i / steps:.0f}% of the line")
        if np.max(np.abs(q - waypoints[-1])) > MAX_JOINT_STEP:
            raise PlanningFailed("linear move passes a singularity")
        waypoints.append(q)
    _check_path(model, waypoints, start, pose, tolerance)
    return waypoints


def _step_count(start: RigidTransform, goal: RigidTransform) -> int:
    distance = np.linalg.norm(goal.translation() - start.translation())
    angle = start.rotation().InvertAndCompose(goal.rotation()).ToAngleAxis().angle()
    return int(np.ceil(max(distance / STEP_LENGTH, angle / STEP_ANGLE)))


def _check_path(model, waypoints, start, goal, tolerance) -> None:
    """Deviation from the line and contact with the cell, sampled along the spline."""
    path = spline_path(waypoints)
    length = path.end_time() - path.start_time()
    p0, p1 = start.translation(), goal.translation()
    for s in np.linspace(0.0, length, int(length / CHECK_SPACING) + 2):
        q = path.value(s).ravel()
        if _distance_to_segment(model.tool_pose(q).translation(), p0, p1) > tolerance:
            raise PlanningFailed("linear move cannot stay on the line (near a singularity)")
        if not model.apart(q) or not model.within_limits(q):
            raise PlanningFailed("linear move collides with the cell or leaves the joint limits")


def _distance_to_segment(p, a, b) -> float:
    ab = b - a
    length_squared = float(ab @ ab)
    t = 0.0 if length_squared == 0.0 else float(np.clip((p - a) @ ab / length_squared, 0, 1))
    return float(np.linalg.norm(p - (a + t * ab)))
