"""A person walking where the robot stands still, or holds something still, over the floor
goes round it, as a person does round a carton hanging from a stopped gripper (a user's
palletizing cell: the pelvis 16.6 cm in it) or a stopped arm; and turning where objects
stand, keeps the arms out of them. The body's overlap with a carton is measured in
SceneGraph; with the robot, by the run's safety monitor."""

from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
from pydrake.math import RigidTransform

from hrc_drake.evaluation.realism import realism_verdict
from hrc_drake.human.messages import Box, InTheWayCommand, MoveCommand
from hrc_drake.runner import run
from hrc_drake.scenario import load_scenario
from hrc_drake.scenario.overrides import overridden
from tests.human.scene import FLOOR, Run, furniture
from tests.human.test_actor import STANCE_SLIP, _stance_slip

CARTON = Box((0.6, 0.0, 1.0), 0.0, (0.3, 0.4, 0.25), "carton 1 the robot holds")
"""A carton at chest height over the middle of the walk from (-1.5, 0) to (2.5, 0)."""
GOAL = (2.5, 0.0, 0.0)


def _walk(schedule, cell=(FLOOR,), until=9.0) -> Run:
    carton = (CARTON.size, RigidTransform(list(CARTON.center)))
    run = Run(schedule, start_pose=(-1.5, 0.0, 0.0), cell=cell, objects=[carton])
    run.record(until)
    return run


def test_a_walk_past_a_carton_the_robot_holds_still_goes_round_it():
    run = _walk([(0.1, MoveCommand(1, GOAL, in_the_way=(CARTON,)))])
    assert run.overlap[0] <= 0.01, run.overlap
    status = run.status()
    assert status.results.outcome_of(1) == "succeeded"
    assert np.hypot(*np.subtract(status.base_pose[:2], GOAL[:2])) < 0.05


def test_a_walk_under_way_goes_round_a_carton_that_comes_to_rest_in_its_way():
    move = MoveCommand(1, GOAL)
    run = _walk([(0.1, move), (1.0, (move, InTheWayCommand(2, (CARTON,))))])
    assert run.overlap[0] <= 0.01, run.overlap
    status = run.status()
    assert status.results.outcome_of(1) == "succeeded"
    assert np.hypot(*np.subtract(status.base_pose[:2], GOAL[:2])) < 0.05


LANDED = 0.006
"""m: a foot comes down on its step within this of it, round the curves of a walk round
the robot too (a heel came down 1.0 cm short of it, the audit's limit)."""


def test_a_walk_told_twice_that_the_robot_came_to_rest_in_its_way_stops_once_on_its_feet():
    """The robot's boxes change as it comes to rest (a second message 50 ms after the first):
    the walk already coming to a stop goes on stopping as it was; stopped again on a new
    profile, its pelvis jumped and a landed foot slid 2.6 cm."""
    move = MoveCommand(1, GOAL)
    moved = replace(CARTON, center=(0.62, 0.0, 1.0))
    told = (move, InTheWayCommand(2, (CARTON,)))
    carton = (CARTON.size, RigidTransform(list(CARTON.center)))
    run = Run(
        [(0.1, move), (1.0, told), (1.05, (*told, InTheWayCommand(3, (moved,))))],
        start_pose=(-1.5, 0.0, 0.0),
        cell=(FLOOR,),
        objects=[carton],
    )
    _, stopping = run.record(3.0)
    assert _stance_slip(run.body, stopping) < STANCE_SLIP
    _, going_round = run.record(9.0)
    assert run.overlap[0] <= 0.01, run.overlap
    assert run.status().results.outcome_of(1) == "succeeded"
    assert _stance_slip(run.body, going_round) < LANDED


def test_a_carton_at_rest_off_the_way_leaves_the_walk_as_it_was():
    aside = Box((0.6, 1.5, 1.0), 0.0, (0.3, 0.4, 0.25), "carton 2 the robot holds")
    move = MoveCommand(1, GOAL)
    told = _walk([(0.1, move), (1.0, (move, InTheWayCommand(2, (aside,))))], until=3.0)
    alone = _walk([(0.1, move)], until=3.0)
    assert told.positions() == pytest.approx(alone.positions())


