"""Walking round the cell: the navigation map, its paths, places to stand, `validate`.

The walks near furniture are judged in the world (tests/human/cell_walks.py): planned as
the person plans them, posed at the person's update rate, the body's collision geometry
against the bundled furniture models in Drake's SceneGraph, at most the realism audit's
penetration limit (1 cm) deep.
"""

import math
import shutil
from pathlib import Path

import numpy as np
import pytest
from shapely.geometry import LineString, MultiPoint, Point, box
from shapely.ops import nearest_points

from hrc_drake.cli import main
from hrc_drake.evaluation.realism import LIMITS
from hrc_drake.human.aiming import Unreachable
from hrc_drake.human.body import human_body
from hrc_drake.human.clip import load_clips
from hrc_drake.human.grasp import carry_arms, held_corners
from hrc_drake.human.messages import Hold, MoveCommand
from hrc_drake.human.navigation import NavigationMap, Obstacle
from hrc_drake.human.performer import IDLE_CLIP, Performer, place
from hrc_drake.human.planning import plan_movement, plan_stop
from hrc_drake.human.segments import StepBackSegment, TurnSegment
from tests.human.cell_walks import Cell, Furniture
from tests.human.scene import FLOOR, Run, furniture
from tests.human.test_actor import _stance_slip

REPO = Path(__file__).resolve().parents[2]
TABLE = Obstacle("table", box(-0.6, -0.4, 0.6, 0.4), 0.0, 0.9)
LIMIT = LIMITS["penetration_static"]
TABLE_MODEL = furniture("work_table", 0.0, 0.55)


def test_a_walk_goes_round_a_table_with_the_bodys_clearance():
    nav = NavigationMap([TABLE])
    start, goal = (-2.0, 0.1), (2.0, -0.1)
    path = [start, *nav.path(start, goal), goal]
    assert len(path) > 2, "the straight line crosses the table"
    walk = LineString(path)
    clearance = nav.clearance(TABLE)
    assert walk.distance(TABLE.outline) >= clearance - 1e-6
    assert walk.length < 4.0 + 2 * clearance + 1.2  # round the near side, not far away


def test_a_clear_line_is_walked_straight():
    nav = NavigationMap([TABLE])
    assert nav.path((-2.0, 1.5), (2.0, 1.5)) == []


def test_a_spot_between_two_tables_is_left_along_the_gap_not_over_a_table():
    belt = Obstacle("belt", box(-1.0, -1.0, 1.0, -0.6), 0.0, 0.9)
    nav = NavigationMap([TABLE, belt])
    spot, goal = (0.0, -0.5), (0.0, -2.5)
    path = [spot, *nav.path(spot, goal), goal]
    assert not LineString(path).crosses(belt.outline) and len(path) > 3


def test_a_walk_keeps_out_of_the_robots_inner_space():
    nav = NavigationMap([], keep_out=[LineString([(0, 0), (0, 0.001)]).buffer(0.6)])
    path = [(-2.0, 0.0), *nav.path((-2.0, 0.0), (2.0, 0.0)), (2.0, 0.0)]
    assert LineString(path).distance(LineString([(0, 0), (0, 0.001)])) >= 0.6


@pytest.fixture(scope="module")
def tray_and_work_table() -> Cell:
    """The user's cell of the issue: a side table with a tray, a work table beyond it."""
    return Cell(
        [
            Furniture("tray_table", "side_table", 0.0, 0.0),
            Furniture("work_table", "work_table", 1.4, -1.0),
        ]
    )


ACROSS_THE_WORK_TABLE = (1.4, -1.8, 90.0)
"""A place to stand beyond the work table: the straight line there crosses it."""


def test_a_walk_from_a_place_on_the_clearance_line_goes_round_the_table(tray_and_work_table):
    """The user's case: a place to stand exactly on the navigation map's clearance line of
    the tray table; the walk from there to the work table's far side went straight through
    the work table."""
    cell = tray_and_work_table
    on_line = nearest_points(cell.navigation.blocked.exterior, Point(0.6, 0.0))[0]
    worst = cell.walks((on_line.x, on_line.y, 180.0), ACROSS_THE_WORK_TABLE)
    assert worst.depth <= LIMIT, worst


