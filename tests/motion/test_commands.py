"""Command protocol: busy rejection, Stop, and the vacuum gripper with the workpieces."""

import numpy as np
import pytest
from pydrake.common.schema import Transform
from pydrake.math import RigidTransform, RollPitchYaw

from hrc_drake.messages import CANCELLED, FAILED, REJECTED, RUNNING, SUCCEEDED
from hrc_drake.motion.messages import IDLE, Grip, MoveJoints, MoveLinear, MoveTo, Release, Stop
from hrc_drake.workpieces.config import ObjectType, PlacedObject, WorkpiecesConfig
from tests.motion.motion_helpers import build_station, make_scenario

TOOL_DOWN = RollPitchYaw(np.pi, 0.0, 0.0)
TABLE_TOP = 0.9
PART_HEIGHT = 0.06
PARTS = {"light": (0.15, 0.4), "heavy": (-0.15, 0.4)}
"""Where the parts stand on the work table (x, y)."""
LIGHT_ID = 1
"""Workpieces number objects from 1 in the order they are placed."""
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
    assert station.status().results.result_of(2).outcome == REJECTED
    assert "busy" in station.status().results.result_of(2).reason
    assert station.status().results.outcome_of(1) == RUNNING
    station.command(Grip(seq=3))
    step(station)
    assert station.status().results.outcome_of(3) == REJECTED
    station.command(Stop(seq=4))
    step(station)
    assert station.status().results.outcome_of(1) == CANCELLED
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
    assert "no workpieces system" in station.status().results.last.reason


def parts_on_the_table() -> WorkpiecesConfig:
    config = WorkpiecesConfig(
        types={
            "light": ObjectType(size=[0.08, 0.08, PART_HEIGHT], mass=1.0),
            "heavy": ObjectType(size=[0.08, 0.08, PART_HEIGHT], mass=5.0),
        },
        objects=[
            PlacedObject(type=name, pose=Transform(translation=[x, y, TABLE_TOP + 0.05]))
            for name, (x, y) in PARTS.items()
        ],
    )
    return config


def grasp(name: str) -> RigidTransform:
    x, y = PARTS[name]
    return RigidTransform(TOOL_DOWN, [x, y, TABLE_TOP + PART_HEIGHT])


def test_grip_attaches_the_part_at_the_cup_within_payload():
    station = build_station(make_scenario(), workpieces=parts_on_the_table())
    commands = [
        (MoveTo(seq=1, pose=grasp("light")), SUCCEEDED, None),
        (Grip(seq=2), SUCCEEDED, LIGHT_ID),
        (Grip(seq=3), FAILED, LIGHT_ID),
        (MoveLinear(seq=4, pose=RigidTransform(TOOL_DOWN, [0.15, 0.4, 1.06])), SUCCEEDED, LIGHT_ID),
        (Release(seq=5), SUCCEEDED, None),
        (MoveTo(seq=6, pose=grasp("heavy")), SUCCEEDED, None),
        (Grip(seq=7), FAILED, None),
        (MoveJoints(seq=8, configuration="ready"), SUCCEEDED, None),
        (Grip(seq=9), FAILED, None),
    ]
    for command, outcome, held in commands:
        station.command(command)
        assert station.run_until_finished(command.seq) == outcome, (
            station.status().results.last.reason
        )
        assert station.status().held_object == held, command
    assert "already holding" in station.status().results.result_of(3).reason
