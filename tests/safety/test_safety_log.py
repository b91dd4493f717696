"""The run directory's safety.npz: the monitor at every update, checkable against the
report (the getting-started cell with SSM off, so that the robot keeps moving near the
person and the log holds violations to check)."""

import json

import numpy as np
import pytest

from hrc_drake.human.skeleton import REGIONS
from hrc_drake.runner import run
from hrc_drake.safety.config import SafetyConfig
from hrc_drake.safety.log import read_safety_log
from hrc_drake.safety.messages import SIGNALS
from hrc_drake.scenario import load_scenario
from hrc_drake.scenario.overrides import overridden
from tests.safety.recompute import episodes

DURATION = 12.0


@pytest.fixture(scope="module")
def run_directory(tmp_path_factory):
    out = tmp_path_factory.mktemp("run")
    scenario = overridden(load_scenario("getting_started"), [("safety.ssm", False)])
    run(scenario, duration=DURATION, out_dir=out)
    return json.loads((out / "report.json").read_text())["safety"], read_safety_log(
        out / "safety.npz"
    )


def test_one_entry_per_monitor_update(run_directory):
    """Every period, or a multiple of it up to far_period while the person was far
    (Judge.next_period: beyond about 2.4 m for the iisy 3)."""
    _, log = run_directory
    assert set(SIGNALS) <= set(log)
    steps = np.diff(log["time"])
    config = SafetyConfig()
    multiples = steps / config.period
    assert np.allclose(multiples, np.round(multiples), rtol=0, atol=1e-6)
    assert steps.max() <= config.far_period + 1e-9
    far = multiples > 1.5
    assert np.all(log["separation"][:-1][far] > 2.4)
    assert log["time"][0] == 0.0 and log["time"][-1] >= DURATION - 0.02
    assert list(log["regions"]) == list(REGIONS)


def test_terms_add_up_to_s_p(run_directory):
    _, log = run_directory
    person = np.isfinite(log["separation"])
    total = log["s_h"] + log["s_r"] + log["s_s"] + log["margins"]
    protective = log["protective"][person]
    # S_p is the sum of its terms, or ISO 13855's least distance (0.5 m) where that is larger
    is_sum = np.isclose(protective, total[person], rtol=0, atol=1e-12)
    is_least = (protective == 0.5) & (total[person] <= 0.5)
    assert np.all(is_sum | is_least) and is_sum.any()
    assert np.all(log["v_h"][person] >= 1.6)


def test_report_agrees_with_the_log(run_directory):
    report, log = run_directory
    finite = np.isfinite(log["separation"])
    closest = int(np.argmin(np.where(finite, log["separation"], np.inf)))
    assert report["min_separation"]["distance"] == pytest.approx(log["separation"][closest])
    assert report["min_separation"]["region"] == log["regions"][int(log["region"][closest])]
    assert report["min_separation"]["link"] == log["parts"][int(log["part"][closest])]
    moving = log["robot_speed"] > report["ssm_violations"]["moving_speed"]
    flags = moving & (log["separation"] < log["protective"])
    assert np.array_equal(flags, log["violation"] > 0)
    runs = episodes(flags, log["time"])
    reported = report["ssm_violations"]["episodes"]
    assert report["ssm_violations"]["count"] == len(reported) == len(runs) > 0
    for (start, end), episode in zip(runs, reported, strict=True):
        assert (episode["start"], episode["end"]) == pytest.approx((start, end))
        during = (log["time"] >= start) & (log["time"] <= end)
        deficit = (log["protective"] - log["separation"])[during].max()
        assert episode["deficit"] == pytest.approx(deficit)
