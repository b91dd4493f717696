"""Sweeps that never lose or mix results: a failed run is a row and the sweep goes on, a
killed worker is a failed row, a killed sweep leaves no workers, damaged rows are set
aside with their file and line, rows of another scenario version are never reused, failed
runs can be retried, and seeds are streamed."""

import itertools
import json
import os
import signal
import subprocess
import sys
import time
from multiprocessing import get_context
from pathlib import Path

from hrc_drake.scenario import resolve_scenario_path
from hrc_drake.sweep import parse_seeds, plan, sweep
from hrc_drake.sweep.execute import _finished, _Worker
from hrc_drake.sweep.rows import RunSpec
from tests.corpus.corpus_helpers import Case, write_workspace

BASE = resolve_scenario_path("base")
LATE_FAULT = Case(
    "robot.xml",
    '<SetRobotVelocity velocity="{speed}"/>',
    '<Sleep msec="150"/><SetRobotVelocity velocity="{sped}"/>',
    (),
)
"""A tree that reads a blackboard entry nobody wrote, 0.15 s into the run."""


def test_a_failed_run_is_a_row_and_the_sweep_goes_on(tmp_path):
    scenario = write_workspace(tmp_path, LATE_FAULT)
    specs = plan(scenario, parse_seeds("0:2"), ["duration=0.1,0.3"])
    result = sweep(specs, tmp_path / "sweep", workers=1)
    assert [row["status"] for row in result.rows] == ["ok", "ok", "failed", "failed"]
    assert "RunStopped" in result.rows[2]["error"]
    assert "blackboard entry 'sped' is not set" in result.rows[2]["error"]
    summary = json.loads(result.files["summary"].read_text())
    assert len(summary["failed"]) == 2


def test_seeds_are_streamed_not_listed():
    seeds = parse_seeds("0:1000000000000000,7,5:12")
    assert len(seeds) == 1_000_000_000_000_000
    assert list(itertools.islice(seeds, 3)) == [0, 1, 2]
    assert list(parse_seeds("10:12,3,11:14,3")) == [10, 11, 3, 12, 13]
    assert len(parse_seeds("10:12,3,11:14,3")) == 5
    specs = plan(BASE, seeds, ["duration=0.5,1"])
    assert len(specs) == 2_000_000_000_000_000
    assert [spec.seed for spec in itertools.islice(specs, 2)] == [0, 1]


def test_damaged_rows_are_set_aside_with_file_and_line(tmp_path, hrc_drake):
    out = tmp_path / "sweep"
    args = ("sweep", BASE, "--seeds", "0:2", "--set", "duration=0.05", "--workers", "1")
    assert hrc_drake(*args, "--out", out)[0] == 0
    rows = out / "runs.jsonl"
    good, second = rows.read_text().splitlines()
    rows.write_text(f'{good[:40]}\n[1, 2]\n{second}\n{{"key": "seed=9"}}\n')
    status, stdout, err = hrc_drake(*args, "--out", out)
    assert status == 0, err
    warnings = err.splitlines()
    assert len(warnings) == 3
    assert warnings[0].startswith(f"hrc-drake: warning: {rows}:1: damaged row (not JSON")
    assert warnings[1].startswith(f"hrc-drake: warning: {rows}:2: damaged row (not a JSON object)")
    assert warnings[2].startswith(f"hrc-drake: warning: {rows}:4: damaged row (no int 'seed')")
    assert "set aside in runs.damaged.jsonl" in warnings[0]
    assert (out / "runs.damaged.jsonl").read_text().splitlines() == [
        good[:40],
        "[1, 2]",
        '{"key": "seed=9"}',
    ]
    assert "2 runs (1 already done, 0 failed)" in stdout
    assert len(rows.read_text().splitlines()) == 2


def test_rows_of_an_edited_scenario_are_not_reused(tmp_path, hrc_drake):
    scenario = write_workspace(tmp_path)
    out = tmp_path / "sweep"
    args = ("sweep", scenario, "--seeds", "0", "--set", "duration=0.05", "--workers", "1")
    assert hrc_drake(*args, "--out", out)[0] == 0
    status, stdout, _ = hrc_drake(*args, "--out", out)
    assert "1 runs (1 already done, 0 failed)" in stdout
    (tmp_path / "robot.xml").write_text((tmp_path / "robot.xml").read_text() + "<!-- -->\n")
    status, stdout, err = hrc_drake(*args, "--out", out)
    assert status == 0, err
    assert "1 runs (0 already done, 0 failed)" in stdout
    hashes = {json.loads(line)["scenario_hash"] for line in (out / "runs.jsonl").open()}
    assert len(hashes) == 2


