"""`hrc-drake falsify` closed-loop on the walk-up cell: with the monitor weakened (it takes
the person for 0.8 m/s) the search finds an SSM violation where as many plain seeds find
none; with the monitor as ISO 13855 has it, it reports its lowest margin and no violation;
a worst case's command reproduces it; a finished search asked again runs nothing.

Short runs (7 s, the person setting off within the first second) and a budget of 4 keep
the default suite fast; the long test spends the scenario's own durations and more trials.
"""

import json
import shlex

import pytest

from hrc_drake.cli import main
from hrc_drake.falsify import falsify, prepare
from hrc_drake.paths import resource_dir
from hrc_drake.sweep import parse_seeds, plan, sweep

SHORT = ("--duration", "7", "--set", "falsify.parameters.set_off.high=1000")
WEAK = ("--set", "safety.v_h_rule=constant", "--set", "safety.v_h=0.8")
SEARCH = ("--budget", "4", "--set", "falsify.batch=2", "--set", "falsify.worst=1")


def monte_carlo(out, seeds: str, sets: list[str]) -> list[dict]:
    """The same cell over plain seeds (the scenario's own randomness), on the sweep."""
    rows = sweep(plan(prepare("walk_up").scenario_path, parse_seeds(seeds), sets), out, 2).rows
    assert all(row["status"] == "ok" for row in rows)
    return [row["metrics"]["margin"] for row in rows]


@pytest.fixture(scope="module")
def weak_search(tmp_path_factory):
    out = tmp_path_factory.mktemp("weak")
    return out, main(["falsify", "walk_up", *SHORT, *WEAK, *SEARCH, "--out", str(out / "s")])


def test_weakened_monitor_violation_found_where_seeds_find_none(weak_search, tmp_path):
    out, status = weak_search
    assert status == 0
    found = json.loads((out / "s" / "falsify.json").read_text())
    assert len(found["trials"]) == 4 and found["violations"] >= 1
    assert found["lowest_margin"] < 0 and found["worst"][0]["violation"]
    sets = ["duration=7", "safety.v_h_rule=constant", "safety.v_h=0.8"]
    margins = monte_carlo(tmp_path, "0:4", sets)
    assert not any(m["violation"] for m in margins), margins
    assert min(m["value"] for m in margins) > found["lowest_margin"]


def test_worst_case_directory_and_its_command_reproduce_it(weak_search, hrc_drake, tmp_path):
    out, _ = weak_search
    worst = json.loads((out / "s" / "falsify.json").read_text())["worst"][0]
    case = out / "s" / "cases" / f"trial-{worst['trial']:04d}"
    for name in ("report.json", "report.html", "replay.html", "safety.npz", "timeline.png"):
        assert (case / name).is_file(), name
    command = (case / "command.txt").read_text().strip()
    assert command == worst["command"]
    assert json.loads((case / "report.json").read_text())["margin"]["value"] == worst["margin"]
    arguments = shlex.split(command)
    assert arguments[:2] == ["hrc-drake", "run"]
    assert hrc_drake(*arguments[1:], "--out", tmp_path / "again")[0] == 0
    again = json.loads((tmp_path / "again" / "report.json").read_text())["margin"]
    assert again["value"] == worst["margin"] and again["violation"]


def test_report_page_plots_margins_and_worst_timelines(weak_search):
    out, _ = weak_search
    page = (out / "s" / "falsify.html").read_text()
    assert "violate ISO/TS 15066" in page
    assert '<img src="margin.png"' in page and '<img src="worst_cases.png"' in page
    assert "cases/trial-" in page and "replay.html" in page
    trials = (out / "s" / "trials.csv").read_text().splitlines()
    assert trials[0].startswith("trial,status,set_off,side,stand_dx")
    assert len(trials) == 5


