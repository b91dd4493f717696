"""With `avoid_person`, the planner treats the person where they stand as an obstacle:
a target next to them is refused, and a move past them goes around them."""

import dataclasses
import math
from pathlib import Path

import numpy as np
from pydrake.math import RigidTransform, RollPitchYaw
from pydrake.systems.analysis import Simulator

from hrc_drake.builder import build_diagram
from hrc_drake.messages import FAILED, SUCCEEDED
from hrc_drake.motion.messages import MoveTo
from hrc_drake.scenario import HumanConfig, load_scenario

CELL = Path(__file__).resolve().parents[1] / "station" / "cell.yaml"
PERSON_XY = (0.0, -0.7)
NEXT_TO_THE_PERSON = RigidTransform(RollPitchYaw(math.pi, 0.0, 0.0), [0.0, -0.4, 1.0])


def move_next_to_the_person(avoid_person: bool):
    scenario = load_scenario(CELL)
    motion = dataclasses.replace(scenario.robot.motion, avoid_person=avoid_person)
    scenario = dataclasses.replace(
        scenario,
        robot=dataclasses.replace(scenario.robot, motion=motion),
        human=HumanConfig(start=[*PERSON_XY, 90.0]),
        safety=dataclasses.replace(scenario.safety, enabled=False),
    )
    diagram = build_diagram(scenario)
    simulator = Simulator(diagram)
    context = simulator.get_context()
    diagram.GetInputPort("robot_motion.robot_tree_command").FixValue(
        context, MoveTo(1, NEXT_TO_THE_PERSON)
    )
    simulator.AdvanceTo(4.0)
    return diagram.GetOutputPort("robot_status").Eval(context)


def test_without_perception_the_planner_goes_next_to_the_person():
    status = move_next_to_the_person(avoid_person=False)
    assert status.results.outcome_of(1) == SUCCEEDED
    np.testing.assert_allclose(
        status.tool_pose.translation(), NEXT_TO_THE_PERSON.translation(), atol=2e-3
    )


def test_with_perception_a_target_at_the_person_is_refused():
    status = move_next_to_the_person(avoid_person=True)
    assert status.results.outcome_of(1) == FAILED
    assert "collision" in status.results.result_of(1).reason
