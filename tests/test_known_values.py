"""What a tree's ports will read, known before it runs: followed from the scenario's
entries and the SubTrees' literals through SubTree remapping and OffsetPose, never
guessed where the world decides (a pose NextObject finds)."""

import pytest

from hrc_drake.agent_trees import AgentTree, load_agent_tree, sections
from hrc_drake.areas import Area
from hrc_drake.known_values import known_inputs
from hrc_drake.nodes.agent import Places
from hrc_drake.tree_types import Pose

TREE = """\
<root BTCPP_format="4" main_tree_to_execute="Main">
  <BehaviorTree ID="Main">
    <Sequence>
      <SubTree ID="Lift" spot="{=}" by="0;0;0.1"/>
      <SubTree ID="Lift" spot="{other}" by="0;0;0.2"/>
      <NextObject area="table" pose="{found}"/>
      <RobotMove name="to_found" target="{found}"/>
      <SetRobotVelocity velocity="{speed}"/>
      <SetBlackboard output_key="goal" value="0.5;0;1"/>
      <RobotMove name="to_goal" target="{goal}"/>
    </Sequence>
  </BehaviorTree>
  <BehaviorTree ID="Lift">
    <Sequence>
      <OffsetPose input="{spot}" offset="{by}" output="{up}"/>
      <RobotMove name="lifted" target="{up}"/>
    </Sequence>
  </BehaviorTree>
</root>
"""


def known(tmp_path) -> dict[str, list]:
    """The known values of every input, by node name and port."""
    (tmp_path / "robot.xml").write_text(TREE)
    places = Places(
        locations={"spot": Pose((0.4, 0.0, 0.9)), "other": Pose((0.0, 0.4, 0.8))},
        areas={"table": Area.from_polygon([[0, 0], [1, 0], [1, 1]])},
    )
    config = AgentTree(str(tmp_path / "robot.xml"))
    tree, _ = load_agent_tree(config, "robot", places, {"speed": "0.5"})
    found: dict[str, list] = {}
    for node, port, values in known_inputs(tree, sections(places)):
        found.setdefault(f"{node.name}.{port}", []).extend(values)  # a name per SubTree use
    return found


def test_values_followed_through_subtree_remapping_and_offset_pose(tmp_path):
    found = known(tmp_path)
    lifted = found["lifted.target"]
    assert [k.value.position for k in lifted] == [
        pytest.approx((0.4, 0.0, 1.0)),
        pytest.approx((0.0, 0.4, 1.0)),
    ]
    assert [str(k) for k in lifted] == [
        "the value OffsetPose (robot.xml:15) made from location 'spot'",
        "the value OffsetPose (robot.xml:15) made from location 'other'",
    ]
    assert [str(k) for k in found["SetRobotVelocity.velocity"]] == ["parameter 'speed'"]
    assert found["SetRobotVelocity.velocity"][0].value == 0.5


def test_a_value_set_blackboard_copies_reads_as_the_port_reads_it(tmp_path):
    (goal,) = known(tmp_path)["to_goal.target"]
    assert goal.value == Pose((0.5, 0.0, 1.0))
    assert str(goal) == "the value SetBlackboard (robot.xml:9) made from '0.5;0;1'"


def test_what_the_world_decides_is_not_known(tmp_path):
    assert "to_found.target" not in known(tmp_path)
