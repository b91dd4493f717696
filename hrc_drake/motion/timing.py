"""Time-parameterisation: a joint-space path timed by TOPP-RA within the robot's limits.

The geometric path is a piecewise cubic in the path length σ (joint-space arc length). Its
shape is either exact on the collision-checked polyline (zero velocity at each corner, so it
never leaves the checked segments) or a C² spline through the waypoints (faster, checked
again by the planner before use). TOPP-RA then finds the fastest timing within the joint
velocity and acceleration limits and the tool's collaborative speed limit.
"""

import numpy as np
from pydrake.multibody.optimization import CalcGridPointsOptions, Toppra
from pydrake.trajectories import (
    PathParameterizedTrajectory,
    PiecewisePolynomial,
    Trajectory,
)

VELOCITY_MARGIN = 0.95
"""TOPP-RA enforces the limits at grid points only; the margin covers the spans between."""
ACCELERATION_MARGIN = 0.85
"""Below execution's margin, so that a motion resumed after a stop can regain its speed
while the planned motion itself accelerates."""

GRID = CalcGridPointsOptions(max_err=1e-4, max_iter=100, max_seg_length=0.02, min_points=50)


class TimedPath:
    """q(τ) for τ in [0, duration]: a planned motion at nominal (full) speed."""

    def __init__(self, trajectory: Trajectory):
        self.trajectory = trajectory
        self.duration = trajectory.end_time() - trajectory.start_time()
        self._start = trajectory.start_time()

    def position(self, tau: float) -> np.ndarray:
        return self.trajectory.value(self._start + tau).ravel()

    def velocity(self, tau: float) -> np.ndarray:
        return self.trajectory.EvalDerivative(self._start + tau, 1).ravel()

    def acceleration(self, tau: float) -> np.ndarray:
        return self.trajectory.EvalDerivative(self._start + tau, 2).ravel()

    @property
    def end(self) -> np.ndarray:
        return self.position(self.duration)


def polyline_path(waypoints: list[np.ndarray]) -> PiecewisePolynomial:
    """Cubic segments that stay on the straight segments, at rest at every corner."""
    samples = np.column_stack(waypoints)
    return PiecewisePolynomial.CubicHermite(
        _arc_lengths(waypoints), samples, np.zeros_like(samples)
    )


def spline_path(waypoints: list[np.ndarray]) -> PiecewisePolynomial:
    """A C² cubic spline through the waypoints, at rest at both ends."""
    samples = np.column_stack(waypoints)
    zero = np.zeros(samples.shape[0])
    return PiecewisePolynomial.CubicWithContinuousSecondDerivatives(
        _arc_lengths(waypoints), samples, zero, zero
    )


def time_path(path: PiecewisePolynomial, model, tool_speed_limit: float) -> TimedPath | None:
    """The fastest timing of `path` within the limits of `model`; None if TOPP-RA fails."""
    toppra = Toppra(path, model.plant, Toppra.CalcGridPoints(path, GRID))
    velocity = VELOCITY_MARGIN * model.velocity_limits
    acceleration = ACCELERATION_MARGIN * model.acceleration_limits
    toppra.AddJointVelocityLimit(-velocity, velocity)
    toppra.AddJointAccelerationLimit(-acceleration, acceleration)
    toppra.AddFrameTranslationalSpeedLimit(model.tcp, VELOCITY_MARGIN * tool_speed_limit)
    timing = toppra.SolvePathParameterization()
    if timing is None:
        return None
    return TimedPath(PathParameterizedTrajectory(path, timing))


def _arc_lengths(waypoints: list[np.ndarray]) -> list[float]:
    steps = [np.linalg.norm(b - a) for a, b in zip(waypoints, waypoints[1:], strict=False)]
    return list(np.concatenate([[0.0], np.cumsum(steps)]))
