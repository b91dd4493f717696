"""Sweeps: parallel rows equal serial runs, interrupted sweeps resume, failures are rows,
and a Dask cluster gives the same rows as the local pool."""

import json
import os
import re
import signal
import subprocess
import sys
import time

import pytest

from hrc_drake.runner import run
from hrc_drake.scenario import Scenario, load_scenario, resolve_scenario_path
from hrc_drake.scenario.overrides import grid, overridden, parse_sets
from hrc_drake.sweep import parse_seeds, plan, sweep
from hrc_drake.yaml_check import InputError

BASE = resolve_scenario_path("base")
SHORT = ["duration=0.5"]


def metrics_as_stored(metrics: dict) -> dict:
    return json.loads(json.dumps(metrics))


def test_seed_ranges_and_lists():
    assert list(parse_seeds("0:4")) == [0, 1, 2, 3]
    assert list(parse_seeds("0:2,7,1")) == [0, 1, 7]
    with pytest.raises(InputError, match="--seeds x"):
        parse_seeds("x")


def test_set_builds_a_typed_grid():
    axes = parse_sets(["duration=1,2", "robot.tool=none"], Scenario)
    assert axes == [("duration", [1.0, 2.0]), ("robot.tool", ["none"])]
    points = grid(axes)
    assert points == [
        (("duration", 1.0), ("robot.tool", "none")),
        (("duration", 2.0), ("robot.tool", "none")),
    ]
    scenario = overridden(load_scenario("base"), points[1])
    assert (scenario.duration, scenario.robot.tool) == (2.0, "none")


@pytest.mark.parametrize(
    "text, message",
    [
        ("durration=1", "unknown field 'durration' (did you mean 'duration'?)"),
        ("robot.varient=x", "unknown field 'varient' (did you mean 'variant'?)"),
        ("duration=fast", "'fast' is not a float"),
        ("cell=1", "only number, boolean and text fields"),
        ("duration", "expected PATH=VALUE"),
    ],
)
def test_bad_set_is_one_clear_line(text, message):
    with pytest.raises(InputError, match=re.escape(message)):
        parse_sets([text], Scenario)


def test_two_workers_equal_runs_one_by_one(tmp_path):
    specs = plan(BASE, list(range(8)), SHORT)
    result = sweep(specs, tmp_path, workers=2)
    assert [row["seed"] for row in result.rows] == list(range(8))
    scenario = load_scenario("base")
    for row in result.rows:
        assert row["status"] == "ok"
        alone = run(scenario, seed=row["seed"], duration=0.5).metrics
        assert row["metrics"] == metrics_as_stored(alone)
    for name in ("rows", "csv", "summary", "report_html"):
        assert result.files[name].is_file()


def test_dask_cluster_gives_the_same_rows(tmp_path):
    from distributed import LocalCluster

    specs = plan(BASE, [0, 1, 2], SHORT)
    local = sweep(specs, tmp_path / "local", workers=2)
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=False) as cluster:
        remote = sweep(specs, tmp_path / "dask", dask_address=cluster.scheduler_address)
    assert [r["metrics"] for r in remote.rows] == [r["metrics"] for r in local.rows]
    assert [r["key"] for r in remote.rows] == [r["key"] for r in local.rows]


def sweep_cli(out, *extra):
    command = [sys.executable, "-m", "hrc_drake.cli", "sweep", "base", "--seeds", "0:8"]
    return [*command, "--set", "duration=1", "--workers", "1", "--out", str(out), *extra]


def test_killed_sweep_resumes_without_rerunning_finished_seeds(tmp_path):
    rows = tmp_path / "runs.jsonl"
    process = subprocess.Popen(
        sweep_cli(tmp_path), start_new_session=True, stderr=subprocess.DEVNULL
    )
    deadline = time.monotonic() + 60
    while time.monotonic() < deadline and _lines(rows) < 2:
        time.sleep(0.05)
    os.killpg(process.pid, signal.SIGKILL)
    process.wait()
    before = rows.read_text().splitlines()
    assert 2 <= len(before) < 8
    done = subprocess.run(sweep_cli(tmp_path), capture_output=True, text=True, check=True)
    assert f"({len(before)} already done, 0 failed)" in done.stdout
    after = rows.read_text().splitlines()
    assert after[: len(before)] == before
    assert sorted(json.loads(line)["seed"] for line in after) == list(range(8))


def test_a_sweep_is_known_again_whatever_order_its_sets_were_given_in(tmp_path):
    """runs.jsonl keeps the --set values sorted; a rerun still finds its rows."""
    specs = plan(BASE, parse_seeds("0:2"), ["safety.v_h=1.6", "duration=0.2"])
    first = sweep(specs, tmp_path)
    again = sweep(plan(BASE, parse_seeds("0:2"), ["duration=0.2", "safety.v_h=1.6"]), tmp_path)
    assert (first.skipped, again.skipped) == (0, 2)
    assert again.rows == first.rows


def test_cli_rejects_unknown_field_with_exit_2(capsys):
    from hrc_drake.cli import main

    assert main(["sweep", "base", "--set", "safety.nonsense=1"]) == 2
    assert "unknown field" in capsys.readouterr().err


def _lines(path) -> int:
    return len(path.read_text().splitlines()) if path.is_file() else 0


def test_sweep_workers_print_none_of_drakes_info_messages(tmp_path):
    command = [sys.executable, "-m", "hrc_drake.cli", "sweep", "base", "--seeds", "0:2"]
    command += ["--set", "duration=0.2", "--workers", "2", "--out", str(tmp_path)]
    done = subprocess.run(command, capture_output=True, text=True, check=True)
    assert "2 runs" in done.stdout or "0 failed" in done.stdout, done.stdout
    assert "drake" not in done.stderr.lower(), done.stderr


def test_sweep_takes_a_duration_as_run_and_falsify_do(tmp_path, hrc_drake):
    out = tmp_path / "sweep"
    args = ("sweep", "base", "--seeds", "0:2", "--duration", "0.2", "--workers", "1")
    status, said, err = hrc_drake(*args, "--out", out)
    assert status == 0, err
    rows = [json.loads(line) for line in (out / "runs.jsonl").read_text().splitlines()]
    assert [row["metrics"]["duration"] for row in rows] == [0.2, 0.2]
    assert [row["key"] for row in rows] == ["seed=0 duration=0.2", "seed=1 duration=0.2"]
    assert rows[0]["set"] == {"duration": 0.2}  # a replay command sets it too
    assert "  duration=0.2: none of 2 runs violates ISO/TS 15066\n" in said
    status, _, err = hrc_drake(*args, "--set", "duration=1,2", "--out", tmp_path / "both")
    assert status == 2 and err.count("\n") == 1
    assert "--set duration: --duration 0.2 sets it already" in err
    status, _, err = hrc_drake("sweep", "base", "--duration", "-1", "--out", tmp_path / "bad")
    assert status == 2 and "--duration -1.0" in err, err


def test_a_sweep_is_named_by_its_scenarios_name_not_its_file(tmp_path):
    """The corpus's scenario.yaml is called `corpus`: so are the report and its title, also
    when the sweep is asked for from Python."""
    from tests.corpus.corpus_helpers import write_workspace

    path = write_workspace(tmp_path)
    result = sweep(plan(path, parse_seeds("0:1"), ["duration=0.05"]), tmp_path / "out")
    page = result.files["report_html"].read_text()
    assert "<title>sweep corpus</title>" in page
    assert "<h1>Sweep of corpus: 1 runs (0 failed)</h1>" in page
    assert json.loads(result.files["summary"].read_text())["scenario"] == "corpus"
