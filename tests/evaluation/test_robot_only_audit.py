"""A cell with objects and no person still gets the objects' part of the realism audit:
what the robot holds, in the cell or another object (#26: a robot-only cell's parts went
unmeasured, a part set 5 cm into another said nothing). The person's measures are absent,
and the report says why. The robot refuses to set a part into another now, so the bad
put-down here is into the table, which a linear move to the tree's target still makes."""

import json
from pathlib import Path

import pytest

from hrc_drake.evaluation.sweep_report import realism_counts

NO_PERSON = "no person in this cell"
CELL = Path(__file__).parent / "cells" / "robot_only" / "cell.yaml"
RESTING_ON_IT = "parameters.put_down_at=0.35;0.9;1.1"
"""The part's top where it rests on the other part's (the cell's own: 5 cm into the table)."""


def _run(hrc_drake, out: Path, *overrides) -> tuple[dict, str, str]:
    status, stdout, err = hrc_drake("run", CELL, "--out", out, *overrides)
    assert status == 0, err
    return json.loads((out / "report.json").read_text()), stdout, (out / "report.html").read_text()


def test_a_part_the_robot_sets_into_the_table_is_reported_without_a_person(tmp_path, hrc_drake):
    report, stdout, html = _run(hrc_drake, tmp_path / "run")
    held = report["realism"]["penetration_carried"]
    assert held["max"] == pytest.approx(0.05, abs=0.002)
    assert held["where"] == "part 1 in work_table"
    assert report["realism"]["person"] == NO_PERSON
    assert "penetration_static" not in report["realism"]
    verdict = (
        "realism: 1 of 1 measures over their limits; worst: held object in the cell or another "
        "object 5.0 cm (limit 1 cm): part 1 in work_table at"
    )
    assert verdict in stdout
    assert f"not measured: the person's measures ({NO_PERSON})" in stdout
    assert "The realism audit: 1 of 1 measures over their limits" in html
    counts = realism_counts([{"metrics": report}])
    assert counts == {"audited": 1, "over_limits": 1, "measures": {"penetration_carried": 1}}


def test_a_part_set_down_on_another_is_within_the_limits(tmp_path, hrc_drake):
    report, stdout, _ = _run(hrc_drake, tmp_path / "run", "--set", RESTING_ON_IT)
    assert report["realism"]["penetration_carried"]["max"] <= 0.01
    assert report["bt"]["robot"]["RobotRelease::9"]["successes"] == 1
    assert "realism: within its limits (1 measure); not measured: the person's measures" in stdout