def sweep_command(out: Path, *extra) -> list[str]:
    command = [sys.executable, "-m", "hrc_drake.cli", "sweep", "base", "--seeds", "0:3"]
    return [*command, "--set", "duration=0.3", "--workers", "1", "--out", str(out), *extra]


def workers_of(pid: int) -> list[int]:
    """The sweep's worker processes (spawned children running spawn_main)."""
    found = []
    for status in Path("/proc").glob("[0-9]*/status"):
        try:
            fields = dict(line.split(":\t", 1) for line in status.read_text().splitlines())
            command = (status.parent / "cmdline").read_bytes()
        except (OSError, ValueError):
            continue
        if fields.get("PPid", "").strip() == str(pid) and b"spawn_main" in command:
            found.append(int(status.parent.name))
    return found


def wait_for(condition, seconds=60.0):
    deadline = time.monotonic() + seconds
    while time.monotonic() < deadline:
        value = condition()
        if value:
            return value
        time.sleep(0.05)
    raise AssertionError("timed out")


def alive(pid: int) -> bool:
    status = Path(f"/proc/{pid}/status")
    return status.is_file() and "State:\tZ" not in status.read_text()


def test_a_worker_killed_before_it_takes_its_run_is_a_failed_row():
    """Killed between runs, as the sweep handed it the next one: the send broke the whole
    sweep (BrokenPipeError; CI, once, with the machine loaded). It is that run's failed
    row, as a worker killed during its run is."""
    context = get_context("spawn")
    worker = _Worker(context)
    worker.process.kill()
    worker.process.join()
    worker.start(RunSpec("base", seed=4))
    rows: list[dict] = []
    free = _finished([worker], rows.append, context)
    assert [row["seed"] for row in rows] == [4]
    assert "the worker process running this run died (killed by SIGKILL)" in rows[0]["error"]
    for fresh in free:
        fresh.stop()


def test_a_killed_worker_is_a_failed_row_and_retry_failed_runs_it_again(tmp_path, hrc_drake):
    sweep_process = subprocess.Popen(
        sweep_command(tmp_path), stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True
    )
    worker = wait_for(lambda: workers_of(sweep_process.pid))[0]
    os.kill(worker, signal.SIGKILL)
    stdout, stderr = sweep_process.communicate(timeout=120)
    assert sweep_process.returncode == 0, stderr
    assert "3 runs (0 already done, 1 failed)" in stdout
    rows = [json.loads(line) for line in (tmp_path / "runs.jsonl").open()]
    failed = [row for row in rows if row["status"] == "failed"]
    assert [row["seed"] for row in failed] == [0]
    assert "the worker process running this run died (killed by SIGKILL)" in failed[0]["error"]
    assert (tmp_path / "summary.json").is_file()

    again = hrc_drake(
        "sweep",
        "base",
        "--seeds",
        "0:3",
        "--set",
        "duration=0.3",
        "--workers",
        "1",
        "--out",
        tmp_path,
    )
    assert "3 runs (3 already done, 1 failed)" in again[1]
    retried = hrc_drake(
        "sweep",
        "base",
        "--seeds",
        "0:3",
        "--set",
        "duration=0.3",
        "--workers",
        "1",
        "--out",
        tmp_path,
        "--retry-failed",
    )
    assert retried[0] == 0, retried[2]
    assert "3 runs (2 already done, 0 failed)" in retried[1]


def test_a_killed_sweep_leaves_no_workers(tmp_path):
    sweep_process = subprocess.Popen(
        sweep_command(tmp_path / "sweep", "--workers", "2"),
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
    )
    # A spawned worker imports Drake before it can follow its parent (execute._die_with),
    # and exits as soon as it does if the parent is gone: on a loaded machine (load 7) that
    # took longer than this test allowed once. Both waits leave room for the imports.
    workers = wait_for(lambda: len(w := workers_of(sweep_process.pid)) == 2 and w, seconds=300)
    os.kill(sweep_process.pid, signal.SIGKILL)
    sweep_process.wait()
    wait_for(lambda: not any(alive(pid) for pid in workers), seconds=120)
