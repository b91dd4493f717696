"""docs/building-a-cell.md cannot rot: its cell is built from its own YAML and XML snippets
in an empty folder, validates, runs within the realism audit's limits; the validate line it
quotes is what validate says; its catalogue is the models' own sizes and heights; every
picture it shows exists."""

import importlib.util
import re
from pathlib import Path

import pytest

from hrc_drake.runner import run
from hrc_drake.scenario import load_scenario
from tests.scenarios.realism_checks import assert_within_the_audit_limits

DOCS = Path(__file__).resolve().parents[2] / "docs"
GUIDE = DOCS / "building-a-cell.md"
SHORT = 16.0
"""s: the person refills the tray first (next to the robot, which slows down for them) and
the robot puts the tray's first part on the belt (at 14.5 s)."""
NO_ROOM = (
    "belt_side: {translation: [1.9, 0.6, 0.0]",
    "belt_side: {translation: [1.9, 0.45, 0.0]",
)
"""The guide's place-to-stand mistake: the place by the belt 0.21 m from its rail."""


def _script():
    spec = importlib.util.spec_from_file_location("building_a_cell", DOCS / "building_a_cell.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


GUIDE_SCRIPT = _script()


@pytest.fixture(scope="module")
def cell(tmp_path_factory) -> Path:
    return GUIDE_SCRIPT.write_guide_cell(tmp_path_factory.mktemp("my_cell"))


def test_every_snippet_is_a_piece_of_the_cell():
    text = GUIDE.read_text()
    files = GUIDE_SCRIPT.guide_files(text)
    assert set(files) == {"cell.yaml", "robot.xml", "human.xml"}
    snippets = re.findall(r"^```(?:yaml|xml)", text, re.MULTILINE)
    assert len(snippets) == len(GUIDE_SCRIPT.SNIPPET.findall(text)) >= 6


def test_the_guides_cell_validates(cell, hrc_drake):
    status, out, err = hrc_drake("validate", cell)
    assert (status, err) == (0, "")
    assert "ok (guide_cell; trees robot: robot.xml, human: human.xml)" in out


def test_the_validate_line_the_guide_quotes_is_validates(tmp_path, hrc_drake, monkeypatch):
    cell = GUIDE_SCRIPT.write_guide_cell(tmp_path)
    text = cell.read_text()
    assert NO_ROOM[0] in text
    cell.write_text(text.replace(*NO_ROOM))
    monkeypatch.chdir(tmp_path)
    status, _, err = hrc_drake("validate", "cell.yaml")
    quoted = re.search(r"```text\n(.*?)```", GUIDE.read_text(), re.DOTALL).group(1)
    assert status == 2
    assert err.removeprefix("hrc-drake: error: ").split() == quoted.split()


def test_a_run_of_a_cell_validate_refuses_runs_and_warns(tmp_path, hrc_drake, monkeypatch):
    """A user who runs without validating sees the run and validate's lines as warnings."""
    cell = GUIDE_SCRIPT.write_guide_cell(tmp_path)
    cell.write_text(cell.read_text().replace(*NO_ROOM))
    monkeypatch.chdir(tmp_path)
    status, out, err = hrc_drake("run", "cell.yaml", "--duration", "0.2", "--out", "run")
    quoted = re.search(r"```text\n(.*?)```", GUIDE.read_text(), re.DOTALL).group(1)
    first, last = err.strip().split("\n")
    assert status == 0 and (tmp_path / "run" / "report.json").is_file()
    assert first.removeprefix("hrc-drake: warning: ").split() == quoted.split()
    assert last == "hrc-drake: warning: validate finds 1 line above in the cell as run"
    assert "simulated 0.2 s" in out


def released(metrics: dict) -> int:
    """Parts the robot let go of (on the belt)."""
    robot = metrics["bt"]["robot"]
    return sum(stats["successes"] for path, stats in robot.items() if "RobotRelease" in path)


ACTIVITIES = ("assemble", "check_the_belt", "refill")


def test_the_guides_cell_runs_within_the_realism_limits(cell):
    metrics = run(load_scenario(cell), duration=SHORT).metrics
    assert_within_the_audit_limits(metrics["realism"])
    assert released(metrics) == 1


@pytest.mark.long
def test_the_guides_cell_runs_its_minute_within_the_realism_limits(cell):
    """The whole run: the tray's three parts on the belt, the person assembling, checking
    the belt and refilling the tray (taking a part off the work table, carrying it and
    putting it down in the tray)."""
    metrics = run(load_scenario(cell)).metrics
    assert_within_the_audit_limits(metrics["realism"])
    assert released(metrics) >= 3
    assert all(metrics["bt"]["human"][a]["successes"] for a in ACTIVITIES)


def test_the_catalogue_is_the_models_own():
    text = GUIDE.read_text()
    shown = text.split(GUIDE_SCRIPT.BEGIN)[1].split(GUIDE_SCRIPT.END)[0].strip()
    assert shown == GUIDE_SCRIPT.catalogue()


def test_every_picture_the_guide_shows_is_there():
    pictures = re.findall(r"!\[[^\]]*\]\(([^)]+)\)", GUIDE.read_text())
    assert len(pictures) >= 10
    missing = [p for p in pictures if not (DOCS / p).is_file()]
    assert not missing
