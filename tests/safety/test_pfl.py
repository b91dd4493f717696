"""Energy-transfer contact estimate against the formula worked by hand."""

import math

import pytest

from hrc_drake.human.skeleton import REGIONS
from hrc_drake.safety.pfl import (
    REGION_LIMITS,
    assess_contact,
    max_permissible_speed,
    reduced_mass,
    robot_effective_mass,
)


def test_every_body_region_of_the_human_model_has_limits():
    assert set(REGION_LIMITS) == set(REGIONS)


def test_hand_contact_by_hand():
    # Robot: 14 kg moving parts, 1 kg tool + 1 kg part → m_R = 7 + 2 = 9 kg.
    m_r = robot_effective_mass(14.0, 2.0)
    assert m_r == 9.0
    # Hand: m_H = 0.6 kg, k = 75 N/mm. μ = 1 / (1/0.6 + 1/9) = 0.5625 kg.
    assert reduced_mass(0.6, m_r) == pytest.approx(0.5625)
    # F = v sqrt(μ k) = 0.5 · sqrt(0.5625 · 75000) = 0.5 · 205.396 = 102.698 N
    contact = assess_contact("hand", 0.5, m_r, contact_area_cm2=1.0)
    assert contact.force == pytest.approx(0.5 * math.sqrt(0.5625 * 75000))
    assert contact.force == pytest.approx(102.698, abs=1e-3)
    # Pressure on 1 cm²: 102.7 N/cm². Transient limits 280 N, 520 N/cm² → ratio 0.3668
    assert contact.pressure == pytest.approx(contact.force)
    assert contact.limit_ratio == pytest.approx(102.698 / 280, abs=1e-5)
    assert not contact.violation


def test_chest_contact_over_the_pressure_limit():
    # m_R = 9 kg, chest m_H = 40 kg: μ = 360/49 = 7.3469 kg, k = 25 N/mm.
    # F = 1.0 · sqrt(7.3469 · 25000) = 428.57 N > 280 N; pressure 428.57 > 240 N/cm².
    contact = assess_contact("chest", 1.0, 9.0, contact_area_cm2=1.0)
    assert contact.force == pytest.approx(428.571, abs=1e-3)
    assert contact.limit_ratio == pytest.approx(428.571 / 240, abs=1e-4)
    assert contact.violation


def test_larger_area_lowers_pressure_only():
    small = assess_contact("thigh", 0.3, 9.0, contact_area_cm2=1.0)
    large = assess_contact("thigh", 0.3, 9.0, contact_area_cm2=4.0)
    assert large.force == small.force
    assert large.pressure == pytest.approx(small.pressure / 4)


def test_face_and_skull_contact_is_always_a_violation():
    for region in ("face", "skull_forehead"):
        contact = assess_contact(region, 0.001, 9.0, contact_area_cm2=1.0)
        assert contact.limit_ratio < 1.0
        assert contact.violation
        assert max_permissible_speed(region, 9.0) == 0.0


def test_permissible_speed_reaches_the_transient_force_limit():
    # Lower arm: μ = 1 / (1/2 + 1/9) = 1.6364 kg, k = 40 N/mm: sqrt(μ k) = 255.84 N·s/m;
    # v_max = 320 N / 255.84 = 1.2508 m/s.
    v_max = max_permissible_speed("lower_arm", 9.0)
    assert v_max == pytest.approx(1.2508, abs=1e-4)
    assert assess_contact("lower_arm", v_max, 9.0, 10.0).force == pytest.approx(320.0)


def test_separating_contact_has_no_force():
    contact = assess_contact("pelvis", -0.2, 9.0, 1.0)
    assert contact.relative_speed == 0.0 and contact.force == 0.0