def test_a_finished_search_asked_again_runs_nothing(weak_search, hrc_drake):
    out, _ = weak_search
    rows = (out / "s" / "runs.jsonl").read_text()
    before = json.loads((out / "s" / "falsify.json").read_text())
    status, said, err = hrc_drake("falsify", "walk_up", *SHORT, *WEAK, *SEARCH, "--out", out / "s")
    assert status == 0, err
    assert (out / "s" / "runs.jsonl").read_text() == rows
    assert json.loads((out / "s" / "falsify.json").read_text()) == before
    assert "4 trials (0 failed)" in said and "violate ISO/TS 15066" in said


def test_correct_monitor_reports_its_lowest_margin_and_no_violation(tmp_path, hrc_drake):
    status, said, err = hrc_drake("falsify", "walk_up", *SHORT, *SEARCH, "--out", tmp_path)
    assert status == 0, err
    found = json.loads((tmp_path / "falsify.json").read_text())
    margins = [trial["margin"] for trial in found["trials"]]
    assert found["violations"] == 0 and not any(t["violation"] for t in found["trials"])
    assert found["lowest_margin"] == min(margins) > 0
    assert "4 trials (0 failed), no violation" in said
    assert f"margin {found['lowest_margin']:.3f} m" in said


def test_one_seed_same_trials_on_local_workers_and_on_dask(tmp_path):
    """Rounds of 2 trials on two local workers and on a Dask cluster: the same values, the
    same margins (short runs; the worst case is not run again)."""
    from distributed import LocalCluster

    sets = (("duration", 3.0), ("falsify.batch", 2), ("falsify.worst", 0))
    search = prepare("walk_up", 5, sets)
    local = falsify(search, 4, tmp_path / "local", workers=2)
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=False) as cluster:
        dask = falsify(search, 4, tmp_path / "dask", dask_address=cluster.scheduler_address)
    assert [t.values for t in dask.trials] == [t.values for t in local.trials]
    assert [t.row["metrics"] for t in dask.trials] == [t.row["metrics"] for t in local.trials]
    assert all(t.ok for t in local.trials)


@pytest.mark.long
def test_scenario_length_search_against_as_many_seeds(tmp_path):
    """The walk-up cell as written (14 s runs): 8 trials find the weakened monitor's
    violation and 8 seeds none; 12 trials of the correct monitor find none."""
    weak_sets = (("safety.v_h_rule", "constant"), ("safety.v_h", 0.8), ("duration", 14.0))
    weak = falsify(prepare("walk_up", 0, weak_sets), 8, tmp_path / "weak", workers=2)
    assert weak.violations
    margins = monte_carlo(tmp_path / "mc", "0:8", [f"{p}={v}" for p, v in weak_sets])
    assert not any(m["violation"] for m in margins)
    correct = falsify(prepare("walk_up", 0, (("duration", 14.0),)), 12, tmp_path / "ok", workers=2)
    assert not correct.violations and not correct.failed
    assert correct.worst[0].margin["value"] > 0


def test_a_search_is_named_by_its_scenarios_name_not_its_file(tmp_path, hrc_drake, monkeypatch):
    """walk_up saved as cell.yaml and called `watching`: the search's directory, report
    title, result line and progress are `watching`, never `cell`."""
    text = (resource_dir("scenarios") / "walk_up.yaml").read_text()
    text = text.replace("name: walk_up", "name: watching")
    (tmp_path / "cell.yaml").write_text(text.replace("../trees/", f"{resource_dir('trees')}/"))
    monkeypatch.chdir(tmp_path)
    one = ("--budget", "1", "--set", "falsify.batch=1", "--set", "falsify.worst=1")
    status, said, err = hrc_drake("falsify", "cell.yaml", "--duration", "1", *one, "--workers", "1")
    assert status == 0, err
    assert said.splitlines()[0].startswith("watching: 1 trials (0 failed)")
    assert [p.name for p in (tmp_path / "searches").iterdir()] == ["watching"]
    page = (tmp_path / "searches" / "watching" / "falsify.html").read_text()
    assert "<title>falsify watching</title>" in page
    assert "<h1>Worst cases of watching</h1>" in page
    assert "cell" not in page.replace("cell.yaml", "")
