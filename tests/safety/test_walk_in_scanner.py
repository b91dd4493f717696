"""Closed-loop walk-ins seen through a laser scanner or a light curtain (tests/safety/
walk_in.py): the monitor knows only what the sensor reports (the scanner 0.3 m above the
floor), a response time late.

Walking in from 4.5 m at 1.6 m/s and reaching in at 2.0 m/s, the person is detected at
the scan plane on their lower legs (checked against Drake's distances to the posed body),
the robot slows and stands still before anything touches it, with S_p built from the
scanner's intrusion distance C = 1200 mm − 0.4 H and its response time (recomputed term by
term from the stopping data). Behind a wall of fence panels the same walk-in is never
detected: the robot sweeps on at full speed into the person, and the run's margin, judged
on the real body, shows the violation. A light curtain across the approach stops the robot
while the person crosses it and, once they are through, knows nothing of them. An
independent recomputation of the real body's distances and S_p agrees with the log in all.
"""

import numpy as np
import pytest

from hrc_drake.evaluation.margin import margin_metrics
from hrc_drake.safety.log import log_of
from hrc_drake.safety.reference import reference_model
from hrc_drake.safety.stopping import StopModel
from tests.safety.recompute import Scene, worst_stopping_times
from tests.safety.test_walk_in import assert_recomputation_agrees, assert_ssm_holds
from tests.safety.walk_in import (
    CURTAIN,
    LIGHT_CURTAIN,
    OCCLUDED,
    SCANNER,
    SEEN,
    START_SCANNED,
    Case,
    simulate,
)

VARIANT = "lbr_iisy3_r760"
CASES = {
    kind: Case(VARIANT, 90.0, START_SCANNED, 0.5, sensor=kind) for kind in (SEEN, OCCLUDED, CURTAIN)
}
COMMAND_LATENCY = 0.01


@pytest.fixture(scope="module")
def outcomes():
    return {kind: simulate(case) for kind, case in CASES.items()}


def test_the_robot_stands_still_before_the_scanned_person_reaches_it(outcomes):
    """Judged on the real body: under way while the person is far, never moving closer than
    S_p, at rest before anything touches it, going again once they left."""
    outcome = outcomes[SEEN]
    assert_ssm_holds(outcome)
    assert np.nanmin(outcome.signals_named("sensed_separation")) < 0.5


