"""Speed and separation monitoring (ISO/TS 15066, 5.5.4): the protective separation
distance S_p and the largest speed scale that keeps the separation above it.

Stopping from a scaled speed: the robot moving at scale s (speed s·v_r) stops with the same
deceleration as from full speed, so its stopping time is s·T_s and its stopping distance
s²·S_s, where T_s and S_s are the stop from full speed. That makes S_p a quadratic in s:

    S_p(s) = v_h (T_r + s T_s) + s v_r T_r + s² S_s + C + Z_d + Z_r
"""

import math
from dataclasses import dataclass

FREE = "free"
REDUCED = "reduced"
STOPPED = "stopped"
ZONES = (FREE, REDUCED, STOPPED)


@dataclass(frozen=True)
class SsmParameters:
    """The terms of S_p that do not depend on the current motion (SI units).

    reaction_time T_r, stopping_time T_s and stopping_distance S_s (the stop from full
    speed), intrusion_distance C, sensor_uncertainty Z_d, robot_uncertainty Z_r.
    """

    reaction_time: float
    stopping_time: float
    stopping_distance: float
    intrusion_distance: float = 0.0
    sensor_uncertainty: float = 0.0
    robot_uncertainty: float = 0.0

    @property
    def constant_terms(self) -> float:
        return self.intrusion_distance + self.sensor_uncertainty + self.robot_uncertainty


def protective_separation(
    v_h: float, v_r: float, params: SsmParameters, scale: float = 1.0
) -> float:
    """S_p for a person approaching at v_h and a robot approaching at v_r (m/s).

    `scale` is the fraction of full speed the robot moves at; v_r is its speed at that
    scale, and the stopping time and distance shrink with it (see module docstring).
    """
    s_h = v_h * (params.reaction_time + scale * params.stopping_time)
    s_r = v_r * params.reaction_time
    s_s = scale**2 * params.stopping_distance
    return s_h + s_r + s_s + params.constant_terms


def max_safe_scale(separation: float, v_h: float, v_r_full: float, params: SsmParameters) -> float:
    """Largest s in [0, 1] with S_p(s) <= separation, where the robot approaches at s·v_r_full.

    0 means even a robot at rest is too close (monitored stop); 1 means full speed is safe.
    """
    # S_p(s) = a s² + b s + c
    a = params.stopping_distance
    b = v_h * params.stopping_time + v_r_full * params.reaction_time
    c = v_h * params.reaction_time + params.constant_terms
    room = separation - c
    if room <= 0.0:
        return 0.0
    if a > 0.0:
        s = (-b + math.sqrt(b * b + 4.0 * a * room)) / (2.0 * a)
    elif b > 0.0:
        s = room / b
    else:
        return 1.0
    return min(1.0, s)


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
