"""A free-space move keeps the robot, and what it holds, out of the objects resting in the cell,
but not out of those it works on at its ends: what it takes or sets down, what it has just let
go.

The checks are made outside the planner: the part's corners along the planned path against the
object's outline and top, and, in a run, the realism audit's depth of what the robot holds."""

import json
from pathlib import Path

import numpy as np
import pytest
from pydrake.math import RigidTransform

from hrc_drake.motion.errors import PlanningFailed
from hrc_drake.motion.messages import MoveLinear, MoveTo
from hrc_drake.motion.model import RestingObject
from hrc_drake.motion.options import MotionOptions
from hrc_drake.motion.planner import MotionPlanner
from hrc_drake.workpieces.geometry import Solid
from tests.motion.motion_helpers import build_station, make_scenario
from tests.motion.test_held_part import (
    BOX_AT,
    BOX_TOP,
    DOWN,
    PART,
    SIZE,
    TABLE_TOP,
    VARIANT,
    lowest_over_the_box,
    posture,
)

CRATE = RestingObject(
    Solid("box", (0.2, 0.3, BOX_TOP - TABLE_TOP)),
    RigidTransform([BOX_AT[0], BOX_AT[1], (BOX_TOP + TABLE_TOP) / 2]),
    "crate 2",
)
"""A crate resting on the table where test_held_part's cell has its box (same outline)."""
CELLS = Path(__file__).parent / "cells"


@pytest.fixture(scope="module")
def planner():
    return build_station(make_scenario(VARIANT)).motion.planner


def test_a_held_part_is_carried_over_a_resting_crate(planner):
    start, target = posture(planner, -0.35, 1.3), RigidTransform(DOWN, [0.35, BOX_AT[1], 1.3])
    blind = planner.plan(MoveTo(seq=1, pose=target), start, held=PART)
    assert lowest_over_the_box(planner, blind) < BOX_TOP - 0.03, "the straight move must clip it"

    seen = planner.plan(MoveTo(seq=1, pose=target), start, held=PART, objects=(CRATE,))
    assert lowest_over_the_box(planner, seen) > BOX_TOP
    end = planner.model.tool_pose(seen.end).translation()
    assert np.linalg.norm(end - target.translation()) < 1e-3


def test_the_robot_sets_a_part_down_on_a_crate_and_leaves_it(planner):
    """The crate is touched at the move's end (the part set on it) and at the next move's
    start: both plan, and each ends where it was sent."""
    start = posture(planner, -0.35, 1.3)
    on_the_crate = RigidTransform(DOWN, [BOX_AT[0], BOX_AT[1], BOX_TOP + SIZE[2]])
    put = planner.plan(MoveTo(seq=1, pose=on_the_crate), start, held=PART, objects=(CRATE,))
    assert planner.model.tool_pose(put.end).translation() == pytest.approx(
        on_the_crate.translation(), abs=1e-3
    )
    away = RigidTransform(DOWN, [0.35, BOX_AT[1], 1.3])
    left = planner.plan(MoveTo(seq=2, pose=away), put.end, objects=(CRATE,))
    assert planner.model.tool_pose(left.end).translation() == pytest.approx(
        away.translation(), abs=1e-3
    )


def test_a_target_that_puts_the_held_part_into_a_crate_is_refused(planner):
    """What the robot touches where it stops is what it works on, but 5 cm deep in is a
    target in the crate, not on it: the plan fails and names the crate."""
    start = posture(planner, -0.35, 1.3)
    into = RigidTransform(DOWN, [BOX_AT[0], BOX_AT[1], BOX_TOP + SIZE[2] - 0.05])
    with pytest.raises(PlanningFailed, match="would be 5.0 cm into crate 2 resting there"):
        planner.plan(MoveTo(seq=1, pose=into), start, held=PART, objects=(CRATE,))


