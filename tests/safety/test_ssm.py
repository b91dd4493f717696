"""Protective separation distance and the safe speed scale, against numbers worked by hand."""

import pytest

from hrc_drake.motion.stopping import stopping_data
from hrc_drake.safety.config import SafetyConfig
from hrc_drake.safety.ssm import (
    FREE,
    REDUCED,
    STOPPED,
    SsmParameters,
    max_safe_scale,
    next_scale,
    protective_separation,
    zone,
)
from hrc_drake.safety.stopping import ssm_parameters

# T_r 0.1 s, T_s 0.3 s, S_s 0.15 m, C 0.1 m, Z_d 0.05 m, Z_r 0.02 m
PARAMS = SsmParameters(0.1, 0.3, 0.15, 0.1, 0.05, 0.02)


def test_iso_default_person_and_full_speed_robot():
    # S_h = 1.6 (0.1 + 0.3) = 0.64; S_r = 1.0 · 0.1 = 0.1; S_s = 0.15; C+Z = 0.17 → 1.06 m
    assert protective_separation(1.6, 1.0, PARAMS) == pytest.approx(1.06)


def test_short_distance_person_speed():
    # S_h = 2.0 · 0.4 = 0.8; S_r = 0.5 · 0.1 = 0.05; + 0.15 + 0.17 → 1.17 m
    assert protective_separation(2.0, 0.5, PARAMS) == pytest.approx(1.17)


def test_robot_at_half_scale_stops_sooner_and_shorter():
    # s = 0.5: S_h = 1.6 (0.1 + 0.15) = 0.4; S_r = 0.5 · 0.1 = 0.05;
    # S_s = 0.25 · 0.15 = 0.0375; + 0.17 → 0.6575 m
    assert protective_separation(1.6, 0.5, PARAMS, scale=0.5) == pytest.approx(0.6575)


def test_robot_at_rest_leaves_person_travel_and_margins():
    # S_h = 1.6 · 0.1 = 0.16; + 0.17 → 0.33 m
    assert protective_separation(1.6, 0.0, PARAMS, scale=0.0) == pytest.approx(0.33)


def test_safe_scale_inverts_protective_separation():
    # S_p(s) = 0.15 s² + (1.6·0.3 + 1.0·0.1) s + 0.33 = 0.15 s² + 0.58 s + 0.33.
    # s = 0.5 gives 0.0375 + 0.29 + 0.33 = 0.6575 m.
    assert max_safe_scale(0.6575, 1.6, 1.0, PARAMS) == pytest.approx(0.5)
    assert max_safe_scale(1.06, 1.6, 1.0, PARAMS) == pytest.approx(1.0)


def test_safe_scale_is_one_when_far_and_zero_inside_the_fixed_terms():
    assert max_safe_scale(5.0, 1.6, 1.0, PARAMS) == 1.0
    assert max_safe_scale(0.33, 1.6, 1.0, PARAMS) == 0.0
    assert max_safe_scale(-0.1, 1.6, 1.0, PARAMS) == 0.0


def test_safe_scale_without_stopping_distance_is_linear():
    params = SsmParameters(0.1, 0.3, 0.0)
    # S_p(s) = 0.16 + 0.58 s; at 0.45 m: s = 0.29 / 0.58 = 0.5
    assert max_safe_scale(0.45, 1.6, 1.0, params) == pytest.approx(0.5)


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


def test_config_stop_figures_override_the_variant_data():
    default = ssm_parameters(SafetyConfig(), "lbr_iisy3_r760")
    measured = stopping_data("lbr_iisy3_r760")
    assert (default.stopping_time, default.stopping_distance) == (measured.time, measured.distance)
    given = ssm_parameters(SafetyConfig(stopping_time=0.5, stopping_distance=0.2), "x")
    assert (given.stopping_time, given.stopping_distance) == (0.5, 0.2)
    assert given.constant_terms == pytest.approx(0.1 + 0.05 + 0.02)
