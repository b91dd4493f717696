"""The realism audit samples every second of the person's poses (30 Hz, `human.audit_every`)
and finds what it finds at every pose (60 Hz): its worst values within 2 mm and 1°, the
pelvis speed's swing within a percentage point, on the same run of coexistence (the audit
only reads, so both runs are the same run)."""

import pytest

from hrc_drake.evaluation.realism import LIMITS, realism_metrics
from hrc_drake.runner import simulate
from hrc_drake.scenario import load_scenario, overridden

DURATION = 20.5
"""s: coexistence's person has walked, lifted and stood at the bench (the worst foot slip at
16.7 s and floor contact at 19.9 s of the full run among them)."""
TOLERANCE = {measure: 0.002 for measure in LIMITS} | {"carried_tilt_deg": 1.0}


def audit(every: int | None) -> dict:
    scenario = load_scenario("coexistence")
    if every is not None:
        scenario = overridden(scenario, [("human.audit_every", every)])
    return realism_metrics(simulate(overridden(scenario, [("duration", DURATION)])).realism)


@pytest.fixture(scope="module")
def audits():
    return audit(None), audit(1)


def test_the_audit_skips_poses_by_default():
    assert load_scenario("coexistence").human.audit_every > 1


@pytest.mark.parametrize("measure", sorted(LIMITS))
def test_worst_values_as_at_every_pose(audits, measure):
    default, every_pose = audits
    assert default[measure]["max"] == pytest.approx(
        every_pose[measure]["max"], abs=TOLERANCE[measure]
    )


def test_the_pelvis_speed_swings_as_at_every_pose(audits):
    default, every_pose = (a["pelvis_speed"] for a in audits)
    assert default["strides"] == every_pose["strides"] > 0
    assert default["variation_max"] == pytest.approx(every_pose["variation_max"], abs=0.01)
    assert default["mean_speed"] == pytest.approx(every_pose["mean_speed"], rel=0.01)
