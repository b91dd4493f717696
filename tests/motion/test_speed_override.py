"""Speed override: SetSpeed and the safety scale change the pace, never the path."""

import numpy as np
import pytest

from hrc_drake.iisy import VARIANTS
from hrc_drake.messages import FINISHED, RUNNING, SUCCEEDED
from hrc_drake.motion.messages import STOPPED, MoveJoints, SetSpeed
from hrc_drake.safety.stopping import StopModel
from tests.motion.motion_helpers import build_station, distance_to_polyline, make_scenario, record

VARIANT = "lbr_iisy3_r760"
GOAL = tuple(np.radians([70, -50, 60, 40, 60, 60]))
CHANGE_AT = 0.5
RESUME_AT = 1.5


def move(station):
    station.command(MoveJoints(seq=1, q=GOAL))


def run(actions):
    return record(build_station(make_scenario(VARIANT)), 1, {0.0: move, **actions})


@pytest.fixture(scope="module")
def reference():
    return run({})


@pytest.fixture(scope="module")
def half_speed():
    return run({CHANGE_AT: lambda s: s.command(SetSpeed(seq=2, fraction=0.5))})


@pytest.fixture(scope="module")
def safety_stop():
    return run(
        {
            CHANGE_AT: lambda s: s.set_safety_scale(0.0),
            RESUME_AT: lambda s: s.set_safety_scale(1.0),
        }
    )


@pytest.fixture(scope="module")
def slow_from_start():
    return record(
        build_station(make_scenario(VARIANT)),
        1,
        {0.0: lambda s: s.command(SetSpeed(seq=0, fraction=0.5)), 0.02: move},
    )


def succeeded_once(trace) -> bool:
    """Running until the end, then succeeded: no partial outcome on the way."""
    finished = [i for i, outcome in enumerate(trace.outcomes) if outcome in FINISHED]
    return trace.final == SUCCEEDED and all(trace.outcomes[i] == SUCCEEDED for i in finished)


def test_half_speed_keeps_the_path_and_doubles_the_remaining_time(reference, half_speed):
    assert succeeded_once(half_speed)
    ref, half = reference.arrays(), half_speed.arrays()
    assert distance_to_polyline(half["tool"], ref["tool"]).max() < 5e-3
    ratio = (half["t"][-1] - CHANGE_AT) / (ref["t"][-1] - CHANGE_AT)
    assert 1.7 < ratio < 2.2, ratio


def test_safety_stop_holds_on_the_path_and_resumes(reference, safety_stop):
    assert succeeded_once(safety_stop)
    ref, run_ = reference.arrays(), safety_stop.arrays()
    assert distance_to_polyline(run_["tool"], ref["tool"]).max() < 5e-3
    t = run_["t"]
    stop = StopModel.of_variant(VARIANT)
    stop_time = stop.time(1.0) + 0.02  # the next update receives the stop
    at_change = run_["tool"][np.searchsorted(t, CHANGE_AT)]
    held = run_["tool"][(t > CHANGE_AT + stop_time) & (t < RESUME_AT)]
    assert len(held) > 100
    assert np.linalg.norm(held - at_change, axis=1).max() < stop.distance(1.0, 1.0)
    assert np.linalg.norm(held - held[0], axis=1).max() < 5e-4
    assert STOPPED in run_["modes"][(t > CHANGE_AT + stop_time) & (t < RESUME_AT)]
    assert t[-1] > RESUME_AT


@pytest.mark.parametrize(
    "trace_name, scale",
    [("reference", 1.0), ("half_speed", 1.0), ("safety_stop", 1.0), ("slow_from_start", 0.5)],
)
def test_joint_limits_times_scale_hold_at_every_step(trace_name, scale, request):
    trace = request.getfixturevalue(trace_name).arrays()
    variant = VARIANTS[VARIANT]
    window = np.lib.stride_tricks.sliding_window_view(
        np.pad(trace["speed_scale"], 12, mode="edge"), 25
    ).max(axis=1)
    speed_ratio = np.abs(trace["velocity"]) / np.array(variant.velocity_limits)
    assert np.all(speed_ratio <= window[:, None] * (1 + 1e-9))
    assert np.all(trace["speed_scale"][trace["outcomes"] == RUNNING] <= scale + 1e-9)
    acceleration_ratio = np.abs(trace["acceleration"]) / np.array(variant.acceleration_limits)
    assert acceleration_ratio.max() <= scale
