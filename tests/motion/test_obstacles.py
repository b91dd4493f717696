"""A target behind a box on the table is reached without touching anything on the way."""

import numpy as np
from pydrake.math import RigidTransform, RollPitchYaw

from hrc_drake.messages import SUCCEEDED
from hrc_drake.motion.messages import MoveTo
from hrc_drake.wiring import ROBOT_MODEL, TOOL_MODEL
from tests.motion.motion_helpers import build_station, make_scenario

BOX_AT = (0.3, 0.35)
BEHIND_THE_BOX = RigidTransform(RollPitchYaw(np.pi, 0.0, 0.0), [-0.1, 0.42, 0.96])


def robot_cell_distance(station) -> float:
    """Smallest signed distance between the robot (arm, tool) and the rest of the scene."""
    query = station.diagram.GetOutputPort("query_object").Eval(station.context)
    inspector = query.inspector()

    def on_robot(geometry) -> bool:
        model = inspector.GetName(inspector.GetFrameId(geometry)).split("::")[0]
        return model in (ROBOT_MODEL, TOOL_MODEL)

    distances = [
        pair.distance
        for pair in query.ComputeSignedDistancePairwiseClosestPoints(0.2)
        if on_robot(pair.id_A) != on_robot(pair.id_B)
    ]
    return min(distances, default=np.inf)


def test_target_behind_box_is_reached_around_it():
    station = build_station(make_scenario(box_at=BOX_AT))
    planner = station.motion.planner
    q_start = station.q()
    q_goal = planner.ik.solve(BEHIND_THE_BOX, q_start, False, np.random.default_rng(0), 16)
    assert not planner.model.edge_collision_free(q_start, q_goal), "the straight path must collide"

    closest = []
    station.command(MoveTo(seq=1, pose=BEHIND_THE_BOX))
    outcome = station.run_until_finished(
        1, on_step=lambda s: closest.append(robot_cell_distance(s))
    )
    assert outcome == SUCCEEDED, station.status().results.last.reason
    assert min(closest) > 0.0
    assert max(closest) - min(closest) > 0.01  # the queried scene follows the moving robot
    assert np.linalg.norm(station.tool_pose().translation() - BEHIND_THE_BOX.translation()) < 2e-3


def test_apart_answers_as_every_pair_measured_does():
    """`apart` measures only the nearest pairs; near contact and in it, it answers as the
    nearest of every pair of the robot and the cell (and itself) within a metre does."""
    model = build_station(make_scenario(box_at=BOX_AT)).motion.planner.model
    rng = np.random.default_rng(3)
    start = np.asarray(make_scenario(box_at=BOX_AT).station.initial_positions)
    found = []
    for _ in range(400):
        q = np.clip(start + rng.normal(scale=0.6, size=start.size), model.lower, model.upper)
        distances = model.checker.CalcRobotClearance(q, 1.0).distances()
        nearest = distances.min() if distances.size else np.inf
        found.append(model.apart(q))
        assert found[-1] == (nearest > 0.0), nearest
    assert 20 < sum(found) < len(found) - 20, "both answers are tried"