def test_a_linear_set_down_ends_on_the_crate_not_in_it(planner):
    """A RobotMoveLinear sets the part down on the crate's top (touching it) as the tree
    tells it; one 5 cm lower would leave it in the crate (a user's tree set a part 4.5 cm
    into the one lying on the table, and the run let it): refused, naming the crate."""
    start = posture(planner, *BOX_AT[:1], BOX_TOP + SIZE[2] + 0.05)
    on_it = RigidTransform(DOWN, [BOX_AT[0], BOX_AT[1], BOX_TOP + SIZE[2]])
    put = planner.plan(MoveLinear(seq=1, pose=on_it), start, held=PART, objects=(CRATE,))
    assert planner.model.tool_pose(put.end).translation() == pytest.approx(
        on_it.translation(), abs=1e-3
    )
    into = RigidTransform(DOWN, [BOX_AT[0], BOX_AT[1], BOX_TOP + SIZE[2] - 0.05])
    with pytest.raises(PlanningFailed, match="would be 5.0 cm into crate 2 resting there"):
        planner.plan(MoveLinear(seq=2, pose=into), start, held=PART, objects=(CRATE,))


def test_a_move_the_objects_block_says_they_are_why(planner):
    """With a search too small to go round the crate, the failure names the objects: the
    same move among the cell alone is the straight line."""
    tight = MotionPlanner(planner.station, MotionOptions(search_nodes=2), planner.seed)
    start, target = posture(planner, -0.35, 1.3), RigidTransform(DOWN, [0.35, BOX_AT[1], 1.3])
    assert tight.plan(MoveTo(seq=1, pose=target), start, held=PART) is not None
    with pytest.raises(PlanningFailed, match="out of the objects resting in the cell"):
        tight.plan(MoveTo(seq=1, pose=target), start, held=PART, objects=(CRATE,))


def test_a_part_lifted_5_cm_is_swung_over_the_taller_crate_beside_it(tmp_path, hrc_drake):
    """A user's tree lifts a part 5 cm and swings it past a 25 cm crate: the run carried it
    15 cm deep through the crate, and the audit said so. Now it goes over, and is set down."""
    status, _, err = hrc_drake(
        "run", CELLS / "swing_past_objects" / "cell.yaml", "--out", tmp_path / "run"
    )
    assert status == 0, err
    report = json.loads((tmp_path / "run" / "report.json").read_text())
    assert report["realism"]["penetration_carried"]["max"] <= 0.01
    assert report["bt"]["robot"]["RobotRelease::8"]["successes"] == 1


def test_a_carton_is_turned_to_fit_beside_its_neighbour(tmp_path, hrc_drake):
    """A user's palletizing cell: the slot beside a carton has no rotation, so the tool may
    turn about its axis. Turned the way nearest its posture, the robot set the carton down
    4.5 cm into its neighbour (the audit: carton 1 in carton 2). Now it is turned to fit,
    and set down touching it."""
    cell = CELLS / "carton_beside_carton" / "cell.yaml"
    status, _, err = hrc_drake("run", cell, "--out", tmp_path / "run")
    assert status == 0, err
    report = json.loads((tmp_path / "run" / "report.json").read_text())
    assert report["realism"]["penetration_carried"]["max"] <= 0.01
    assert report["bt"]["robot"]["RobotRelease::13"]["successes"] == 1


def test_a_linear_set_down_onto_a_part_lying_there_is_refused(tmp_path, hrc_drake):
    """A user's tree sets its part down with a RobotMoveLinear 4.5 cm too low, where another
    part lies: the run set it 4.5 cm into that part (the audit: part 1 in part 2). Now the
    move is refused, naming the part, and nothing goes into anything."""
    cell = CELLS / "set_down_into_a_part" / "cell.yaml"
    status, _, err = hrc_drake("run", cell, "--out", tmp_path / "run")
    assert status == 0, err
    report = json.loads((tmp_path / "run" / "report.json").read_text())
    assert report["realism"]["penetration_carried"]["max"] <= 0.01
    put = report["bt"]["robot"]["RobotMoveLinear::7"]
    assert put["first_failure"] == (
        "failed: at the target the robot (or the part it holds) would be 4.5 cm into part 2 "
        "resting there (limit 1 cm): move or turn the target"
    )
