"""RobotMotion holds, moves to joint targets, and reports every command's outcome."""

import numpy as np
import pytest

from hrc_drake.messages import FAILED, REJECTED, SUCCEEDED
from hrc_drake.motion.messages import IDLE, MoveJoints, SetSpeed, Stop
from tests.motion.motion_helpers import build_station, make_scenario


@pytest.fixture(scope="module")
def station():
    return build_station(make_scenario())


def test_holds_initial_configuration_without_commands(station):
    home = station.q()
    station.simulator.AdvanceTo(station.context.get_time() + 0.5)
    assert np.abs(station.q() - home).max() < 1e-4
    status = station.status()
    assert status.mode == IDLE and status.results.last is None and status.speed_scale == 1.0


def test_move_joints_to_named_configuration_and_back(station):
    station.command(MoveJoints(seq=1, configuration="ready"))
    assert station.run_until_finished(1) == SUCCEEDED
    assert np.abs(station.q() - np.radians([0, -45, 90, 0, 45, 0])).max() < 1e-3
    station.command(MoveJoints(seq=2, configuration="home"))
    assert station.run_until_finished(2) == SUCCEEDED


def test_unknown_configuration_fails_with_reason(station):
    station.command(MoveJoints(seq=3, configuration="nowhere"))
    assert station.run_until_finished(3) == FAILED
    assert "unknown configuration 'nowhere'" in station.status().results.last.reason


def test_bad_speed_is_rejected_and_stop_when_idle_succeeds(station):
    station.command(SetSpeed(seq=4, fraction=1.5))
    assert station.run_until_finished(4) == REJECTED
    station.command(Stop(seq=5))
    assert station.run_until_finished(5) == SUCCEEDED
