"""The benchmark scripts still run against the library they measure: each is run once with
the smallest work it accepts, and must finish with status 0 and print its figures. Nothing
is timed here (the scripts print ratios; docs: benchmarks/). `falsify.py` is left out: its
smallest run takes minutes (a search); `revision.py` is no script but the loader of a
module's older code that two of them share (exercised by them)."""

import subprocess
import sys
from pathlib import Path

import pytest

BENCHMARKS = Path(__file__).resolve().parents[1] / "benchmarks"
SMALLEST = {
    "arm_check.py": ["--duration", "0.5", "--repeats", "1", "coexistence"],
    "base_scenario.py": ["--duration", "0.5", "--repeats", "1"],
    "bt_tick.py": [],
    "desired_motion.py": ["--duration", "0.5"],
    "ergonomics_cost.py": ["--duration", "0.5", "getting_started"],
    "groot_cost.py": ["--duration", "0.5", "--repeats", "1", "getting_started"],
    "human_cost.py": ["--duration", "0.5", "--repeats", "1"],
    "human_planning.py": ["--duration", "2", "--repeats", "1", "coexistence"],
    "human_update.py": ["--duration", "0.5", "--against", "HEAD", "--repeats", "1", "coexistence"],
    "layout.py": ["--scenario", "getting_started", "--samples", "2"],
    "plant_contact.py": ["--duration", "0.5", "cooperation"],
    "plant_step.py": ["--duration", "0.5", "cooperation"],
    "profile_scenarios.py": ["--duration", "0.5", "getting_started"],
    "python_systems.py": ["--duration", "0.5", "--systems", "0", "2"],
    "realism_cost.py": ["--duration", "0.5", "coexistence"],
    "refused_again.py": ["--duration", "0.2"],
    "replay.py": ["--scenario", "getting_started", "--duration", "0.5", "--repeats", "1"],
    "robot_motion.py": ["--targets", "1", "--duration", "0.5", "--repeats", "1"],
    "robot_update.py": ["--duration", "0.5", "getting_started"],
    "safety_measure.py": ["--duration", "0.5", "coexistence"],
    "safety_cost.py": ["--duration", "0.5", "--repeats", "1", "cooperation"],
    "scenarios.py": ["--duration", "0.5", "cooperation"],
    "sensing_cost.py": ["--duration", "0.5", "--repeats", "1"],
    "sweep.py": ["base", "--runs", "2", "--duration", "0.5", "--repeats", "1"],
    "system_updates.py": ["--duration", "0.5", "getting_started"],
    "tracking.py": ["--duration", "0.5", "cooperation"],
    "update_events.py": ["--duration", "0.5"],
    "workpieces_update.py": ["--duration", "0.5", "--repeat", "1", "cooperation"],
}


def test_every_benchmark_is_exercised_or_named_as_too_long():
    scripts = {p.name for p in BENCHMARKS.glob("*.py")}
    assert scripts == set(SMALLEST) | {"falsify.py", "revision.py"}


@pytest.mark.parametrize("script", SMALLEST)
def test_benchmark_runs(script):
    result = subprocess.run(
        [sys.executable, BENCHMARKS / script, *SMALLEST[script]],
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert result.returncode == 0, result.stderr[-2000:]
    assert result.stdout.strip(), "it printed no figures"
