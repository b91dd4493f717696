"""The planner skips the solves of tool poses its arm is too short for (ArmLength): it must
never skip a pose some joint positions reach, and every pose it skips must be one the
solves would not have reached either, so the answers stay the same, only sooner."""

import numpy as np
import pytest
from pydrake.math import RigidTransform

from hrc_drake.iisy import VARIANTS
from hrc_drake.motion.ik import ArmLength
from hrc_drake.motion.model import PlanningModel
from hrc_drake.motion.planner import MotionPlanner
from hrc_drake.nodes.robot import TOOL_DOWN
from hrc_drake.seeding import stream
from hrc_drake.wiring import ROBOT_MOTION
from tests.motion.motion_helpers import make_scenario


@pytest.fixture(scope="module", params=sorted(VARIANTS))
def planner(request) -> MotionPlanner:
    scenario = make_scenario(request.param)
    return MotionPlanner(scenario.station, scenario.robot.motion, stream(0, ROBOT_MOTION))


def test_no_pose_the_arm_takes_lies_beyond_its_length(planner):
    """Tool poses of random joint positions (stretched ones too, A3 near straight): none
    is beyond, and the stretched ones come within 6 % of the length: the bound is near (the
    iisy 3 and 15 reach it; the iisy 11's offsets, at right angles to its links, keep its
    farthest wrist 3 % short)."""
    model, arm = planner.model, planner.ik.arm_length
    rng = np.random.default_rng(0)
    postures = rng.uniform(model.lower, model.upper, (400, model.lower.size))
    stretched = postures.copy()
    stretched[:, 2] = rng.uniform(-0.1, 0.1, len(postures)) + _straight_elbow(model, arm)
    reach = []
    for q in np.vstack([postures, stretched]):
        pose = model.tool_pose(np.clip(q, model.lower, model.upper))
        assert not arm.beyond(pose), q
        reach.append(arm.wrist_distance(pose))
    assert max(reach) > 0.94 * arm.length


def test_a_pose_beyond_is_one_no_solve_reaches(planner):
    """Just beyond the length, straight out from the shoulder and tilted: every start of the
    planner's budget, solved as before the bound, fails."""
    arm = planner.ik.arm_length
    shoulder_radius, shoulder_height = arm.shoulder
    for azimuth in (0.0, 2.0):
        for rise in (-0.3, 0.0, 0.3):
            distance = arm.length + arm.slack + 0.005
            radial = shoulder_radius + distance * np.cos(rise)
            wrist = arm.axis_point + (shoulder_height + distance * np.sin(rise)) * arm.axis
            wrist = wrist + radial * np.array([np.cos(azimuth), np.sin(azimuth), 0.0])
            tcp = wrist - arm.wrist_along * TOOL_DOWN.matrix()[:, 2]
            pose = RigidTransform(TOOL_DOWN, tcp)
            assert arm.beyond(pose)
            assert _solved_without_the_bound(planner, pose) is None


def _straight_elbow(model: PlanningModel, arm: ArmLength) -> float:
    """The A3 angle that puts the wrist farthest from the shoulder (others at home)."""
    angles = np.linspace(model.lower[2], model.upper[2], 721)
    q = np.array(model.variant.home)
    reach = []
    for angle in angles:
        q[2] = angle
        reach.append(arm.wrist_distance(model.tool_pose(q)))
    return float(angles[int(np.argmax(reach))])


def _solved_without_the_bound(planner: MotionPlanner, pose: RigidTransform):
    ik = planner.ik
    beyond, ik.arm_length.beyond = ik.arm_length.beyond, lambda pose: False
    try:
        rng = np.random.default_rng(planner.seed)
        q_start = planner.station.initial_positions
        return ik.kinematic_solution(pose, q_start, True, rng, planner.options.ik_attempts)
    finally:
        ik.arm_length.beyond = beyond