def test_a_walk_from_a_place_inside_the_clearance_keeps_the_body_out(tray_and_work_table):
    """The nearest place with room at the tray table lies inside its clearance (a person
    needs less room to stand and turn than to walk past); the walk from there keeps out."""
    cell = tray_and_work_table
    x, y = cell.navigation.clear_spot(0.45, 0.0, math.pi)
    assert not cell.navigation.free((x, y))
    worst = cell.walks((x, y, 180.0), ACROSS_THE_WORK_TABLE)
    assert worst.depth <= LIMIT, worst


def test_a_place_to_stand_inside_the_clearance_is_reached_and_left_clear(tray_and_work_table):
    """A place to stand 0.15 m from the tray table: the person walks there (to the nearest
    place with room), turns and walks on without touching either table."""
    worst = tray_and_work_table.walks((-1.5, -1.0, 0.0), (0.55, 0.0, 180.0), ACROSS_THE_WORK_TABLE)
    assert worst.depth <= LIMIT, worst


def test_a_walk_does_not_squeeze_between_tables_whose_clearances_overlap():
    """Two tables 0.62 m apart: the person's arms would brush both; the walk goes round."""
    cell = Cell(
        [
            Furniture("left_table", "side_table", 0.0, 0.0),
            Furniture("right_table", "side_table", 0.0, 1.22),
        ]
    )
    worst = cell.walks((-1.5, 0.61, 0.0), (1.5, 0.61, 0.0))
    assert worst.depth <= LIMIT, worst


def test_a_place_to_stand_in_a_gap_narrower_than_the_body_is_not_walked_into():
    """Between a pallet and a belt 0.36 m apart no place has room: the walk there is
    refused with the reason, rather than walked into the belt."""
    cell = Cell(
        [
            Furniture("pallet", "euro_pallet", 0.0, 0.0),
            Furniture("belt", "conveyor", 0.0, -1.0),
        ]
    )
    with pytest.raises(Unreachable, match="into (belt|pallet)"):
        cell.walks((2.0, -0.6, 180.0), (0.0, -0.58, 90.0))


def test_a_place_faced_far_off_the_way_there_is_turned_to_without_sliding_a_foot():
    """Arriving at full pace at a place that faces 57 degrees off the last leg (the walk
    back to the work table in collaboration), the person turns on the spot rather than
    over the closing steps, which slid a foot 5 cm."""
    performer = Performer(human_body(), load_clips())
    half = math.radians(57.0) / 2
    command = MoveCommand(1, (3.3, 0.0, 0.0), (math.cos(half), 0.0, 0.0, math.sin(half)))
    activity = plan_movement(performer, command, (0.0, 0.0, 0.0), 0.0)
    poses = [activity.pose(performer, t) for t in np.arange(0.0, activity.end, 1 / 60)]
    assert _stance_slip(performer.body, poses) < LIMITS["foot_slip"]


@pytest.mark.parametrize(
    ("start", "goal"),
    [((0.0, 0.0, 0.0), (1.2, 1.2, 0.0)), ((0.0, 0.0, 90.0), (1.0, -1.2, -90.0))],
    ids=["turning to its place over the last steps", "setting off after a half turn"],
)
def test_a_walk_that_turns_keeps_the_feet_above_the_floor(start, goal):
    """A foot swung round a turn lands rolled (the leg gives the foot its roll): the edge
    of its sole went 1.1-1.2 cm into the floor as the heel came down."""
    cell = Cell([Furniture("floor", "floor", 0.0, 0.0)])
    assert cell.walks(start, goal).depth <= LIMIT


@pytest.mark.parametrize(
    ("start", "goal"),
    [((-1.2, -0.3, 0.0), (1.2, 1.3)), ((-1.2, 0.55, 0.0), (1.2, 0.55))],
    ids=["round a corner", "along its long side"],
)
def test_a_carton_carried_past_a_table_stays_out_of_it(start, goal):
    """A carton in both hands is carried at the height of a table's top (its bottom
    0.87-0.92 m, the top 0.86-0.90 m) and 0.4 m in front of the belly: only the walk's room
    round the table keeps it from going into the top. Carried round our work table model
    (its top covers x -0.6..0.6, y 0.15..0.95), its footprint stays off the top's."""
    carton = Hold("both", (0.4, 0.3, 0.2))
    run = Run([(0.1, MoveCommand(1, goal, hold=carton))], start, [FLOOR, TABLE_MODEL])
    _, poses = run.record(9.0)
    carry = carry_arms(run.body, carton)
    top = box(-0.6, 0.15, 0.6, 0.95)
    footprints = [MultiPoint(held_corners(run.body, carry, q)[:, :2]).convex_hull for q in poses]
    assert run.status().results.outcome_of(1) == "succeeded"
    assert min(top.distance(footprint) for footprint in footprints) > 0.0


