"""A walk's closing step: the foot it brings beside the other rolls only as far as that
short step needs (#26: a user's KLT rack)."""

from hrc_drake.evaluation.realism import LIMITS
from hrc_drake.runner import run
from hrc_drake.scenario import load_scenario
from tests.human.user_cells import copied
from tests.scenarios.realism_checks import assert_within_the_audit_limits


def test_a_tall_man_arriving_before_a_klt_keeps_his_thigh_out_of_it(tmp_path):
    """A 95th-percentile man walks to a place 0.36 m in front of a KLT on a rack's 0.5 m
    board: the place has room to stand and turn, yet on the walk's last step, a 4 cm step
    closing his feet after the pelvis had stopped, his heel rose as in a full stride and
    threw the knee 31 cm ahead of the pelvis: the thigh went 3.1 cm into the KLT. He now
    arrives, keeping out of it within the audit's limits."""
    report = run(load_scenario(copied("klt_at_the_knee", tmp_path)))
    walk = report.metrics["bt"]["human"]["ActorMovement::2"]
    assert walk["successes"] == 1, walk
    realism = report.metrics["realism"]
    assert realism["penetration_objects"]["max"] <= LIMITS["penetration_objects"], realism
    assert_within_the_audit_limits(realism)
