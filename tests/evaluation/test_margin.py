"""The safety margin in report.json: the least separation - S_p while the robot moves, judged
with ISO 13855's approach speeds whatever the monitor assumes, and contacts by their limit
ratio (the walk-up cell, the person standing beside the working robot)."""

import json

import numpy as np
import pytest

from hrc_drake.evaluation.margin import CONTACT_SCALE, contact_ratio, margin_metrics, margin_model
from hrc_drake.runner import run, run_setup
from hrc_drake.safety.log import read_safety_log
from hrc_drake.safety.messages import ContactRecord
from hrc_drake.safety.pfl import QUASI_STATIC, TRANSIENT, assess_contact
from hrc_drake.safety.reference import reference_protective
from hrc_drake.scenario import load_scenario

BESIDE = (
    ("duration", 7.0),
    ("parameters.set_off_ms", "0"),
    ("parameters.visit_area", "right_side"),
)
WEAK = (("safety.v_h_rule", "constant"), ("safety.v_h", 0.8))
"""A monitor that takes the person for half as fast as ISO 13855 does."""


def walk_up_run(out, overrides):
    scenario = load_scenario("walk_up", overrides)
    run(scenario, out_dir=out)
    report = json.loads((out / "report.json").read_text())
    return scenario, report, read_safety_log(out / "safety.npz")


@pytest.fixture(scope="module")
def correct(tmp_path_factory):
    return walk_up_run(tmp_path_factory.mktemp("correct"), BESIDE)


@pytest.fixture(scope="module")
def weak(tmp_path_factory):
    return walk_up_run(tmp_path_factory.mktemp("weak"), BESIDE + WEAK)


def least_margin(log, protective, moving_speed):
    """min(separation - S_p) over the updates at which the robot moved, by hand."""
    moving = (log["robot_speed"] > moving_speed) & np.isfinite(log["separation"])
    return np.min(log["separation"][moving] - protective[moving])


def test_with_the_iso_rule_the_margin_uses_the_monitors_own_s_p(correct):
    scenario, report, log = correct
    person = np.isfinite(log["separation"])
    recomputed = reference_protective(log, margin_model(run_setup(scenario)))
    np.testing.assert_allclose(recomputed[person], log["protective"][person], rtol=0, atol=1e-12)
    margin = report["margin"]
    assert margin["ssm"] == pytest.approx(
        least_margin(log, log["protective"], scenario.safety.moving_speed), abs=1e-9
    )
    assert margin["value"] == margin["ssm"] > 0  # no contact; the monitor keeps its distance
    assert not margin["violation"] and report["safety"]["ssm_violations"]["count"] == 0
    at = margin["at"]
    assert at["separation"] - at["protective"] == pytest.approx(margin["ssm"], abs=1e-8)
    assert at["region"] and at["part"] and at["robot_speed"] > scenario.safety.moving_speed


def test_a_monitor_assuming_a_slower_person_shows_its_violation(weak, correct):
    """The weak monitor's own verdict sees nothing: it lets the robot move as fast as its
    smaller S_p allows. Judged with ISO 13855's speeds, the run violates SSM."""
    scenario, report, log = weak
    assert report["safety"]["ssm_violations"]["count"] == 0
    reference = reference_protective(log, margin_model(run_setup(scenario)))
    moving = (log["robot_speed"] > scenario.safety.moving_speed) & np.isfinite(log["separation"])
    assert np.all(reference[moving] > log["protective"][moving])
    margin = report["margin"]
    assert margin["violation"] and margin["value"] < 0
    assert margin["ssm"] == pytest.approx(
        least_margin(log, reference, scenario.safety.moving_speed), abs=1e-9
    )
    assert margin["value"] < correct[1]["margin"]["value"]


def record(assessment) -> ContactRecord:
    return ContactRecord(1.0, 1.2, assessment, True, assessment.violation)


def test_contacts_count_by_their_worst_limit_ratio():
    soft = record(assess_contact("thigh", "link_3", 0.2, 10.0, 1.0, TRANSIENT))
    hard = record(assess_contact("hand", "link_6", 0.5, 10.0, 1.0, QUASI_STATIC))
    worst = max(
        (r.worst.force_ratio, r.worst.pressure_ratio) for r in (soft, hard)
    )  # the pressure governs on 1 cm²
    assert contact_ratio((soft, hard)) == pytest.approx(max(worst))
    assert contact_ratio(()) == 0.0


def test_a_contact_the_region_must_never_have_counts_over_its_limit():
    face = assess_contact("face", "link_6", 0.01, 10.0, 1.0, TRANSIENT)
    assert not face.violation or max(face.force_ratio, face.pressure_ratio) < 1.0
    ratio = contact_ratio((record(face),))
    assert ratio == pytest.approx(1.0 + max(face.force_ratio, face.pressure_ratio))
    assert ratio > 1.0


def test_the_margin_is_the_lower_of_ssm_and_contact(correct):
    scenario, _, log = correct
    model = margin_model(run_setup(scenario))
    contact = record(assess_contact("hand", "link_6", 0.4, 10.0, 1.0, QUASI_STATIC))
    ratio = contact_ratio((contact,))
    found = margin_metrics(log, model, scenario.safety.moving_speed, (contact,), ("x",) * 20)
    assert found["contact_ratio"] == pytest.approx(ratio)
    assert found["value"] == pytest.approx(min(found["ssm"], CONTACT_SCALE * (1.0 - ratio)))
    assert found["violation"] == (found["value"] < 0)


def test_no_margin_where_the_robot_never_moved_near_a_person(correct):
    scenario, _, log = correct
    still = {**log, "robot_speed": np.zeros_like(log["robot_speed"])}
    found = margin_metrics(still, margin_model(run_setup(scenario)), 0.01, (), ("x",) * 20)
    assert found == {"value": None, "ssm": None, "contact_ratio": 0.0, "violation": False}
    assert run(load_scenario("base"), duration=0.1).metrics["margin"] == {}  # no monitor
