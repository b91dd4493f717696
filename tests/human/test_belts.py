"""The person and a running belt: what the palms set down on it waits for them to leave its
way, and a pick of what it carries is refused at once, saying where to take it instead
(`validate` says so before the run where the belt carries what the pick finds off)."""

from pathlib import Path

from hrc_drake.runner import run
from hrc_drake.scenario import load_scenario
from hrc_drake.scenario.findings import findings
from tests.scenarios.realism_checks import assert_within_the_audit_limits

CELLS = Path(__file__).resolve().parent / "cells"
IN_THE_CARTON = 0.003
"""m: how far a hand may go into a carton (the audit allows 1 cm; none is meant)."""


def _node(report, name: str) -> dict:
    return report.metrics["bt"]["human"][name]


def test_a_carton_set_down_on_a_running_belt_waits_for_the_palms_to_leave_its_way():
    """A user's palletizing cell, cut down: the carton taken off a queueing belt's end and
    set down 0.35 m upstream on the running belt, a palm on each of its faces along the
    belt. Set off at once, it ran into the palm ahead of it as the hands opened: 5.2 cm in
    (the user's cell). It stays until the palms are out of its way."""
    report = run(load_scenario(CELLS / "belt_put_down" / "cell.yaml"), duration=5.0)
    for node in ("ActorPick::2", "ActorPlace::3"):
        assert (_node(report, node)["successes"], _node(report, node)["failures"]) == (1, 0)
    realism = report.metrics["realism"]
    assert_within_the_audit_limits(realism)
    assert realism["penetration_objects"]["max"] <= IN_THE_CARTON, realism["penetration_objects"]


def test_a_pick_of_a_carton_riding_up_a_queueing_belt_is_refused_saying_where_it_rests():
    """The carton rides up the belt to its end, 1.35 m on. The pick aimed where it was
    when it started, and the belt carried the carton into the palm: 14.4 cm in at 0.9 s
    (the user's cell). Refused at once, the hands go nowhere near it."""
    report = run(load_scenario(CELLS / "belt_pick_moving" / "cell.yaml"), duration=1.5)
    pick = _node(report, "ActorPick::2")
    rests = "take it where the belt brings it to rest, at (0.05, 0.55, 0.92)"
    assert pick["successes"] == 0, pick
    assert pick["first_failure"] == f"carton 1 is moving on belt 'infeed' at 0.20 m/s: {rests}"
    assert report.metrics["realism"]["penetration_objects"]["max"] == 0.0


def test_validate_says_a_pick_finds_what_a_belt_carries_off_and_the_run_refuses_it():
    """The pick takes what a NextObject finds in an area on a belt that carries its
    objects off its end: it is moving whenever found. `validate` says so at the pick (it
    said ok), not when the area reaches beyond the belt, and the run refuses the pick when
    it starts."""
    cell = CELLS / "belt_carried_off" / "cell.yaml"
    scenario = load_scenario(cell)
    (said,) = [f for f in findings(scenario, cell) if "belt" in f.message]
    assert said.where == "tree 'Human', node 'ActorPick::3', port 'object_id'"
    assert "area 'on_the_belt', which lies on belt 'infeed'" in said.message
    assert "(at_end: queue)" in said.message
    scenario.areas["on_the_belt"] = [[-1.7, 0.3], [0.2, 0.3], [0.2, 1.6], [-1.7, 1.6]]
    assert not [f for f in findings(scenario, cell) if "belt" in f.message]  # the floor too
    pick = _node(run(load_scenario(cell), duration=0.3), "ActorPick::3")
    assert pick["successes"] == 0, pick
    assert pick["first_failure"].endswith(
        "which carries it off: take it before it goes on the "
        "belt, or have the belt queue what it carries "
        "(at_end: queue) and take it where it comes to rest"
    )
