"""Closed-loop proof of speed and separation monitoring: a person walks straight at the
robot at 1.6 m/s while it sweeps at full speed, and reaches in with a hand at 2.0 m/s.

With SSM, in every case the robot stands still before anything touches it, it never moves
while the separation is below S_p, and it resumes once the person has left. Without SSM the
same walk-ins (the hand held in for a whole sweep) end in contacts with the moving robot
and SSM violations. An independent
recomputation from the logged trajectories (tests/safety/recompute.py) agrees with the log
and the report.

The default suite runs a few cases on the iisy 3 R760; `-m long` runs every variant from
eight directions, two start distances, two start times and two places to reach in from.
"""

import itertools

import numpy as np
import pytest

from hrc_drake.iisy import VARIANTS
from tests.safety.recompute import episodes, recompute
from tests.safety.walk_in import STAND, SWEEP_TIME, Case, simulate

BEARINGS = tuple(range(0, 360, 45))
GAPS = (1.25, 2.75)
"""m beyond the variant's reach where the person starts (2.0 and 3.5 m out for the R760)"""
DELAYS = (0.3, 1.7)
"""s: the person sets off early in one sweep and late in it (a sweep takes about 5 s)"""
STANDS = (STAND, 1.0)
"""m from the base axis: inside the sweep (the hand reaches the robot), and just outside"""

SHORT = (
    Case("lbr_iisy3_r760", 90.0, 3.0, 0.5),
    Case("lbr_iisy3_r760", 225.0, 2.0, 1.7),
)
SHORT_WITHOUT_SSM = Case("lbr_iisy3_r760", 90.0, 3.0, 0.5, ssm=False)
LONG = [
    Case(variant, bearing, VARIANTS[variant].reach + gap, delay, stand=stand)
    for variant, bearing, gap, delay, stand in itertools.product(
        sorted(VARIANTS), BEARINGS, GAPS, DELAYS, STANDS
    )
]
LONG_WITHOUT_SSM = [
    Case(variant, bearing, VARIANTS[variant].reach + GAPS[0], 0.3, ssm=False, hold=SWEEP_TIME)
    for variant, bearing in itertools.product(sorted(VARIANTS), BEARINGS)
]
"""The hand stays in for a whole sweep: the arm meets it head-on, not only grazing it (a
grazing touch has no approach speed along the contact normal, so no force)"""


def assert_ssm_holds(outcome) -> None:
    totals = outcome.status.totals
    moving = outcome.signals_named("robot_speed") > outcome.config.moving_speed
    separation = outcome.signals_named("separation")
    protective = outcome.signals_named("protective")
    # the robot was under way (as fast as S_p let it) before the person came near
    far = separation > 1.0
    assert outcome.signals_named("robot_speed")[far].max() > 0.1
    reach = 0.05 if outcome.case.stand <= STAND else 0.4
    assert totals.min_separation < reach, "the person did not come as near as planned"
    # never moving closer than S_p: in the report and at every logged update
    assert totals.violations == 0, totals.violation_episodes[:3]
    assert np.all(separation[moving] >= protective[moving])
    # at rest before anything touched it: every contact is the person's
    assert totals.robot_contacts == 0, [r.worst for r in totals.contact_records][:3]
    assert all(not record.robot_moving for record in totals.contact_records)
    # stopped while the person was near, going again once they left
    assert totals.stopped_time > 0.5
    assert moving[-50:].any(), "the robot did not resume"


def assert_unmonitored_robot_hits(outcome) -> None:
    totals = outcome.status.totals
    assert np.all(outcome.signals_named("scale") == 1.0)
    assert totals.violations >= 1 and totals.worst_deficit > 0.3
    hits = [r for r in totals.contact_records if r.robot_moving]
    assert hits, "the sweeping robot never touched the person"
    assert max(r.worst.force for r in hits) > 50.0


def assert_recomputation_agrees(outcome) -> None:
    """Separation, pair, S_p and violation episodes from the trajectories alone."""
    again = recompute(outcome, outcome.case.variant)
    np.testing.assert_allclose(again.separation, outcome.signals_named("separation"), atol=1e-9)
    parts = [outcome.part_names[int(k)] for k in outcome.signals_named("part")]
    assert again.part == parts
    np.testing.assert_allclose(again.robot_speed, outcome.signals_named("robot_speed"), atol=1e-9)
    np.testing.assert_allclose(
        again.robot_approach, outcome.signals_named("approach_speed"), atol=1e-9
    )
    np.testing.assert_allclose(
        again.human_approach, outcome.signals_named("human_approach"), atol=1e-9
    )
    np.testing.assert_allclose(again.protective, outcome.signals_named("protective"), atol=1e-9)
    logged = outcome.signals_named("violation") > 0.0
    assert np.array_equal(again.violation, logged)
    recomputed = episodes(again.violation, outcome.times)
    reported = [(e.start, e.end) for e in outcome.status.totals.violation_episodes]
    # the report also holds the last update, which no logger sample recorded yet
    assert len(reported) == len(recomputed)
    for (start, end), (r_start, r_end) in zip(recomputed, reported, strict=True):
        assert start == pytest.approx(r_start, abs=1e-9)
        assert end == pytest.approx(r_end, abs=1e-9) or end == outcome.times[-1]


@pytest.fixture(scope="module")
def short_outcomes():
    return {case: simulate(case) for case in (*SHORT, SHORT_WITHOUT_SSM)}


@pytest.mark.parametrize("case", SHORT, ids=lambda c: c.id)
def test_monitored_robot_is_at_rest_before_the_person_reaches_it(case, short_outcomes):
    assert_ssm_holds(short_outcomes[case])


def test_unmonitored_robot_hits_the_person(short_outcomes):
    assert_unmonitored_robot_hits(short_outcomes[SHORT_WITHOUT_SSM])


@pytest.mark.parametrize("case", [SHORT[0], SHORT_WITHOUT_SSM], ids=lambda c: c.id)
def test_independent_recomputation_agrees(case, short_outcomes):
    assert_recomputation_agrees(short_outcomes[case])


@pytest.mark.long
@pytest.mark.parametrize("case", LONG, ids=lambda c: c.id)
def test_walk_in_grid(case):
    outcome = simulate(case)
    assert_ssm_holds(outcome)
    if case.bearing % 90 == 0 and case.delay == DELAYS[0] and case.stand == STAND:
        assert_recomputation_agrees(outcome)


@pytest.mark.long
@pytest.mark.parametrize("case", LONG_WITHOUT_SSM, ids=lambda c: c.id)
def test_walk_in_grid_without_ssm(case):
    outcome = simulate(case)
    assert_unmonitored_robot_hits(outcome)
    if case.bearing % 90 == 0:
        assert_recomputation_agrees(outcome)
