"""Protective separation distance and the safe speed scale, against numbers worked by hand
(ISO/TS 15066 5.5.4.2.3 with ISO 13855's approach speeds; docs/safety.md)."""

import pytest

from hrc_drake.safety.config import CONSTANT, MEASURED, SafetyConfig
from hrc_drake.safety.ssm import (
    FREE,
    REDUCED,
    STOPPED,
    SsmModel,
    max_safe_scale,
    next_scale,
    protective_separation,
    zone,
)
from hrc_drake.safety.stopping import Stop, StopModel

# A stop model by hand: 0.01 s from (almost) rest, 0.2 / 0.4 / 0.6 s from 33 / 66 / 100 %
# speed, the fastest point travelling half its speed times the stopping time.
STOP = StopModel(speeds=(0.0, 0.33, 0.66, 1.0), times=(0.01, 0.2, 0.4, 0.6), distance_factor=0.5)
# T_r = sensing 0.08 + monitor period 0.01 + command latency 0.01 = 0.1 s;
# C + Z_d + Z_r = 0.1 + 0.05 + 0.02 = 0.17 m; V = 1 m/s.
CONFIG = SafetyConfig(robot_speed=1.0)
MODEL = SsmModel.from_config(CONFIG, STOP, command_latency=0.01)


def test_reaction_time_and_margins():
    assert MODEL.reaction_time == pytest.approx(0.1)
    assert MODEL.lead_time == pytest.approx(0.02)
    assert MODEL.margins == pytest.approx(0.17)


def test_full_speed_robot_and_walking_person():
    # T_s = 0.6 s; S_s = 0.5 · 1.0 m/s · 0.6 s = 0.3 m. With 2.0 m/s: 2.0 · 0.7 + 0.1 + 0.3
    # + 0.17 = 1.97 m > 0.5 m, so 1.6 m/s: S_h = 1.6 · 0.7 = 1.12 → 1.12 + 0.1 + 0.3 + 0.17
    terms = protective_separation(MODEL, 1.0, 1.0, 1.0, 0.0)
    assert (terms.v_h, terms.stopping_time) == (1.6, 0.6)
    assert (terms.s_h, terms.s_r, terms.s_s) == pytest.approx((1.12, 0.1, 0.3))
    assert terms.total == pytest.approx(1.69)


def test_half_speed_stops_in_about_half_the_time_and_a_quarter_of_the_distance():
    # T_s(0.5) = 0.2 + (0.5 - 0.33) / 0.33 · 0.2 = 0.30303 s; the fastest point at 0.5 m/s
    # travels 0.5 · 0.5 · 0.30303 = 0.075758 m. S_h = 1.6 · 0.40303 = 0.644848;
    # S_r = 0.5 · 0.1 = 0.05 → 0.644848 + 0.05 + 0.075758 + 0.17 = 0.940606 m
    terms = protective_separation(MODEL, 0.5, 0.5, 0.5, 0.0)
    assert terms.stopping_time == pytest.approx(0.30303, abs=1e-5)
    assert terms.s_s == pytest.approx(0.075758, abs=1e-6)
    assert terms.total == pytest.approx(0.940606, abs=1e-6)


def test_robot_at_rest_near_the_person_uses_the_hand_speed():
    # T_s = 0, S_s = 0; with 2.0 m/s: 2.0 · 0.1 + 0.17 = 0.37 m ≤ 0.5 m: ISO 13855's K = 2000
    terms = protective_separation(MODEL, 0.0, 0.0, 0.0, 0.0)
    assert terms.v_h == 2.0 and terms.total == pytest.approx(0.37)


def test_iso_13855_least_distance_between_the_two_speeds():
    # r = 0.1: T_s = 0.01 + 0.1 · 0.19 / 0.33 = 0.067576 s; S_s = 0.5 · 0.1 · 0.067576.
    # With 2.0 m/s: 2.0 · 0.167576 + 0.01 + 0.003379 + 0.17 = 0.5185 m > 0.5 m; with
    # 1.6 m/s: 0.268122 + 0.01 + 0.003379 + 0.17 = 0.4515 m < 0.5 m → S = 0.5 m
    terms = protective_separation(MODEL, 0.1, 0.1, 0.1, 0.0)
    assert terms.v_h == 1.6
    assert terms.s_h + terms.s_r + terms.s_s + terms.margins == pytest.approx(0.4515, abs=1e-4)
    assert terms.total == 0.5


def test_the_rules_ignore_the_measured_speed_and_the_measured_rule_takes_it():
    # ISO 13855 at rest: 0.37 m whatever the hand does
    assert protective_separation(MODEL, 0.0, 0.0, 0.0, 2.5).total == pytest.approx(0.37)
    model = SsmModel.from_config(SafetyConfig(v_h_rule=MEASURED), STOP, 0.01)
    # a hand reaching in at 2.5 m/s towards a robot at rest: 2.5 · 0.1 + 0.17 = 0.42 m
    assert protective_separation(model, 0.0, 0.0, 0.0, 2.5).total == pytest.approx(0.42)
    # a person standing still by a robot at full speed: 0 + 0.1 + 0.3 + 0.17 = 0.57 m
    assert protective_separation(model, 1.0, 1.0, 1.0, 0.0).total == pytest.approx(0.57)


def test_constant_rule_keeps_one_speed():
    model = SsmModel.from_config(SafetyConfig(v_h_rule=CONSTANT), STOP, 0.01)
    # at rest: 1.6 · 0.1 + 0.17 = 0.33 m (no 2.0 m/s, no 0.5 m least distance)
    assert protective_separation(model, 0.0, 0.0, 0.0, 0.0).total == pytest.approx(0.33)


