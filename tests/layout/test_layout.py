"""`hrc-drake layout`: the cell from above as a user places things by it. The command writes
PNG and SVG; a mistake validate finds is marked at the point validate names; the reach
shading says what the planner says (a target inside it is reached, one outside it and one
the arm would reach only through the table are not)."""

import xml.etree.ElementTree as ET

import numpy as np
import pytest
from pydrake.math import RigidTransform

from hrc_drake.layout import draw_layout, layout_of
from hrc_drake.layout.reach_map import ReachMapper
from hrc_drake.motion.planner import MotionPlanner
from hrc_drake.motion.reach import reach_problem
from hrc_drake.nodes.robot import TOOL_DOWN
from hrc_drake.runner import run
from hrc_drake.scenario import load_scenario
from hrc_drake.scenario.findings import findings
from hrc_drake.seeding import stream
from hrc_drake.wiring import ROBOT_MOTION
from tests.corpus.test_new_cell import copy_of_the_cell

BELT_OUT_OF_REACH = {
    "cell.yaml": {"belt_place: {translation: [0.5,": "belt_place: {translation: [0.75,"}
}
"""The new user's belt end 0.75 m from the base: validate says the arm reaches 0.55-0.58 m."""
SVG = "{http://www.w3.org/2000/svg}"


@pytest.fixture(scope="module")
def mistaken_cell(tmp_path_factory):
    """The new user's cell with its belt end out of reach (one layout for the module: the
    process keeps what it gathered)."""
    return copy_of_the_cell(tmp_path_factory.mktemp("cell"), BELT_OUT_OF_REACH)


def test_the_command_writes_png_and_svg(tmp_path, mistaken_cell, hrc_drake):
    scenario = mistaken_cell
    for name in ("layout.png", "layout.svg"):
        status, out, err = hrc_drake("layout", scenario, "-o", tmp_path / name)
        assert (status, err) == (0, ""), err
        assert out.splitlines() == [
            str(tmp_path / name),
            "3 findings marked (hrc-drake validate lists them)",
        ]
    assert (tmp_path / "layout.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    svg = ET.parse(tmp_path / "layout.svg").getroot()
    titles = [t.text for t in svg.iter(f"{SVG}text")] + _svg_strings(tmp_path / "layout.svg")
    assert any("my_cell" in (t or "") for t in titles)
    status, _, err = hrc_drake("layout", scenario, "-o", tmp_path / "layout.pdf")
    assert status == 2 and err.count("\n") == 1 and "use a .png, .svg file name" in err


def _svg_strings(path) -> list[str]:
    """Text matplotlib wrote as comments beside its glyph paths."""
    return [line for line in path.read_text().splitlines() if "<!--" in line]


def test_a_finding_is_marked_at_the_point_validate_names(mistaken_cell):
    path = mistaken_cell
    scenario = load_scenario(path)
    found = findings(scenario, path)
    assert found and all(f.point is not None for f in found)
    layout = layout_of(scenario, path)
    assert [str(f) for f in layout.findings] == [str(f) for f in found]
    figure = draw_layout(layout)
    panels = [ax for ax in figure.axes if ax.get_title()]
    for n, finding in enumerate(found, 1):
        marks = [
            line.get_xydata()[0]
            for ax in panels
            for line in ax.lines
            if line.get_gid() == f"finding-{n}"
        ]
        assert len(marks) == len(panels), f"finding {n} is not marked on every panel"
        np.testing.assert_allclose(marks, [finding.point[:2]] * len(panels))
    belt = next(f for f in found if "belt_place' at (0.75, 0.00, 0.90)" in f.message)
    assert belt.point[:2] == pytest.approx((0.75, 0.0))


def test_the_reach_shading_says_what_the_planner_says():
    """getting_started's iisy 3 on its pedestal, its work table from y 0.3 (top 0.9 m)."""
    scenario = load_scenario("getting_started")
    planner = MotionPlanner(
        scenario.station, scenario.robot.motion, stream(scenario.seed, ROBOT_MOTION)
    )
    mapper = ReachMapper(planner)
    above_the_table, into_the_table = mapper.reach_map(0.96), mapper.reach_map(0.85)
    inside, outside, in_the_table = (0.35, -0.2), (0.72, -0.1), (0.0, 0.45)

    def planner_says(xy, z) -> str:
        return reach_problem(planner, RigidTransform(TOOL_DOWN, [*xy, z]), True)

    assert above_the_table.share_at(*inside) > 0.5
    assert planner_says(inside, 0.96) == ""
    assert above_the_table.share_at(*outside) == 0.0
    assert "out of reach" in planner_says(outside, 0.96)
    cell = into_the_table.cell(*in_the_table)
    assert into_the_table.share[cell] == 0.0 and into_the_table.blocked[cell]
    assert "would touch work_table" in planner_says(in_the_table, 0.85)


def test_each_runs_report_shows_the_layout_with_what_validate_finds(tmp_path, mistaken_cell):
    """A run of the mistaken cell (its layout gathered once in this module) writes
    layout.png beside report.html, which shows it in its Layout section."""
    scenario = load_scenario(mistaken_cell)
    report = run(scenario, duration=0.2, out_dir=tmp_path / "run", scenario_file=mistaken_cell)
    layout = report.files["layout"]
    assert layout == tmp_path / "run" / "layout.png"
    assert layout.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    html = (tmp_path / "run" / "report.html").read_text()
    assert '<h2 id="layout">Layout</h2><img src="layout.png"' in html
    assert len(layout_of(scenario, mistaken_cell).findings) == 3


def test_the_whole_cell_shows_the_safety_scanner_and_its_fields():
    """Where the person stops or slows the robot is part of how the cell can be used: the
    bundled scanner cell's scanner and each speed set's fields are drawn where the scenario
    puts them."""
    scenario = load_scenario("guarded_cell")
    ((name, scanner),) = scenario.safety.sensors.scanners.items()
    whole = draw_layout(layout_of(scenario, None)).axes[0]
    marks = [line.get_xydata()[0] for line in whole.lines if line.get_gid() == f"scanner-{name}"]
    np.testing.assert_allclose(marks, [scanner.pose[:2]])
    drawn = {patch.get_gid(): patch.get_path().vertices for patch in whole.patches}
    for fields in scanner.fields:
        for kind in ("protective", "warning"):
            outline = drawn[f"{name}-{kind}-{fields.speed:g}"]
            np.testing.assert_allclose(outline[:-1], getattr(fields, kind))
