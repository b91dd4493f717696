"""Speed-scaled execution of a timed path: the path parameter and its rate.

A planned motion is a timed path q(τ) that respects the joint limits at nominal speed
(τ is the planned time). Execution advances τ at a rate r = dτ/dt, the effective speed
scale, so the robot always stays on the planned path whatever the scale does:

    q̇ = q'(τ) r,    q̈ = q''(τ) r² + q'(τ) ṙ.

With 0 ≤ r ≤ 1 the velocities are at most the limits × r, and the first acceleration term at
most the limits × r². At every update RobotMotion picks ṙ, held until the next update, to
bring r to the commanded scale within one period where it can, and otherwise as fast as the
joint acceleration limits allow (the second term uses what the first leaves over): scaled
by the target when speeding up, in full when braking (see `next_progress`).
"""

from dataclasses import dataclass

import numpy as np

ACCELERATION_MARGIN = 0.95
"""Share of the joint acceleration limits that a speed change may use: the rest absorbs the
change of q'(τ) and q''(τ) within one update period."""
AT_REST_RATE = 1e-9
"""Path rates below this count as standing still (the rate never goes negative)."""


@dataclass(frozen=True)
class Progress:
    """Where execution is on the path: τ, r and ṙ as set by the update at time `since`."""

    tau: float
    rate: float
    rate_change: float
    since: float

    def at(self, t: float, duration: float) -> "Progress":
        """Extrapolated to time t (ṙ constant, r never below 0, τ never past the end)."""
        dt = max(0.0, t - self.since)
        if self.rate_change < 0.0:
            dt_rest = self.rate / -self.rate_change
            if dt_rest < dt:
                return self._moved(dt_rest, duration, t, rate_change=0.0)
        return self._moved(dt, duration, t, rate_change=self.rate_change)

    def _moved(self, dt: float, duration: float, t: float, rate_change: float) -> "Progress":
        tau = self.tau + self.rate * dt + 0.5 * self.rate_change * dt * dt
        rate = max(0.0, self.rate + self.rate_change * dt)
        return Progress(min(tau, duration), rate, rate_change, t)

    @property
    def at_rest(self) -> bool:
        return self.rate < AT_REST_RATE

    def finished(self, duration: float) -> bool:
        return self.tau >= duration


