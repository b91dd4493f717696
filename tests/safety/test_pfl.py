"""Power and force limiting against ISO/TS 15066 Annex A, worked by hand for every region.

Robot: 14 kg moving parts, 1 kg tool + 1 kg part → m_R = 14/2 + 2 = 9 kg; contact area
1 cm², so a pressure in N/cm² equals the force in N. Per region (Table A.2, most
restrictive pressure; docs/safety.md): μ = (1/m_H + 1/m_R)⁻¹ and sqrt(μ k) with k in N/m.

Transient: v_max = min(2 F, 2 p A) / sqrt(μ k); skull, forehead and face: not permitted.
Quasi-static (pinned, μ = m_R): v_max = min(F, p A) / sqrt(m_R k).
"""

import math

import pytest

from hrc_drake.human.skeleton import REGIONS
from hrc_drake.safety.pfl import (
    QUASI_STATIC,
    REGION_LIMITS,
    TRANSIENT,
    assess_contact,
    max_permissible_speed,
    reduced_mass,
    robot_effective_mass,
)

M_R = 9.0
AREA = 1.0

# region: (F N, p N/cm², m_H kg, k N/mm, sqrt(μ k) N·s/m, transient v_max, which limit
#          governs it, sqrt(m_R k), quasi-static v_max)
HAND_WORKED = {
    # μ = 1/(1/4.4 + 1/9) = 2.9552; sqrt(2.9552 · 150000) = 665.795; banned transient;
    # pinned: sqrt(9 · 150000) = 1161.895, min(130, 110) / 1161.895 = 0.0947 (pressure)
    "skull_forehead": (130, 110, 4.4, 150, 665.795, 0.0, "pressure", 1161.895, 0.0947),
    # sqrt(2.9552 · 75000) = 470.788; pinned: 65 / sqrt(9 · 75000) = 65 / 821.584 = 0.0791
    "face": (65, 110, 4.4, 75, 470.788, 0.0, "force", 821.584, 0.0791),
    # μ = 1/(1/1.2 + 1/9) = 1.0588; sqrt(1.0588 · 50000) = 230.089; 280 / 230.089 = 1.2169
    "neck": (150, 140, 1.2, 50, 230.089, 1.2169, "pressure", 670.820, 0.2087),
    # μ = 1/(1/40 + 1/9) = 360/49 = 7.3469; sqrt(7.3469 · 35000) = 507.093; 320 / 507.093
    "back_shoulders": (210, 160, 40, 35, 507.093, 0.6310, "pressure", 561.249, 0.2851),
    # sqrt(7.3469 · 25000) = 428.571; 240 / 428.571 = 0.5600; pinned 120 / 474.342
    "chest": (140, 120, 40, 25, 428.571, 0.5600, "pressure", 474.342, 0.2530),
    # sqrt(7.3469 · 10000) = 271.052; 220 / 271.052 = 0.8117; pinned 110 / 300
    "abdomen": (110, 140, 40, 10, 271.052, 0.8117, "force", 300.000, 0.3667),
    # 360 / 428.571 = 0.8400; pinned 180 / 474.342 = 0.3795
    "pelvis": (180, 210, 40, 25, 428.571, 0.8400, "force", 474.342, 0.3795),
    # μ = 1/(1/3 + 1/9) = 2.25; sqrt(2.25 · 30000) = 259.808; 300 / 259.808 = 1.1547
    "upper_arm": (150, 190, 3, 30, 259.808, 1.1547, "force", 519.615, 0.2887),
    # μ = 1/(1/2 + 1/9) = 1.6364; sqrt(1.6364 · 40000) = 255.841; 320 / 255.841 = 1.2508
    "lower_arm": (160, 180, 2, 40, 255.841, 1.2508, "force", 600.000, 0.2667),
    # μ = 1/(1/0.6 + 1/9) = 0.5625; sqrt(0.5625 · 75000) = 205.396; 280 / 205.396 = 1.3632
    "hand": (140, 190, 0.6, 75, 205.396, 1.3632, "force", 821.584, 0.1704),
    # μ = 1/(1/75 + 1/9) = 8.0357; sqrt(8.0357 · 50000) = 633.866; 440 / 633.866 = 0.6942
    "thigh": (220, 220, 75, 50, 633.866, 0.6942, "force", 670.820, 0.3280),
    # sqrt(8.0357 · 60000) = 694.365; 260 / 694.365 = 0.3744; pinned 130 / 734.847
    "lower_leg": (130, 210, 75, 60, 694.365, 0.3744, "force", 734.847, 0.1769),
}