def test_a_carton_at_rest_in_a_corridor_with_no_way_round_stops_the_walk_and_fails_it():
    """In a corridor of fences 1.2 m wide, closed beyond the goal, the carton leaves no way
    past: the person stops short of it, and the walk fails saying what is in the way."""
    sides = [furniture("fence", x, y) for x in (-1.0, 1.0, 3.0) for y in (-0.6, 0.6)]
    cell = (FLOOR, *sides, furniture("fence", 4.0, 0.0, 90.0))
    move = MoveCommand(1, GOAL)
    run = _walk([(0.1, move), (0.6, (move, InTheWayCommand(2, (CARTON,))))], cell=cell)
    assert run.overlap[0] <= 0.01, run.overlap
    result = run.status().results.result_of(1)
    assert (result.outcome, run.status().state) == ("failed", "IDLE")
    assert "'carton 1 the robot holds' in the way" in result.reason


PAST_THE_GRIPPER = Path(__file__).resolve().parent / "cells" / "past_the_gripper" / "cell.yaml"


@pytest.mark.parametrize(
    "wait", ["16500", "14000"], ids=["at rest before the walk", "coming to rest 1.4 m ahead"]
)
def test_a_person_walks_round_a_carton_the_robot_holds_where_they_would_stand(wait):
    """A user's palletizing cell, cut down: the robot takes a carton off the belt's end and
    holds it still where the person walks to stand (no speed and separation monitoring, so
    it stays there). The person walked into it, the abdomen 19.7 cm in it, whether the
    robot was at rest before the walk began or came to rest during it; now the walk goes
    round it to the nearest place with room, within the audit's limits. The robot lifts the
    carton straight off the belt before it swings it over (swung at once, it dragged the
    carton 1.4 cm through the belt, which the audit measures since it looks at what the
    robot holds), and so comes to rest 1.5 s later, at 15.5 s."""
    scenario = overridden(load_scenario(PAST_THE_GRIPPER), [("parameters.wait_msec", wait)])
    report = run(scenario)
    walk = report.metrics["bt"]["human"]["ActorMovement::3"]
    assert (walk["successes"], walk["failures"]) == (1, 0), walk
    verdict = realism_verdict(report.metrics["realism"])[0]
    assert verdict.startswith("within its limits"), verdict


ROUND_THE_ARM = Path(__file__).resolve().parent / "cells" / "round_the_arm" / "cell.yaml"


@pytest.mark.parametrize(
    "wait", ["6000", "3000"], ids=["at rest before the walk", "coming to rest during it"]
)
def test_a_person_walks_round_the_robots_arm_at_rest(wait):
    """The robot stands still with its arm stretched out 1.05 m over the floor (no speed and
    separation monitoring, so it stays there) where the person walks past: the chest went
    16.8 cm into link_5, 13 contacts with the robot at rest. The walk goes round the arm."""
    scenario = overridden(load_scenario(ROUND_THE_ARM), [("parameters.wait_msec", wait)])
    report = run(scenario)
    walk = report.metrics["bt"]["human"]["ActorMovement::3"]
    assert (walk["successes"], walk["failures"]) == (1, 0), walk
    contacts = report.metrics["safety"]["contacts"]
    assert contacts["count"] == 0, contacts
    assert report.metrics["safety"]["min_separation"]["distance"] > 0.03


TURN_FROM_THE_CART = Path(__file__).resolve().parent / "cells" / "turn_from_the_cart" / "cell.yaml"


def test_turning_away_from_a_box_just_put_down_keeps_the_hand_out_of_it():
    """A user's hand-over cell, cut down: a KLT carried to a cart and put down at its edge;
    turning to walk off, the free hand swung 1.16 cm into it (the walk's turn kept the arms
    out of the cart, not of what stands on it)."""
    report = run(load_scenario(TURN_FROM_THE_CART))
    walk = report.metrics["bt"]["human"]["ActorMovement::6"]
    assert (walk["successes"], walk["failures"]) == (1, 0), walk
    verdict = realism_verdict(report.metrics["realism"])[0]
    assert verdict.startswith("within its limits"), verdict
