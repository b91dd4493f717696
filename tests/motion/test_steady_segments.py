"""RobotMotion runs its update only when something changes or its desired segment ends: a
robot holding still or cruising costs a Python update per STEADY_HORIZON, not per period,
and a command or a new safety scale is still taken at the next period."""

import numpy as np
import pytest

from hrc_drake.messages import SUCCEEDED
from hrc_drake.motion.messages import MoveJoints, SetSpeed
from hrc_drake.motion.options import MotionOptions
from hrc_drake.motion.state_machine import STEADY_HORIZON
from tests.motion.motion_helpers import build_station, make_scenario

PERIOD = MotionOptions().period


@pytest.fixture()
def station():
    return build_station(make_scenario())


def _update_times(station, duration: float) -> set[float]:
    """The times of the updates that ran over `duration`, from the desired segment's start
    (the time of the last update that wrote it), sampled every period."""
    motion_context = station.motion.GetMyContextFromRoot(station.context)
    segment = station.motion.GetOutputPort("desired_segment")
    times = set()
    end = station.context.get_time() + duration
    while station.context.get_time() < end - 1e-9:
        station.simulator.AdvanceTo(station.context.get_time() + PERIOD)
        times.add(round(float(segment.Eval(motion_context)[0]), 6))
    return times


def test_holding_still_updates_once_per_horizon(station):
    station.simulator.AdvanceTo(0.1)
    assert len(_update_times(station, 0.4)) <= 0.4 / STEADY_HORIZON + 1


def test_a_command_is_taken_at_the_next_period_while_holding(station):
    station.simulator.AdvanceTo(0.1 + PERIOD / 2)  # inside a steady segment
    station.command(SetSpeed(seq=1, fraction=0.5))
    station.simulator.AdvanceTo(0.1 + 1.5 * PERIOD)
    assert station.status().results.outcome_of(1) == SUCCEEDED


def test_a_safety_scale_change_is_taken_at_the_next_period_while_cruising(station):
    station.command(MoveJoints(seq=1, configuration="ready"))
    station.simulator.AdvanceTo(0.6)  # moving along the path
    assert station.velocity_norm() > 0.1
    station.set_safety_scale(0.0)
    station.simulator.AdvanceTo(0.6 + PERIOD + 1e-6)
    assert station.status().safety_scale == 0.0
    assert station.status().speed_scale < 1.0  # braking from the next update on


def test_cruising_skips_updates_and_the_move_arrives(station):
    station.command(MoveJoints(seq=1, configuration="ready"))
    station.simulator.AdvanceTo(0.2)
    times = _update_times(station, 0.6)
    assert len(times) < 0.6 / PERIOD  # some periods carried by a longer segment
    assert station.run_until_finished(1) == SUCCEEDED
    assert np.abs(station.q() - np.radians([0, -45, 90, 0, 45, 0])).max() < 1e-3