def desired_motion(path, progress: Progress) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Desired q, q̇ and q̈ on `path` at `progress` (zero velocity once at the end)."""
    q = path.position(progress.tau)
    if progress.finished(path.duration):
        return q, np.zeros_like(q), np.zeros_like(q)
    dq = path.velocity(progress.tau)
    ddq = path.acceleration(progress.tau)
    r, dr = progress.rate, progress.rate_change
    return q, dq * r, ddq * r * r + dq * dr


def next_progress(
    path, progress: Progress, target: float, period: float, acceleration_limits: np.ndarray
) -> Progress:
    """`progress` with ṙ for the next period: reaches `target` in one period if it can.

    Speeding up, the acceleration limits are scaled by the target, so a slow motion also
    speeds up gently. Slowing down (a SetSpeed, a protective slow-down or stop) brakes the
    way a robot controller's category 2 stop does: on the path, with the full acceleration
    limits. The stop from rate r then takes r times the stop from full speed and travels
    r² times as far: the stopping data (`hrc_drake.modelgen.stopping`) and S_p rest on that.
    The feasible range of ṙ is the intersection, over the joints and over τ now and one
    period ahead, and over r now and target (the extremes of r in the period), of
    |q''(τ) r² + q'(τ) ṙ| ≤ limit.
    """
    speeding_up = target >= progress.rate
    limit_scale = target if speeding_up else 1.0
    wanted = (target - progress.rate) / period
    limits = ACCELERATION_MARGIN * limit_scale * acceleration_limits
    ahead = min(path.duration, progress.tau + max(progress.rate, target) * period)
    dq = np.array((path.velocity(progress.tau), path.velocity(ahead)))
    ddq = np.array((path.acceleration(progress.tau), path.acceleration(ahead)))
    moving = np.abs(dq) > 1e-9  # the joints' bounds where they move, over both rates
    dq, ddq, limits = dq[moving], ddq[moving], np.broadcast_to(limits, moving.shape)[moving]
    rates = np.array(sorted((progress.rate, target)))[:, None]
    curvature_term = ddq * rates * rates
    bound_a = (-limits - curvature_term) / dq
    bound_b = (limits - curvature_term) / dq
    low = np.max(np.minimum(bound_a, bound_b), initial=-np.inf)
    high = np.min(np.maximum(bound_a, bound_b), initial=np.inf)
    chosen = min(max(wanted, low), high) if low <= high else 0.5 * (low + high)
    change = min(chosen, wanted) if speeding_up else max(chosen, wanted)
    return Progress(progress.tau, progress.rate, change, progress.since)


SEGMENT_COEFFICIENTS = 6
"""A desired-motion segment is a quintic per joint: its value, speed and acceleration match
the desired motion at both ends of the segment."""


def hermite_segment(start: np.ndarray, end: np.ndarray, duration: float) -> np.ndarray:
    """The quintic (joints × 6 coefficients in powers of the time since the segment's start)
    that leaves `start` and reaches `end` after `duration`, each (q, q̇, q̈) stacked.

    RobotMotion chooses ṙ at each update and holds it until the next, so the desired motion
    over one period is known at the update: this segment carries it to the plant steps
    until the next update (`step_samples`; exact at the updates, where ṙ changes; between
    them within the error of a quintic over one period)."""
    q0, v0, a0 = np.reshape(start, (3, -1))
    q1, v1, a1 = np.reshape(end, (3, -1))
    T = duration
    h = q1 - q0 - v0 * T - 0.5 * a0 * T * T
    dv = (v1 - v0 - a0 * T) * T
    da = (a1 - a0) * T * T
    c3 = (10.0 * h - 4.0 * dv + 0.5 * da) / T**3
    c4 = (-15.0 * h + 7.0 * dv - da) / T**4
    c5 = (6.0 * h - 3.0 * dv + 0.5 * da) / T**5
    return np.array((q0, v0, 0.5 * a0, c3, c4, c5)).T.copy()  # np.stack's cost a third


SEGMENT_TOLERANCES = np.array([1e-6, 1e-4, 1e-2])
"""rad, rad/s, rad/s²: how far a segment longer than one update period may stray from the
desired q, q̇ and q̈ in its middle (checked there, `faithful_segment`); a segment that strays
farther (across the timing's changes of acceleration) is not used."""


def segment_motion(coefficients: np.ndarray, since: float) -> np.ndarray:
    """q, q̇ and q̈ stacked of a `hermite_segment` (joints × 6) at `since` after its start."""
    powers = since ** np.arange(SEGMENT_COEFFICIENTS)
    q = coefficients @ powers
    v = coefficients[:, 1:] @ (np.arange(1, SEGMENT_COEFFICIENTS) * powers[:-1])
    a = coefficients[:, 2:] @ (np.array([2.0, 6.0, 12.0, 20.0]) * powers[:-2])
    return np.concatenate([q, v, a])


def step_samples(start: float, coefficients: np.ndarray, step: float, times: np.ndarray):
    """q(t - h), q(t) and q(t + h) stacked, of a `hermite_segment` (joints × 6) that starts
    at time `start`, at each of `times` (h = `step`): one row per time.

    Each in Horner form at ((k h + t) - start), k = -1, 0, 1: at t = n h as Drake's periodic
    events compute it, the bits that a SymbolicVectorSystem gave at every plant step
    before RobotMotion sampled its segments itself."""
    offsets = np.array([-step, 0.0, step])[None, :]
    since = ((offsets + np.asarray(times)[:, None]) - start)[..., None]
    value = coefficients[:, -1]
    for c in coefficients[:, -2::-1].T:
        value = c + since * value
    return value.reshape(len(since), -1)


def faithful_segment(coefficients: np.ndarray, middle: np.ndarray, duration: float) -> bool:
    """Whether the segment meets the desired motion `middle` (q, q̇, q̈ stacked) halfway
    within SEGMENT_TOLERANCES."""
    error = np.abs(segment_motion(coefficients, duration / 2) - middle).reshape(3, -1)
    return bool(np.all(error.max(axis=1) <= SEGMENT_TOLERANCES))
