"""MoveLinear keeps the tool on the straight line (approach and retreat)."""

import numpy as np
from pydrake.math import RigidTransform, RollPitchYaw

from hrc_drake.messages import FAILED, SUCCEEDED
from hrc_drake.motion.messages import MoveLinear, MoveTo
from tests.motion.motion_helpers import build_station, distance_to_polyline, make_scenario, record

ABOVE = RigidTransform(RollPitchYaw(np.pi, 0.0, 0.3), [0.1, 0.35, 1.05])
DOWN = 0.1


def test_approach_and_retreat_stay_on_the_line():
    station = build_station(make_scenario())
    station.command(MoveTo(seq=1, pose=ABOVE))
    assert station.run_until_finished(1) == SUCCEEDED, station.status().results.last.reason
    start = station.tool_pose().translation()
    approach = RigidTransform(ABOVE.rotation(), ABOVE.translation() - [0.0, 0.0, DOWN])
    for seq, target in ((2, approach), (3, ABOVE)):
        trace = record(
            station,
            seq,
            {
                station.context.get_time(): lambda s, t=target, n=seq: s.command(
                    MoveLinear(seq=n, pose=t)
                )
            },
        )
        assert trace.final == SUCCEEDED, station.status().results.last.reason
        line = np.array([start, target.translation()])
        assert distance_to_polyline(trace.arrays()["tool"], line).max() < 5e-3
        assert np.linalg.norm(station.tool_pose().translation() - target.translation()) < 2e-3
        start = target.translation()


def test_line_through_the_table_fails_with_reason():
    station = build_station(make_scenario())
    station.command(MoveTo(seq=1, pose=ABOVE))
    assert station.run_until_finished(1) == SUCCEEDED
    into_table = RigidTransform(ABOVE.rotation(), ABOVE.translation() - [0.0, 0.0, 0.3])
    station.command(MoveLinear(seq=2, pose=into_table))
    assert station.run_until_finished(2) == FAILED
    assert "linear move" in station.status().results.last.reason
