"""Workpieces beside the real robot: the tool pose comes from the plant's body poses; the
person's hands come from HumanActor's status."""

import numpy as np
import pytest
from pydrake.common.eigen_geometry import Quaternion
from pydrake.math import RigidTransform
from pydrake.multibody.parsing import Parser
from pydrake.multibody.plant import AddMultibodyPlant, MultibodyPlantConfig
from pydrake.systems.analysis import Simulator
from pydrake.systems.framework import DiagramBuilder

from hrc_drake.human.messages import HumanStatus
from hrc_drake.iisy import TCP_FRAME, VARIANTS
from hrc_drake.messages import NO_COMMANDS, SUCCEEDED, CommandResult
from hrc_drake.paths import add_model_package
from hrc_drake.seeding import stream
from hrc_drake.station import StationSpec, add_robot
from hrc_drake.systems.adapters import HumanHands, hand_poses
from hrc_drake.systems.workpieces import add_workpieces
from hrc_drake.wiring import TOOL_MODEL, WORKPIECES_SYSTEM
from hrc_drake.workpieces.messages import ROBOT_HOLDER, Attach, Spawn
from tests.workpieces.workpieces_rig import PART_HEIGHT, TimedValue, config_with, script


@pytest.fixture(scope="module")
def station():
    """The iisy 3 with its vacuum gripper at home (no gravity, so it holds still), a part
    spawned under the cup, and the vacuum switched on as RobotMotion's Grip does."""
    builder = DiagramBuilder()
    plant, scene_graph = AddMultibodyPlant(MultibodyPlantConfig(time_step=1e-3), builder)
    parser = Parser(plant)
    add_model_package(parser.package_map())
    robot = StationSpec("lbr_iisy3_r760", base_pose=RigidTransform([0, 0, 0.75]))
    arm = add_robot(plant, parser, robot)
    plant.mutable_gravity_field().set_gravity_vector([0.0, 0.0, 0.0])
    plant.Finalize()
    plant.SetDefaultPositions(arm, VARIANTS[robot.variant].home)
    tcp = plant.GetFrameByName(TCP_FRAME, plant.GetModelInstanceByName(TOOL_MODEL))
    X_WT = tcp.CalcPoseInWorld(plant.CreateDefaultContext())
    under_cup = RigidTransform(X_WT.translation() - [0.0, 0.0, PART_HEIGHT / 2])
    seed = stream(0, WORKPIECES_SYSTEM)
    workpieces = add_workpieces(builder, scene_graph, plant, config_with(), seed, tool_frame=tcp)
    spawn = builder.AddSystem(TimedValue(script([(0.0, Spawn(1, "part", under_cup))]), NO_COMMANDS))
    builder.Connect(spawn.get_output_port(), workpieces.GetInputPort("robot_tree_command"))
    grip = Attach(seq=5, holder=ROBOT_HOLDER, max_mass=3.0)
    vacuum = builder.AddSystem(TimedValue(script([(0.005, grip)]), NO_COMMANDS))
    builder.Connect(vacuum.get_output_port(), workpieces.GetInputPort("robot_gripper_command"))
    diagram = builder.Build()
    simulator = Simulator(diagram)
    simulator.AdvanceTo(0.5)
    context = simulator.get_context()
    status = workpieces.GetOutputPort("workpieces_status").Eval(
        workpieces.GetMyContextFromRoot(context)
    )
    return X_WT, status


def test_the_tool_pose_is_the_plants_tcp_and_the_vacuum_attaches_the_part_under_it(station):
    X_WT, status = station
    assert status.results_of("robot_gripper").last == CommandResult(5, SUCCEEDED, object_id=1)
    part = status.object(1)
    assert part.holder == ROBOT_HOLDER and part.mass == 0.4
    top_centre = part.pose.translation() + [0.0, 0.0, PART_HEIGHT / 2]
    assert np.linalg.norm(top_centre - X_WT.translation()) < 2e-3


def test_human_status_hands_become_hand_poses():
    status = HumanStatus(
        left_hand=(1, 2, 3, 1, 0, 0, 0), right_hand=(4, 5, 6, 0, 0, 0, 1), time=2.0
    )
    hands = hand_poses(status)
    assert hands.time == 2.0
    np.testing.assert_allclose(hands.left.translation(), [1, 2, 3])
    expected = RigidTransform(Quaternion(0, 0, 0, 1), [4, 5, 6])
    assert hands.right.IsNearlyEqualTo(expected, 1e-12)
    assert hand_poses(HumanStatus()) is None


def test_the_hands_follow_each_new_status_and_stay_the_same_object_while_it_is_the_same():
    """Workpieces takes hands of the same identity for an unchanged person (it keeps their
    grasp frames), so a new status must give new hands and the same status the same."""
    hands = HumanHands()
    context = hands.CreateDefaultContext()
    port, output = hands.get_input_port(), hands.get_output_port()
    still = HumanStatus(left_hand=(1, 2, 3, 1, 0, 0, 0), right_hand=(4, 5, 6, 1, 0, 0, 0))
    port.FixValue(context, still)
    first = output.Eval(context)
    port.FixValue(context, still)
    assert output.Eval(context) is first
    moved = HumanStatus(left_hand=(1, 2, 4, 1, 0, 0, 0), right_hand=(4, 5, 6, 1, 0, 0, 0))
    port.FixValue(context, moved)
    np.testing.assert_allclose(output.Eval(context).left.translation(), [1, 2, 4])
    port.FixValue(context, HumanStatus())
    assert output.Eval(context) == ()
