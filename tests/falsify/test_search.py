"""The search itself, on a stand-in for the simulator (a margin computed from the trial's
`--set` values), so its promises are checked in a second: one seed gives the same trials
whatever order the runs finish in, a resumed search ends as an uninterrupted one and runs
only what it lacks, failed runs are told as failures and never ranked."""

import math

from hrc_drake.falsify import prepare, ranked
from hrc_drake.falsify.search import run_trials, search_space
from hrc_drake.sweep.rows import RowStore, make_row

HAZARD = {"parameters.stand_dx": 0.25, "parameters.reach": 0.7}
"""Where the stand-in puts the lowest margin."""


def stand_in_margin(overrides: dict) -> float:
    """Lower the closer the trial's values are to HAZARD, and when the person stands
    beside the robot; negative within 0.1 of it there."""
    distance = math.dist(
        [float(overrides[path]) for path in HAZARD], [value for value in HAZARD.values()]
    )
    beside = overrides["parameters.visit_area"] in ("left_side", "right_side")
    return distance - (0.1 if beside else -0.5)


class StandIn:
    """An executor: rows as the workers would return them, in reverse order (runs finish
    in any order); counts the runs it did and fails those `fail` says."""

    def __init__(self, fail=lambda overrides: False):
        self.runs = 0
        self.fail = fail

    def __call__(self, specs, on_row):
        rows = []
        for spec in specs:
            overrides = dict(spec.overrides)
            self.runs += 1
            if self.fail(overrides):
                rows.append(make_row(spec, None, error="RuntimeError: stand-in failure"))
                continue
            margin = stand_in_margin(overrides)
            metrics = {"margin": {"value": margin, "violation": margin < 0}}
            rows.append(make_row(spec, metrics))
        for row in reversed(rows):
            on_row(row)


def search(seed=0, batch=4):
    return prepare("walk_up", seed, (("falsify.batch", batch),))


def test_same_seed_same_trials_whatever_order_runs_finish(tmp_path):
    first = run_trials(search(), 12, RowStore(tmp_path / "a"), StandIn())
    again = run_trials(search(), 12, RowStore(tmp_path / "b"), StandIn())
    assert [t.values for t in first] == [t.values for t in again]
    other = run_trials(search(seed=1), 12, RowStore(tmp_path / "c"), StandIn())
    assert [t.values for t in first] != [t.values for t in other]


def test_values_lie_in_their_ranges_and_set_the_bound_fields(tmp_path):
    trials = run_trials(search(), 12, RowStore(tmp_path), StandIn())
    space = search_space(search().config)
    for trial in trials:
        sets = trial.row["set"]
        assert trial.values["set_off"] in [str(ms) for ms in range(0, 8001, 100)]
        assert trial.values["side"] in space["side"].choices
        assert 0.2 <= float(trial.values["reach"]) <= 0.8
        assert 0.8 <= float(trial.values["walk"]) <= 1.707
        assert sets["trees.human.ports.walk_in.animation_distance"] == trial.values["walk"]
        assert sets["parameters.reach"] == trial.values["reach"]


def test_a_resumed_search_equals_an_uninterrupted_one(tmp_path):
    whole = run_trials(search(), 12, RowStore(tmp_path / "whole"), StandIn())
    runs = StandIn()
    store = RowStore(tmp_path / "resumed")
    run_trials(search(), 5, store, runs)  # stopped after 5 trials (mid-round)
    assert runs.runs == 5
    resumed = run_trials(search(), 12, RowStore(tmp_path / "resumed"), runs)
    assert runs.runs == 12, "the 5 trials already run are not run again"
    assert [t.values for t in resumed] == [t.values for t in whole]
    assert [t.score for t in resumed] == [t.score for t in whole]


def test_the_search_finds_what_random_values_miss(tmp_path):
    """After its random start the sampler closes in on the stand-in's hazard."""
    trials = run_trials(search(), 40, RowStore(tmp_path), StandIn())
    start = min(t.score for t in trials[:8])
    assert min(t.score for t in trials) < start
    assert ranked(trials)[0].score == min(t.score for t in trials)


def test_failed_runs_are_told_as_failures_and_never_ranked(tmp_path):
    def fails(overrides):
        return overrides["parameters.visit_area"] == "far_side"

    trials = run_trials(search(), 8, RowStore(tmp_path), StandIn(fail=fails))
    failed = [t for t in trials if not t.ok]
    assert failed and all(t.values["side"] == "far_side" for t in failed)
    assert all(t.ok for t in ranked(trials))
    again = StandIn()  # the first 8 trials are drawn at random: the same values again
    retried = run_trials(search(), 8, RowStore(tmp_path), again, retry_failed=True)
    assert again.runs == len(failed)
    assert all(t.ok for t in retried)
