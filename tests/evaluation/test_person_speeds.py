"""The person's speeds as a run records them (safety.npz's `walking_speed` and
`human_approach`, timeline.png's speeds panel; docs/safety.md): in the getting-started cell
the person turns, walks 4 m to the window at a normal pace and stands there looking round.
The walking speed is checked against the realism audit's stride speeds, which come from
another path (the person's own status, not the scene's geometry)."""

import numpy as np
import pytest

from hrc_drake.evaluation.metrics import WAITING_SPEED
from hrc_drake.evaluation.report import evaluate
from hrc_drake.evaluation.timeline import timeline_figure
from hrc_drake.runner import simulate
from hrc_drake.safety.log import log_of
from hrc_drake.scenario import load_scenario

WALKING = (2.0, 4.0)
"""s: the person walks steadily towards the window (sets off at 1 s, arrives at 4.5 s)."""
STANDING = (4.75, 7.0)
"""s: arrived, turned to the window and looking round."""
WALKING_PACE = 1.6
"""m/s: ISO 13855's walking speed; a normal pace is 1.2-1.4 m/s (docs/realism.md)."""


@pytest.fixture(scope="module")
def record():
    return simulate(load_scenario("getting_started", [("duration", 7.0)]))


def during(log: dict, span: tuple[float, float], name: str) -> np.ndarray:
    return log[name][(log["time"] >= span[0]) & (log["time"] < span[1])]


def test_the_walking_speed_is_the_pace_of_the_walk_and_zero_standing(record):
    log = log_of(record.signals)
    strides = evaluate(record)["realism"]["pelvis_speed"]
    assert strides["strides"] >= 1
    walking = during(log, WALKING, "walking_speed")
    assert np.median(walking) == pytest.approx(strides["mean_speed"], rel=0.05)
    assert log["walking_speed"].max() <= WALKING_PACE
    assert during(log, STANDING, "walking_speed").max() < WAITING_SPEED


def test_the_timeline_shows_the_persons_two_speeds(record):
    import matplotlib.pyplot as plt

    log = log_of(record.signals)
    fig = timeline_figure(record.signal_times, record.signals)
    lines = {line.get_label(): line.get_ydata() for line in fig.axes[2].lines}
    np.testing.assert_array_equal(lines["person: walking (pelvis)"], log["walking_speed"])
    closest = lines["person: closest region towards the robot"]
    np.testing.assert_array_equal(closest, log["human_approach"])
    assert "person speed" not in lines
    plt.close(fig)