def test_every_body_region_of_the_human_model_has_limits():
    assert set(REGION_LIMITS) == set(REGIONS) == set(HAND_WORKED)


@pytest.mark.parametrize("region", sorted(HAND_WORKED))
def test_table_a2_row(region):
    force, pressure, mass, spring, *_ = HAND_WORKED[region]
    limits = REGION_LIMITS[region]
    assert (limits.max_force, limits.max_pressure) == (force, pressure)
    assert (limits.effective_mass, limits.spring_constant) == (mass, spring)


@pytest.mark.parametrize("region", sorted(HAND_WORKED))
def test_transient_permissible_speed_and_its_force(region):
    *_, stiffness, v_max, governs, _, _ = HAND_WORKED[region]
    force, pressure = HAND_WORKED[region][:2]
    computed = max_permissible_speed(region, M_R, AREA)
    assert computed == pytest.approx(v_max, abs=1e-4)
    contact = assess_contact(region, "link_6", 0.5, M_R, AREA)
    assert contact.force == pytest.approx(0.5 * stiffness, abs=1e-3)
    assert contact.pressure == pytest.approx(contact.force / AREA)
    if v_max == 0.0:  # skull, forehead, face: any transient contact violates
        assert contact.violation and (contact.force_limit, contact.pressure_limit) == (
            force,
            pressure,
        )
        return
    assert (contact.force_limit, contact.pressure_limit) == (2 * force, 2 * pressure)
    at_limit = assess_contact(region, "link_6", computed, M_R, AREA)
    governing = at_limit.force_ratio if governs == "force" else at_limit.pressure_ratio
    other = at_limit.pressure_ratio if governs == "force" else at_limit.force_ratio
    assert governing == pytest.approx(1.0, abs=1e-9) and other <= 1.0 + 1e-9
    assert not at_limit.violation
    assert assess_contact(region, "link_6", 1.01 * computed, M_R, AREA).violation


@pytest.mark.parametrize("region", sorted(HAND_WORKED))
def test_quasi_static_permissible_speed_uses_the_limits_as_they_are(region):
    force, pressure, *_, pinned_stiffness, v_max = HAND_WORKED[region]
    assert max_permissible_speed(region, M_R, AREA, QUASI_STATIC) == pytest.approx(v_max, abs=1e-4)
    contact = assess_contact(region, "link_6", v_max, M_R, AREA, QUASI_STATIC)
    assert contact.force == pytest.approx(v_max * pinned_stiffness, rel=1e-3)
    assert (contact.force_limit, contact.pressure_limit) == (force, pressure)
    assert max(contact.force_ratio, contact.pressure_ratio) == pytest.approx(1.0, abs=2e-3)


def test_a_pinned_hand_pressed_at_rest_reads_its_compression():
    # Pinned, hardly moving, 3 mm deep: F = k · depth = 75 N/mm · 3 mm = 225 N > 140 N.
    contact = assess_contact("hand", "link_6", 0.0, M_R, AREA, QUASI_STATIC, depth=0.003)
    assert contact.force == pytest.approx(225.0)
    assert contact.force_ratio == pytest.approx(225.0 / 140.0)
    assert contact.violation
    # The same touch where the hand can recoil reads the (zero) impact only.
    assert assess_contact("hand", "link_6", 0.0, M_R, AREA, TRANSIENT, depth=0.003).force == 0.0


def test_masses_by_hand():
    assert robot_effective_mass(14.0, 2.0) == M_R
    assert reduced_mass(0.6, M_R) == pytest.approx(0.5625)
    assert reduced_mass(40.0, M_R) == pytest.approx(360.0 / 49.0)


def test_larger_area_lowers_pressure_only():
    small = assess_contact("thigh", "link_3", 0.3, M_R, 1.0)
    large = assess_contact("thigh", "link_3", 0.3, M_R, 4.0)
    assert large.force == small.force
    assert large.pressure == pytest.approx(small.pressure / 4)
    # On 4 cm² the chest's pressure bound (4 · 240) lies above its force bound (280).
    assert max_permissible_speed("chest", M_R, 4.0) == pytest.approx(280 / 428.571, abs=1e-4)


def test_separating_contact_has_no_force():
    contact = assess_contact("pelvis", "link_2", -0.2, M_R, AREA)
    assert contact.relative_speed == 0.0 and contact.force == 0.0
    assert not math.isnan(contact.force_ratio)
