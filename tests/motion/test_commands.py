"""Command protocol: busy rejection, Stop, and the vacuum gripper against a test double."""

import numpy as np
import pytest
from motion_helpers import build_station, make_scenario
from pydrake.math import RigidTransform, RollPitchYaw
from workpieces_double import GripperDouble, Part

from hrc_drake.messages import CANCELLED, FAILED, REJECTED, RUNNING, SUCCEEDED
from hrc_drake.motion.messages import IDLE, Grip, MoveJoints, MoveTo, Release, Stop

TOOL_DOWN = RollPitchYaw(np.pi, 0.0, 0.0)
LIGHT = Part("light_part", RigidTransform(TOOL_DOWN, [0.35, 0.2, 1.0]), mass=1.0)
HEAVY = Part("heavy_part", RigidTransform(TOOL_DOWN, [0.35, -0.2, 1.0]), mass=5.0)
FAR_GOAL = tuple(np.radians([90, -50, 60, 40, 60, 60]))


def step(station, seconds=0.02):
    station.simulator.AdvanceTo(station.context.get_time() + seconds)


@pytest.fixture
def station():
    return build_station(make_scenario())


def test_move_while_moving_is_rejected_and_stop_cancels(station):
    station.command(MoveJoints(seq=1, q=FAR_GOAL))
    step(station, 0.3)
    station.command(MoveJoints(seq=2, configuration="ready"))
    step(station)
    assert station.status().result_of(2).outcome == REJECTED
    assert "busy" in station.status().result_of(2).reason
    assert station.status().outcome_of(1) == RUNNING
    station.command(Grip(seq=3))
    step(station)
    assert station.status().outcome_of(3) == REJECTED
    station.command(Stop(seq=4))
    step(station)
    assert station.status().outcome_of(1) == CANCELLED
    assert station.run_until_finished(4) == SUCCEEDED
    assert station.status().mode == IDLE
    stopped_at = station.q()
    step(station, 0.3)
    assert np.abs(station.q() - stopped_at).max() < 1e-3
    station.command(MoveJoints(seq=5, configuration="home"))
    assert station.run_until_finished(5) == SUCCEEDED


def test_grip_without_workpieces_system_fails(station):
    station.command(Grip(seq=1))
    assert station.run_until_finished(1) == FAILED
    assert "no workpieces system" in station.status().reason


def test_grip_attaches_the_part_at_the_cup_within_payload():
    station = build_station(make_scenario(), workpieces=GripperDouble([LIGHT, HEAVY]))
    commands = [
        (MoveTo(seq=1, pose=LIGHT.grasp), SUCCEEDED, None),
        (Grip(seq=2), SUCCEEDED, "light_part"),
        (Grip(seq=3), FAILED, "light_part"),
        (Release(seq=4), SUCCEEDED, None),
        (MoveTo(seq=5, pose=HEAVY.grasp), SUCCEEDED, None),
        (Grip(seq=6), FAILED, None),
        (MoveJoints(seq=7, configuration="ready"), SUCCEEDED, None),
        (Grip(seq=8), FAILED, None),
    ]
    for command, outcome, held in commands:
        station.command(command)
        assert station.run_until_finished(command.seq) == outcome, station.status().reason
        assert station.status().held_object == held
    assert "too heavy" in station.status().result_of(6).reason
    assert "no object" in station.status().result_of(8).reason
