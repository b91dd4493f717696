"""RobotMotion runs its update only when something changes or its desired segment ends: a
robot holding still costs no Python update until something changes, one cruising an update
per STEADY_HORIZON, not per period, and a command or a new safety scale is still taken at
the next period."""

import numpy as np
import pytest

from hrc_drake.messages import SUCCEEDED
from hrc_drake.motion.messages import Grip, MoveJoints, MoveTo, SetSpeed
from hrc_drake.motion.options import MotionOptions
from hrc_drake.motion.state_machine import STEADY_HORIZON
from hrc_drake.workpieces.messages import Despawn
from tests.motion.motion_helpers import build_station, make_scenario
from tests.motion.test_commands import LIGHT_ID, grasp, parts_on_the_table

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


def test_holding_still_runs_no_update_until_something_changes(station):
    station.simulator.AdvanceTo(0.1)
    q = station.q()
    assert _update_times(station, 1.0) == {0.0}  # the first update's segment holds on
    assert np.abs(station.q() - q).max() < 1e-6


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


def test_losing_the_held_object_is_taken_at_the_next_period_while_holding():
    """The object the robot holds still is despawned by a tree while its steady segment
    runs: RobotMotion notices at its next update, not when something else changes."""
    station = build_station(make_scenario(), workpieces=parts_on_the_table())
    for seq, command in enumerate((MoveTo(seq=1, pose=grasp("light")), Grip(seq=2)), start=1):
        station.command(command)
        assert station.run_until_finished(seq) == SUCCEEDED
    assert station.status().held_object == LIGHT_ID
    station.simulator.AdvanceTo(station.context.get_time() + STEADY_HORIZON)
    segment = station.motion.GetOutputPort("desired_segment")
    motion_context = station.motion.GetMyContextFromRoot(station.context)
    planned_at = segment.Eval(motion_context)[0]
    despawn = Despawn(seq=100, object_id=LIGHT_ID)
    station.diagram.GetInputPort("workpieces.robot_tree_command").FixValue(station.context, despawn)
    start = station.context.get_time()
    station.simulator.AdvanceTo(start + 2.5 * PERIOD)  # the workpieces' update, then ours
    assert station.status().held_object is None
    assert planned_at < start - STEADY_HORIZON / 2  # the segment ran on until then
