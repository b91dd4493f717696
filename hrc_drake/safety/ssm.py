"""Speed and separation monitoring (ISO/TS 15066, 5.5.4.2.3; docs/safety.md): the
protective separation distance S_p and the largest speed scale that keeps the separation
above it.

    S_p = v_h (T_r + T_s) + v_r T_r + S_s + C + Z_d + Z_r

v_h is the person's speed towards the robot (ISO 13855's rule, a constant, or the measured
speed of the closest body region), v_r the robot's speed towards the person at the closest
points; T_s and S_s the robot's stop from the speed it moves at now (`StopModel`).

Choosing the scale s, the monitor does not know the coming motion, so it bounds it: every
robot point moves at most s·V (V the robot's top point speed), towards the person too, and
the stop is that from fraction s of full speed. The scale takes effect one monitor period
and one command latency later, so the monitor chooses it for the separation left then: with
that lead added to T_r.
"""

import math
from dataclasses import dataclass

from hrc_drake.safety.config import ISO_13855, MEASURED, V_H_RULES, SafetyConfig
from hrc_drake.safety.stopping import StopModel

FREE = "free"
REDUCED = "reduced"
STOPPED = "stopped"
ZONES = (FREE, REDUCED, STOPPED)


@dataclass(frozen=True)
class SsmModel:
    """What S_p needs besides the current motion (SI units)."""

    reaction_time: float
    """T_r: sensing, monitor period and command latency"""
    lead_time: float
    """how long a chosen scale takes to act: monitor period and command latency"""
    stop: StopModel
    margins: float
    """C + Z_d + Z_r"""
    v_h: float
    v_h_near: float
    near_distance: float
    """ISO 13855: v_h_near applies where S_p with it is at most this (0: never)"""
    robot_speed: float
    """V: the fastest any robot point moves at full speed"""
    measured: bool = False
    """v_h is the measured speed of the closest body region towards the robot"""

    @classmethod
    def from_config(cls, config: SafetyConfig, stop: StopModel, command_latency: float):
        if config.v_h_rule not in V_H_RULES:
            raise ValueError(f"safety.v_h_rule must be one of {V_H_RULES}, not {config.v_h_rule!r}")
        lead = config.period + command_latency
        iso = config.v_h_rule == ISO_13855
        return cls(
            reaction_time=config.sensing_time + lead,
            lead_time=lead,
            stop=stop,
            margins=config.intrusion_distance
            + config.sensor_uncertainty
            + config.robot_uncertainty,
            v_h=config.v_h,
            v_h_near=config.v_h_near if iso else config.v_h,
            near_distance=config.near_distance if iso else 0.0,
            robot_speed=config.robot_speed,
            measured=config.v_h_rule == MEASURED,
        )


@dataclass(frozen=True)
class SsmTerms:
    """S_p and its terms at one moment (m, m/s, s)."""

    v_h: float
    v_r: float
    stopping_time: float
    s_h: float
    s_r: float
    s_s: float
    margins: float
    total: float
    """S_p: the sum of the terms, or ISO 13855's least distance where that is larger"""


NO_TERMS = SsmTerms(0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0)


def protective_separation(
    model: SsmModel, speed_fraction: float, point_speed: float, v_r: float, measured_v_h: float
) -> SsmTerms:
    """S_p for a robot moving at `speed_fraction` of full speed, its fastest point at
    `point_speed` and its closest point towards the person at `v_r`, and a person whose
    closest region approaches at `measured_v_h` (m/s, used by the `measured` rule)."""
    t_s = model.stop.time(speed_fraction)
    s_s = model.stop.distance(speed_fraction, point_speed)
    t_r = model.reaction_time
    s_r = v_r * t_r
    robot_terms = s_r + s_s + model.margins
    if model.measured:
        v_h = measured_v_h
        total = v_h * (t_r + t_s) + robot_terms
    else:  # ISO 13855 (a constant when v_h_near is v_h and the near distance 0)
        v_h = model.v_h_near
        total = v_h * (t_r + t_s) + robot_terms
        if total > model.near_distance:
            v_h = model.v_h
            total = max(v_h * (t_r + t_s) + robot_terms, model.near_distance)
    return SsmTerms(v_h, v_r, t_s, v_h * (t_r + t_s), s_r, s_s, model.margins, total)


def max_safe_scale(separation: float, measured_v_h: float, model: SsmModel) -> float:
    """Largest s in [0, 1] whose bound on S_p, one lead time ahead, fits in `separation`.

    0 means even a robot at rest is too close (monitored stop); 1 means full speed is safe.
    By ISO 13855 the near speed applies below the near distance. Above it, a moving robot's
    S_p is never below the near distance, so the robot must also be able to come to rest
    (after the lead time and its stop) before the person is that near.
    """
    reaction = model.reaction_time + model.lead_time
    near = separation < model.near_distance
    v_h = measured_v_h if model.measured else model.v_h_near if near else model.v_h
    allowed = _largest_scale(separation, v_h, model, reaction, model.margins)
    if near or model.near_distance <= 0.0:
        return allowed
    return min(
        allowed, _largest_scale(separation, v_h, model, model.lead_time, model.near_distance)
    )


def _largest_scale(
    separation: float, v_h: float, model: SsmModel, reaction: float, margins: float
) -> float:
    """Largest s with S(s) ≤ separation, where with T_s(s) = a + b s on each segment of
    the stop model, V the top point speed and T the `reaction` time:

        S(s) = v_h (T + a + b s) + s V T + κ s V (a + b s) + margins
             = κ V b s² + (v_h b + V T + κ V a) s + v_h (T + a) + margins

    (at rest, s = 0, the stopping time is 0).
    """
    stop, V = model.stop, model.robot_speed
    kappa = stop.distance_factor
    speeds, times = stop.speeds, stop.times
    room = separation - v_h * reaction - margins
    if room < 0.0:
        return 0.0
    top = next(
        (
            k
            for k in range(1, len(speeds))
            if v_h * times[k] + speeds[k] * V * (reaction + kappa * times[k]) > room
        ),
        None,
    )
    if top is None:
        return 1.0
    s0, s1 = speeds[top - 1], speeds[top]
    b = (times[top] - times[top - 1]) / (s1 - s0)
    a = times[top - 1] - b * s0
    quadratic = kappa * V * b
    linear = v_h * b + V * reaction + kappa * V * a
    room -= v_h * a
    if room <= 0.0:  # only below the first tabulated speed: moving at all is too fast
        return s0
    if quadratic > 0.0:
        s = (-linear + math.sqrt(linear * linear + 4.0 * quadratic * room)) / (2.0 * quadratic)
    else:
        s = room / linear
    return min(max(s, s0), s1)


def next_scale(
    current: float, allowed: float, allowed_with_margin: float, min_scale: float
) -> float:
    """The scale to command next, with hysteresis so it does not chatter.

    It drops at once to `allowed` (the safe scale at the measured separation) but rises only
    to `allowed_with_margin` (the safe scale at the separation minus the hysteresis
    distance); scales below `min_scale` become a stop.
    """
    scale = allowed if allowed < current else max(current, allowed_with_margin)
    return 0.0 if scale < min_scale else scale


def zone(scale: float) -> str:
    if scale >= 1.0:
        return FREE
    return STOPPED if scale <= 0.0 else REDUCED