@pytest.mark.parametrize("goal", [(0.0, 1.4), (0.0, 0.4)], ids=["turning right", "turning left"])
def test_a_tote_taken_off_a_rack_stays_out_of_it_as_the_person_turns_away(goal):
    """A user's cell: a tote (0.26 m deep, 0.36 m across) taken off a rack's 1.1 m board
    (our shelf model, its front 0.4 m ahead of the person) and carried away behind the
    person. Turned on the spot where it was taken, the tote held in front swept 2.5 cm into
    the rack's upright (the realism audit's figure in the user's run, and here turning
    right). The person steps back from the rack first: the tote keeps out of it all along,
    measured in SceneGraph as the audit measures a carried object."""
    tote = (0.26, 0.36, 0.12)
    rack = Furniture("rack", "shelf", -1.5, 0.9, 90.0)
    cell = Cell([Furniture("floor", "floor", 0.0, 0.0), rack], held=tote)
    carried = cell.carries((-0.9, 0.9, 180.0), goal, Hold("both", tote))
    assert carried.depth <= LIMIT, carried


def test_a_tote_taken_off_a_rack_with_no_room_to_step_back_is_not_carried_off():
    """The rack of the test above with a table 0.3 m behind the person: stepping back, the
    person would turn with the table at their back; turned where they stand, the tote would
    sweep into the rack. The carry fails at once, saying where."""
    tote = Hold("both", (0.26, 0.36, 0.12))
    rack = Furniture("rack", "shelf", -1.5, 0.9, 90.0)
    cell = Cell([rack, Furniture("table", "side_table", -0.3, 0.9, 90.0)])
    command = MoveCommand(1, (0.0, 1.4, 0.0), hold=tote)
    with pytest.raises(Unreachable, match="into 'rack' at the walk's start .turning on the spot"):
        plan_movement(cell.performer, command, (-0.9, 0.9, math.pi), 0.0)


def test_a_step_back_keeps_its_feet_planted_and_a_cancel_finishes_it():
    """Stepping back from the rack (the test above), each foot stays where it stands until
    it steps; cancelled under way, the two steps end where they would have."""
    tote = Hold("both", (0.26, 0.36, 0.12))
    cell = Cell([Furniture("rack", "shelf", -1.5, 0.9, 90.0)])
    performer, start = cell.performer, (-0.9, 0.9, math.pi)
    activity = plan_movement(performer, MoveCommand(1, (0.0, 1.4, 0.0), hold=tote), start, 0.0)
    step = activity.segments[0]
    assert isinstance(step, StepBackSegment)
    times = np.arange(0.0, step.end(performer), 1 / 60)
    assert _stance_slip(performer.body, [step.pose(performer, t) for t in times]) < 0.002
    stop = plan_stop(performer, activity, start, tote, 0.3)
    assert stop.final_pose == pytest.approx((*step.end_position, math.pi))
    assert stop.segments[0] is step


def _standing_and_turning(cell: Cell, x: float, y: float, yaw: float) -> float:
    """The deepest penetration in the world while a person stands at (x, y) facing yaw
    (the idle clip) and steps round by a quarter either way and a half turn."""
    performer, worst = cell.performer, 0.0
    idle = performer.clips[IDLE_CLIP]
    for t in np.arange(0.0, idle.duration, 1 / 30):
        q = place(performer, idle.sample(t), x, y, yaw)
        worst = max(worst, cell.penetration(q).depth)
    for turn in (math.pi / 2, -math.pi / 2, math.pi):
        segment = TurnSegment.between(performer, 0.0, (x, y), yaw, yaw + turn)
        for t in np.arange(0.0, segment.end(performer), 1 / 30):
            worst = max(worst, cell.penetration(segment.pose(performer, t)).depth)
    return worst


