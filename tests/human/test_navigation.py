"""Walking round the cell: the navigation map, its paths, places to stand, `validate`."""

import math
import shutil
from pathlib import Path

from shapely.geometry import LineString, box

from hrc_drake.cli import main
from hrc_drake.human.navigation import CLEARANCE, NavigationMap, Obstacle

REPO = Path(__file__).resolve().parents[2]
TABLE = Obstacle("table", box(-0.6, -0.4, 0.6, 0.4), 0.0, 0.9)


def test_a_walk_goes_round_a_table_with_the_bodys_clearance():
    nav = NavigationMap([TABLE])
    start, goal = (-2.0, 0.1), (2.0, -0.1)
    path = [start, *nav.path(start, goal), goal]
    assert len(path) > 2, "the straight line crosses the table"
    walk = LineString(path)
    assert walk.distance(TABLE.outline) >= CLEARANCE - 1e-6
    assert walk.length < 4.0 + 2 * CLEARANCE + 1.2  # round the near side, not far away


def test_a_clear_line_is_walked_straight():
    nav = NavigationMap([TABLE])
    assert nav.path((-2.0, 1.5), (2.0, 1.5)) == []


def test_a_place_to_stand_in_the_table_moves_out_and_a_clear_one_stays():
    nav = NavigationMap([TABLE])
    facing_table = math.pi / 2
    x, y = nav.clear_spot(0.0, -0.45, facing_table)
    assert nav.stands_clear(x, y, facing_table) and y < -0.45
    assert nav.clear_spot(0.0, -0.8, facing_table) == (0.0, -0.8)


def test_a_walk_keeps_out_of_the_robots_inner_space():
    nav = NavigationMap([], keep_out=[LineString([(0, 0), (0, 0.001)]).buffer(0.6)])
    path = [(-2.0, 0.0), *nav.path((-2.0, 0.0), (2.0, 0.0)), (2.0, 0.0)]
    assert LineString(path).distance(LineString([(0, 0), (0, 0.001)])) >= 0.6


def test_validate_names_the_place_to_stand_that_cannot_work(tmp_path, capsys):
    shutil.copytree(REPO / "trees", tmp_path / "trees")
    (tmp_path / "scenarios").mkdir()
    text = (REPO / "scenarios" / "collaboration.yaml").read_text()
    good = "handover_spot: {translation: [1.4, -0.45, 0.0]"
    assert good in text
    bad = tmp_path / "scenarios" / "collaboration.yaml"
    bad.write_text(text.replace(good, "handover_spot: {translation: [1.25, -0.45, 0.0]"))
    assert main(["validate", str(bad)]) == 2
    error = capsys.readouterr().err.strip()
    line = 1 + text.splitlines().index(
        next(t for t in text.splitlines() if t.strip().startswith("handover_spot:"))
    )
    assert error.startswith(f"hrc-drake: error: {bad}:{line}: locations.handover_spot: ")
    assert "euro_pallet" in error and len(error.splitlines()) == 1