def test_unknown_rule_is_refused():
    with pytest.raises(ValueError, match="safety.v_h_rule"):
        SsmModel.from_config(SafetyConfig(v_h_rule="fast"), STOP, 0.01)


def test_safe_scale_by_hand_walking():
    # Bound with T = T_r + lead = 0.12 s, v = v_r = s · 1 m/s. On [0.33, 0.66],
    # T_s = 0.60606 s, so S(s) = 0.5 · 0.60606 s² + (1.6 · 0.60606 + 0.12) s + 1.6 · 0.12 + 0.17
    #     = 0.30303 s² + 1.089697 s + 0.362; S = 1.0 m at
    # s = (-1.089697 + sqrt(1.089697² + 4 · 0.30303 · 0.638)) / (2 · 0.30303) = 0.51245.
    # A moving robot's S_p is at least 0.5 m, so it must also be at rest, after the lead
    # (0.02 s) and its stop, before the person is within 0.5 m:
    # 0.30303 s² + (1.6 · 0.60606 + 0.02) s + 1.6 · 0.02 + 0.5 ≤ 1.0, i.e.
    # 0.30303 s² + 0.989697 s - 0.468 = 0 → s = (-0.989697 + sqrt(0.979500 + 0.567272))
    # / 0.60606 = (-0.989697 + 1.243693) / 0.60606 = 0.41909, the smaller one
    assert max_safe_scale(1.0, 0.0, MODEL) == pytest.approx(0.41909, abs=1e-4)


def test_safe_scale_by_hand_near():
    # Below 0.5 m the hand speed: on [0, 0.33], T_s = 0.01 + 0.575758 s:
    # S(s) = 0.287879 s² + (2.0 · 0.575758 + 0.12 + 0.5 · 0.01) s + 2.0 · 0.13 + 0.17
    #      = 0.287879 s² + 1.276515 s + 0.43; S = 0.45 m at s = 0.015613
    assert max_safe_scale(0.45, 0.0, MODEL) == pytest.approx(0.015613, abs=1e-5)


def test_safe_scale_ends():
    assert max_safe_scale(5.0, 0.0, MODEL) == 1.0
    assert max_safe_scale(0.40, 0.0, MODEL) == 0.0  # 2.0 · 0.12 + 0.17 = 0.41 m at rest
    assert max_safe_scale(-0.1, 0.0, MODEL) == 0.0


@pytest.mark.parametrize("separation", [0.45, 0.6, 0.9, 1.3, 1.7])
def test_the_chosen_scale_leaves_room_for_the_lead(separation):
    """At the chosen scale, S_p of a robot moving that fast fits in the separation that
    remains after the person and the robot close in during the lead time."""
    s = max_safe_scale(separation, 0.0, MODEL)
    terms = protective_separation(MODEL, s, s, s, 0.0)
    closing = (terms.v_h + s) * MODEL.lead_time
    assert terms.total <= separation - closing + 1e-9
    if separation >= 0.5 and s > 0.0:  # and the robot stops before the person is that near
        person = 1.6 * (MODEL.lead_time + STOP.time(s))
        robot = s * MODEL.lead_time + STOP.distance(s, s)
        assert person + robot <= separation - 0.5 + 1e-9


def test_stop_model_from_measured_stops():
    # worst times per speed: 0.19 (33 %), 0.4 (66 %), 0.6 (100 %); the first segment
    # carried on to rest: 0.19 - (0.4 - 0.19) / 0.33 · 0.33 = -0.02 → 0 s.
    stops = (
        Stop("A1", 0.33, 1.0, 0.19, 0.03, 0.33, 1.0),
        Stop("A2", 0.33, 0.33, 0.12, 0.02, 0.30, 1.0),
        Stop("A2", 0.66, 0.33, 0.4, 0.1, 0.6, 5.0),
        Stop("A1", 1.0, 1.0, 0.6, 0.33, 1.0, 9.0),
    )
    model = StopModel.from_stops(stops)
    assert model.speeds == (0.0, 0.33, 0.66, 1.0)
    assert model.times == pytest.approx((0.0, 0.19, 0.4, 0.6))
    # κ: 0.03 / (0.33 · 0.19) = 0.4785, 0.02 / (0.3 · 0.12) = 0.5556, 0.1 / 0.24 = 0.4167,
    # 0.33 / 0.6 = 0.55 → 0.5556
    assert model.distance_factor == pytest.approx(0.5556, abs=1e-4)
    # T_s(0.5) = 0.19 + 0.17 / 0.33 · 0.21 = 0.298182 s
    assert model.time(0.0) == 0.0 and model.time(0.5) == pytest.approx(0.298182, abs=1e-6)


def test_hysteresis_drops_at_once_and_rises_only_past_the_margin():
    assert next_scale(1.0, allowed=0.4, allowed_with_margin=0.3, min_scale=0.05) == 0.4
    assert next_scale(0.4, allowed=0.45, allowed_with_margin=0.38, min_scale=0.05) == 0.4
    assert next_scale(0.4, allowed=0.6, allowed_with_margin=0.5, min_scale=0.05) == 0.5


def test_crawling_becomes_a_stop_and_resumes_past_the_margin():
    assert next_scale(0.3, allowed=0.04, allowed_with_margin=0.0, min_scale=0.05) == 0.0
    assert next_scale(0.0, allowed=0.08, allowed_with_margin=0.03, min_scale=0.05) == 0.0
    assert next_scale(0.0, allowed=0.2, allowed_with_margin=0.1, min_scale=0.05) == 0.1


def test_zones():
    assert [zone(1.0), zone(0.5), zone(0.0)] == [FREE, REDUCED, STOPPED]
