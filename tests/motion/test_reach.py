"""validate's verdict on a robot target is the run's: a target it finds out of reach fails
the run's move with the planner's own "target unreachable", and the distance it says the
arm reaches is one the run's move gets to, with nothing found."""

import re
from pathlib import Path

from hrc_drake.runner import run
from hrc_drake.scenario import load_scenario
from hrc_drake.scenario.findings import findings

STATION = Path(__file__).resolve().parents[1] / "station"


def scenario_with_goal(directory: Path, x: float) -> Path:
    """The station test cell without its person, its robot sent to (x, 0, 1.0), tool down."""
    text = (STATION / "cell.yaml").read_text().replace("human:\n  start: [2.0, 2.0, 180.0]\n", "")
    tree = STATION / "trees" / "move_to_goal.xml"
    directory.mkdir()
    path = directory / "cell.yaml"
    path.write_text(f'{text}trees:\n  robot: {{file: {tree}}}\nparameters:\n  goal: "{x};0;1.0"\n')
    return path


def moved(path: Path, out: Path) -> tuple[bool, str]:
    """Whether the run's move arrived, and why it failed if it did not."""
    report = run(load_scenario(path), duration=4.0, out_dir=out)
    node = report.metrics["bt"]["robot"]["to_goal"]
    return node["successes"] == 1, node.get("first_failure", "")


def test_validate_and_the_run_agree_on_what_the_robot_reaches(tmp_path):
    far = scenario_with_goal(tmp_path / "far", 0.75)
    (found,) = findings(load_scenario(far), far)
    assert found.where == "parameters.goal" and "RobotMove 'to_goal'" in found.message
    assert "parameter 'goal' at (0.75, 0.00, 1.00): out of reach" in found.message
    reaches = float(re.search(r"reaches (\d\.\d\d) m \(move it", found.message).group(1))
    arrived, why = moved(far, tmp_path / "far_run")
    assert not arrived and "target unreachable" in why

    near = scenario_with_goal(tmp_path / "near", reaches)
    assert findings(load_scenario(near), near) == []
    assert moved(near, tmp_path / "near_run") == (True, "")
