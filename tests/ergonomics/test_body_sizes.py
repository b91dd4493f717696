"""People of every size: the bundled scenarios for a 5th-percentile woman, a 50th- and a
95th-percentile man (ANSUR II, docs/ergonomics.md) do their work, pass the realism audit,
keep their safety verdict and report the ergonomics of the person's work.

The long test runs every scenario for the three; the default suite runs the smallest
person through the collaboration scenario's carry."""

import csv
from pathlib import Path

import pytest

from hrc_drake import load_scenario, run
from hrc_drake.cli import main
from tests.scenarios.realism_checks import assert_holds_what_it_carries, assert_walks_like_a_person

ROOT = Path(__file__).resolve().parents[2]
SCENARIOS = ROOT / "scenarios"
SIZES = {
    "5th-percentile woman": ("female", 5.0),
    "50th-percentile man": ("male", 50.0),
    "95th-percentile man": ("male", 95.0),
}
WORK = {
    "coexistence": (2, 45.0, ("part_finished", "fetch_material", "work_at_bench")),
    "cooperation": (0, 50.0, ("part_rejected", "part_scrapped")),
    "collaboration": (15, 80.0, ("box_by_person", "handover", "regrip")),
}
"""Per scenario: the seed and duration of its short test run, and the events of its work."""


def run_for(name: str, sex: str, percentile: float, duration: float | None = None) -> dict:
    seed, short, _ = WORK[name]
    overrides = [
        ("seed", seed),
        ("duration", duration or short),
        ("human.sex", sex),
        ("human.percentile", percentile),
        ("visualization.record", False),
    ]
    return run(load_scenario(name, overrides)).metrics


def assert_realistic(realism: dict) -> None:
    """What the scenario tests ask of every scenario's person (tests/scenarios)."""
    assert_holds_what_it_carries(realism)
    assert_walks_like_a_person(realism)


def assert_safe(metrics: dict) -> None:
    safety = metrics["safety"]
    assert (safety["ssm_violations"]["count"], safety["contacts"]["count"]) == (0, 0)
    assert not metrics["margin"]["violation"]


def assert_did_the_work(name: str, metrics: dict) -> None:
    events = metrics["tasks"]["events"]
    missing = [event for event in WORK[name][2] if not events.get(event)]
    assert not missing, f"{name}: no {missing} in {events}"


@pytest.mark.long
@pytest.mark.parametrize("person", SIZES)
@pytest.mark.parametrize("name", WORK)
def test_every_scenario_works_for_every_size(name, person):
    metrics = run_for(name, *SIZES[person])
    assert_did_the_work(name, metrics)
    assert_realistic(metrics["realism"])
    assert_safe(metrics)
    assert metrics["ergonomics"]["rula"]["max"]["score"] >= 1


def test_a_sweep_varies_the_person_by_percentile():
    """`--set human.percentile=5,50,95` is a grid of three people, each checked before any
    run and sized by the survey."""
    from hrc_drake.scenario import load_scenario as load
    from hrc_drake.sweep import parse_seeds, plan

    sweep_plan = plan(
        SCENARIOS / "collaboration.yaml", parse_seeds("0"), ["human.percentile=5,50,95"]
    )
    heights = [load("collaboration", point).human.size()[0] for point in sweep_plan.points]
    assert heights == sorted(heights) and len(set(heights)) == 3


def test_falsify_searches_over_body_size(tmp_path):
    """A `falsify:` parameter bound to `human.percentile` makes the search try people of
    other sizes; every trial's row carries the person's ergonomic figures."""
    text = (SCENARIOS / "walk_up.yaml").read_text().replace("../trees/", f"{ROOT}/trees/")
    text = text.replace(
        "falsify:\n  parameters:\n",
        "falsify:\n  parameters:\n    size: {bind: human.percentile, low: 5, high: 95}\n",
    )
    scenario = tmp_path / "walk_up_sizes.yaml"
    scenario.write_text(text)
    search = ["--budget", "2", "--set", "falsify.batch=2", "--set", "falsify.worst=1"]
    assert (
        main(["falsify", str(scenario), "--duration", "4", *search, "--out", str(tmp_path / "s")])
        == 0
    )
    trials = list(csv.DictReader((tmp_path / "s" / "trials.csv").open()))
    assert len({trial["size"] for trial in trials}) == 2
    assert all(int(trial["rula_max"]) >= 1 for trial in trials)


def test_a_5th_percentile_woman_carries_the_collaboration_box():
    """The smallest person (1.52 m, 49 kg) answers the robot's call: she lifts the carton it
    must not handle (3 kg, both hands) and carries it to the belt, holds it and walks as the
    scenario tests ask, and the run stays safe; report.json describes her and her lift."""
    metrics = run_for("collaboration", *SIZES["5th-percentile woman"], duration=35.0)
    assert metrics["tasks"]["events"].get("box_by_person") == 1
    assert_realistic(metrics["realism"])
    assert_safe(metrics)
    ergonomics = metrics["ergonomics"]
    assert ergonomics["person"] == {"height": 1.5229, "mass": 49.21}
    lift = ergonomics["lifts"][0]
    assert (lift["mass"], lift["hands"]) == (3.0, "both_hands")
    assert ergonomics["lifting_index_max"]["value"] > 0