def test_the_scanner_detects_the_legs_at_its_scan_height(outcomes):
    """Every point the scanner reports on the person lies in its scan plane and on the
    surface of a lower leg as Drake measures it (within the measurement error), and every
    scan while the person walks in and stands sees them."""
    outcome = outcomes[SEEN]
    scene = Scene(outcome.scenario)
    path = outcome.case.person
    readings = outcome.readings
    assert all(r.sees_person for r in readings), "a scan missed the person in plain view"
    human = {g: name for g, _, name in scene.human_geometry}
    for reading in readings[:: len(readings) // 12]:
        k = min(np.searchsorted(outcome.times, reading.time), len(outcome.times) - 1)
        query, _ = scene.pose(outcome.robot_q[:, k], path.value(reading.time).ravel())
        points = reading.starts
        np.testing.assert_allclose(points[:, 2], SCANNER.height)
        for point in points:
            nearest = min(
                (r for r in query.ComputeSignedDistanceToPoint(point, 1.0) if r.id_G in human),
                key=lambda r: abs(r.distance),
            )
            assert abs(nearest.distance) <= SCANNER.measurement_error + 1e-9
            assert human[nearest.id_G].split("::")[-1].startswith("lower_leg")


def test_scanned_sp_holds_the_intrusion_distance_and_the_response_time(outcomes):
    """S_p at the nearest detection = v_h (T_r + T_s) + v_r T_r + S_s + C + Z_d + Z_r with
    v_h = 1.6 m/s (S_p > 0.5 m), T_r the scanner's response time and the monitor's and the
    command's periods, v_r the robot's fastest point (the scanner cannot tell its direction),
    C = 1200 mm − 0.4 × 300 mm, Z_d the scanner's measurement error."""
    outcome = outcomes[SEEN]
    config = outcome.config
    speeds, times, kappa = worst_stopping_times(VARIANT)
    seen = outcome.signals_named("seen") > 0
    rate = outcome.signals_named("path_rate")[seen]
    v_r = outcome.signals_named("robot_speed")[seen]
    t_s = np.where(rate > 0.0, np.interp(rate, speeds, times), 0.0)
    t_r = 0.12 + config.period + COMMAND_LATENCY
    intrusion = 1.2 - 0.4 * 0.3
    expected = 1.6 * (t_r + t_s) + v_r * t_r + kappa * v_r * t_s + intrusion + 0.05 + 0.02
    np.testing.assert_allclose(outcome.signals_named("sensed_protective")[seen], expected)


def test_behind_a_wall_the_person_is_not_seen_and_the_margin_shows_the_violation(outcomes):
    outcome = outcomes[OCCLUDED]
    assert not any(r.sees_person for r in outcome.readings)
    reported = outcome.times >= SCANNER.response_time  # before: held still, as at power-up
    assert np.all(outcome.signals_named("scale")[reported] == 1.0), "slowed for no one it saw"
    totals = outcome.status.totals
    assert totals.violations >= 1 and totals.robot_contacts >= 1
    config = outcome.config
    model = reference_model(config, StopModel.of_variant(VARIANT), COMMAND_LATENCY)
    margin = margin_metrics(
        log_of(outcome.signals),
        model,
        config.moving_speed,
        totals.contact_records,
        outcome.part_names,
    )
    assert margin["violation"] and margin["value"] < -1.0


def test_a_light_curtain_stops_the_robot_only_while_it_is_crossed(outcomes):
    """It reports the person while they cross it (walking in and out) and knows nothing of
    them behind it: the robot stops while a beam is interrupted and runs on beside the
    person once they are through, which the margin, judged on the real body, shows. S_p at
    the curtain holds its C = 8 (30 − 14) mm and its response time (ISO 13855's 2.0 m/s
    where S_p is at most 0.5 m)."""
    outcome = outcomes[CURTAIN]
    path = outcome.case.person
    crossing = [r for r in outcome.readings if r.sees_person]
    assert crossing, "the curtain never saw the person cross"
    plane = LIGHT_CURTAIN.ends[0][1]
    for reading in crossing:
        y = path.value(reading.time)[1, 0]  # the person's base y (plant position 1)
        assert abs(y - plane) < 0.5, f"seen at y = {y:.2f} m, away from the curtain"
    seen = outcome.signals_named("seen") > 0
    assert np.all(outcome.signals_named("scale")[seen] == 0.0)
    assert outcome.signals_named("scale")[~seen][-100:].min() == 1.0
    assert outcome.status.totals.violations >= 1
    speeds, times, kappa = worst_stopping_times(VARIANT)
    rate = outcome.signals_named("path_rate")[seen]
    v_r = outcome.signals_named("robot_speed")[seen]
    t_s = np.where(rate > 0.0, np.interp(rate, speeds, times), 0.0)
    t_r = 0.02 + outcome.config.period + COMMAND_LATENCY
    robot = v_r * t_r + kappa * v_r * t_s + 8 * (0.030 - 0.014) + 0.02
    near = 2.0 * (t_r + t_s) + robot
    expected = np.where(near <= 0.5, near, np.maximum(1.6 * (t_r + t_s) + robot, 0.5))
    np.testing.assert_allclose(outcome.signals_named("sensed_protective")[seen], expected)


@pytest.mark.parametrize("kind", CASES)
def test_independent_recomputation_agrees(kind, outcomes):
    """The real body's separation, speeds and S_p (with the scanner's response time in
    T_r) from the trajectories alone."""
    assert_recomputation_agrees(outcomes[kind])