def test_a_place_to_stand_works_exactly_where_the_body_keeps_out_of_the_furniture():
    """The predicate against the world: at places in front of and beside a work table and
    a pallet, a place that works keeps every body part out standing and stepping round,
    and a place it refuses by more than 4 cm does put one in."""
    cell = Cell(
        [
            Furniture("bench", "work_table", 0.0, 0.0),
            Furniture("pallet", "euro_pallet", 2.0, 0.0),
        ]
    )
    for d in (0.1, 0.2, 0.3, 0.36):
        for x, y, yaw in ((0.0, -0.4 - d, math.pi / 2), (0.6 + d, 0.0, 0.0), (2.0, -0.4 - d, 0.0)):
            problem = cell.navigation.stand_problem(x, y, yaw)
            world = _standing_and_turning(cell, x, y, yaw)
            if problem is None:
                assert world <= LIMIT, (x, y, yaw, world)
            elif problem.depth > 0.04:
                assert world > LIMIT, (x, y, yaw, problem, world)


def test_a_place_to_stand_says_what_it_reaches_into_and_how_far():
    nav = NavigationMap([TABLE])
    facing_table = math.pi / 2
    problem = nav.stand_problem(0.0, -0.5, facing_table)
    assert (problem.what, problem.doing) == ("table", "turning on the spot")
    assert problem.depth == pytest.approx(nav.body[2].turning - 0.1)
    problem = nav.stand_problem(0.0, -0.45, facing_table)
    assert problem.depth == pytest.approx(nav.body[2].turning - 0.05)
    assert nav.stand_problem(0.0, -0.8, facing_table) is None
    assert nav.stand_problem(0.0, -0.8, None) is None


def test_a_place_to_stand_without_room_moves_out_and_one_with_room_stays():
    nav = NavigationMap([TABLE])
    facing_table = math.pi / 2
    x, y = nav.clear_spot(0.0, -0.45, facing_table)
    assert nav.stand_problem(x, y, facing_table) is None and y < -0.45
    assert nav.clear_spot(0.0, -0.8, facing_table) == (0.0, -0.8)


def test_validate_names_the_place_to_stand_that_cannot_work(tmp_path, capsys):
    shutil.copytree(REPO / "trees", tmp_path / "trees")
    (tmp_path / "scenarios").mkdir()
    text = (REPO / "scenarios" / "collaboration.yaml").read_text()
    good = "handover_spot: {translation: [1.4, -0.45, 0.0]"
    assert good in text
    bad = tmp_path / "scenarios" / "collaboration.yaml"
    bad.write_text(text.replace(good, "handover_spot: {translation: [1.4, -0.2, 0.0]"))
    assert main(["validate", str(bad)]) == 2
    error = capsys.readouterr().err.strip()
    line = 1 + text.splitlines().index(
        next(t for t in text.splitlines() if t.strip().startswith("handover_spot:"))
    )
    assert error.startswith(f"hrc-drake: error: {bad}:{line}: locations.handover_spot: ")
    assert "euro_pallet" in error and len(error.splitlines()) == 1
    assert "the nearest place with room to stand and turn is [" in error


def test_a_walk_out_of_a_tight_spot_steps_in_only_at_a_goal_that_needs_it():
    """From between two boxes narrower than the walking body the walk steps out first; the
    goal, 0.3 m from a table and reachable straight from the free floor, is walked to
    straight: it also stepped in to it from the edge of the table's clearance, 8 cm short
    (a person leaving a pallet stacked with cartons stopped there to step the last 3 cm
    into the place at a table, collaboration)."""
    navigation = NavigationMap(
        [
            Obstacle("box_a", box(-0.5, -0.5, -0.25, 0.5), 0.0, 1.0),
            Obstacle("box_b", box(0.25, -0.5, 0.5, 0.5), 0.0, 1.0),
            Obstacle("table", box(-0.5, 2.0, 0.5, 2.8), 0.86, 0.9),
        ]
    )
    (way_out,) = navigation.path((0.0, 0.0), (0.0, 1.7))
    assert way_out == pytest.approx((0.0, 0.787), abs=1e-3)
