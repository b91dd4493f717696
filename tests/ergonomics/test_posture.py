"""Posture angles measured on the skeleton are the anatomical angles RULA and REBA ask for,
whatever the person's size, and a known posture scores what the methods' rules give by
hand (tests/ergonomics/postures.py)."""

import pytest

from hrc_drake.ergonomics.posture import poses_of, posture_angles
from hrc_drake.ergonomics.reba import reba_score
from hrc_drake.ergonomics.rula import grand_score
from hrc_drake.ergonomics.scoring import Activity, Load, reba_parts, rula_parts
from hrc_drake.human.body import human_body
from hrc_drake.human.survey import survey_size
from tests.ergonomics.postures import (
    PRONATED_REBA,
    PRONATED_RULA,
    REACHING_PRONATED,
    REACHING_REBA,
    REACHING_RULA,
    REACHING_TWISTED,
    posture,
)


def angles_of(body, degrees):
    positions = body.plant_positions(posture(body, degrees))[:, None]
    return posture_angles(poses_of(body, positions)).at(0)


@pytest.mark.parametrize("size", [survey_size("female", 5), survey_size("male", 95)])
def test_angles_are_the_anatomical_ones_for_every_body_size(size):
    """Trunk flexion is the pelvis' tilt plus the lumbar and thoracic flexion (from the
    vertical); neck flexion is taken from the trunk; a knee bent 50 deg measures 50."""
    body = human_body(*size)
    a = angles_of(
        body,
        {
            "pelvis_tilt": 10.0,
            "lumbar_flexion": 20.0,
            "thorax_flexion": 5.0,
            "neck_flexion": -15.0,
            "left_knee_flexion": 50.0,
            "left_shoulder_abduction": 60.0,
            "right_shoulder_flexion": -30.0,
            "right_wrist_deviation": 20.0,
        },
    )
    assert a.trunk_flexion == pytest.approx(35.0, abs=1e-6)
    assert a.neck_flexion == pytest.approx(-15.0, abs=1e-6)
    assert a.knee_flexion["left"] == pytest.approx(50.0, abs=1e-6)
    assert a.arms["left"].abduction == pytest.approx(60.0, abs=1e-6)
    assert a.arms["left"].flexion == pytest.approx(60.0, abs=1e-6)  # elevation, sideways
    assert a.arms["right"].flexion == pytest.approx(-30.0, abs=1e-6)  # extension
    assert a.arms["right"].wrist_deviation == pytest.approx(20.0, abs=1e-6)
    assert not a.feet_on_floor["left"]


def test_upright_standing_is_neutral():
    a = angles_of(human_body(), {})
    assert (a.trunk_flexion, a.trunk_twist, a.neck_flexion) == pytest.approx((0, 0, 0), abs=1e-6)
    assert a.arms["left"].elbow_flexion == pytest.approx(0.0, abs=1e-6)
    assert all(a.feet_on_floor.values())


def test_a_known_posture_scores_what_the_rules_give_by_hand():
    a = angles_of(human_body(), REACHING_TWISTED)
    load, activity = Load(), Activity()
    rula = {side: grand_score(rula_parts(a, side, load, activity)) for side in a.arms}
    reba = {side: reba_score(reba_parts(a, side, load, activity)) for side in a.arms}
    assert rula == {"left": 4, "right": REACHING_RULA}
    assert reba == {"left": 4, "right": REACHING_REBA}


@pytest.mark.parametrize("side", ["left", "right"])
@pytest.mark.parametrize(
    "pronation, flexion, deviation",
    [(-80, 0, 0), (-30, 0, 0), (45, 0, 0), (75, 0, 0), (75, 30, 0), (45, 40, 20), (-60, -50, 25)],
)
def test_wrist_twist_is_the_forearm_pronation(side, pronation, flexion, deviation):
    """The twist reads the pronation joint (positive: pronation, on both sides), also with
    the wrist flexed and deviated; flexion is taken in the forearm turned with it, so a
    pronated wrist flexed 30 deg measures 30 (not part of it as deviation)."""
    a = angles_of(
        human_body(),
        {
            f"{side}_wrist_pronation": pronation,
            f"{side}_wrist_flexion": flexion,
            f"{side}_wrist_deviation": deviation,
        },
    ).arms[side]
    assert a.wrist_twist == pytest.approx(pronation, abs=1e-6)
    assert a.wrist_flexion == pytest.approx(abs(flexion), abs=1e-6)
    unpronated = angles_of(
        human_body(), {f"{side}_wrist_flexion": flexion, f"{side}_wrist_deviation": deviation}
    ).arms[side]
    assert a.wrist_deviation == pytest.approx(unpronated.wrist_deviation, abs=1e-6)


@pytest.mark.parametrize(
    "pronation, rula_twist, reba_wrist", [(0, 1, 1), (30, 1, 2), (-75, 2, 2), (75, 2, 2)]
)
def test_a_pronated_forearm_scores_the_wrist_twist(pronation, rula_twist, reba_wrist):
    """Standing, wrist straight: RULA's twist is 2 at or near the end of the forearm's
    range (beyond 60 deg), REBA's wrist +1 once it is twisted (beyond 10 deg)."""
    a = angles_of(human_body(), {"right_wrist_pronation": pronation})
    rula = rula_parts(a, "right", Load(), Activity())
    reba = reba_parts(a, "right", Load(), Activity())
    assert (rula.wrist_twist, reba.wrist) == (rula_twist, reba_wrist)


def test_a_known_pronated_posture_scores_what_the_rules_give_by_hand():
    a = angles_of(human_body(), REACHING_PRONATED)
    rula = grand_score(rula_parts(a, "right", Load(), Activity()))
    reba = reba_score(reba_parts(a, "right", Load(), Activity()))
    assert (rula, reba) == (PRONATED_RULA, PRONATED_REBA)


def test_survey_sizes_of_a_5th_percentile_woman_and_a_95th_percentile_man():
    """ANSUR II (Gordon et al. 2014): women's stature 1628.5 mm (SD 64.2), men's 1756.2 mm
    (SD 68.6); the 5th and 95th percentiles lie 1.645 SD from the mean."""
    height, _ = survey_size("female", 5)
    assert height == pytest.approx(1.6285 - 1.645 * 0.0642, abs=1e-3)
    height, _ = survey_size("male", 95)
    assert height == pytest.approx(1.7562 + 1.645 * 0.0686, abs=1e-3)
