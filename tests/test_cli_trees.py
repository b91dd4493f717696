"""The CLI's tree commands: the node palette, Groot2's TreeNodesModel, tree rendering, and
`validate` catching tree mistakes with file, line, node and port."""

import subprocess
import sys
from pathlib import Path

from hrc_drake.bt import tree_nodes_model_xml
from hrc_drake.nodes import hrc_registry
from hrc_drake.paths import resource_dir

ROOT = Path(__file__).resolve().parents[1]
CELL = ROOT / "tests" / "station" / "cell.yaml"
ORIGINAL_NODES = {
    "GenerateXYPose": {"area", "pose"},
    "InAreaTest": {"pose", "area"},
    "OffsetPose": {"input", "offset", "orientation", "output"},
    "InterruptableSequence": set(),
    "WeightedRandom": {"weights"},
    "IsCalled": set(),
    "SetCalledTo": {"state"},
    "RandomFailure": {"failure_chance"},
    "ActorAnimation": {"animation_name", "animation_speed"},
    "ActorMovement": {"animation_name", "animation_distance", "target"},
    "RobotMove": {"target"},
    "SetRobotVelocity": {"velocity"},
}


def hrc_drake(*args, cwd=ROOT):
    return subprocess.run(
        [sys.executable, "-m", "hrc_drake.cli", *map(str, args)],
        capture_output=True,
        text=True,
        cwd=cwd,
    )


def test_the_original_nodes_keep_their_names_and_ports():
    registry = hrc_registry()
    for node, ports in ORIGINAL_NODES.items():
        assert set(registry[node].ports) == ports, node


def test_list_nodes_prints_every_node_with_its_ports():
    result = hrc_drake("list", "--nodes")
    assert result.returncode == 0
    for node in ORIGINAL_NODES:
        assert f"\n{node} (" in "\n" + result.stdout
    assert "input  target: Pose" in result.stdout


def test_shipped_palette_is_the_registry(tmp_path):
    shipped = (resource_dir("trees") / "hrc_nodes.xml").read_text()
    assert shipped == tree_nodes_model_xml(hrc_registry()) + "\n", (
        "trees/hrc_nodes.xml is stale: run `hrc-drake list --nodes --xml trees/hrc_nodes.xml`"
    )
    written = tmp_path / "palette.xml"
    assert hrc_drake("list", "--nodes", "--xml", written).returncode == 0
    assert written.read_text() == shipped


def test_tree_renders_a_scenario_tree(tmp_path):
    scenario = _scenario_with_trees(tmp_path, "call_robot.xml")
    out = tmp_path / "robot.svg"
    result = hrc_drake("tree", scenario, "--agent", "robot", "-o", out)
    assert result.returncode == 0, result.stderr
    assert "SetCalledTo" in out.read_text()


def test_validate_names_file_line_node_and_port_of_tree_mistakes(tmp_path):
    tree = tmp_path / "bad.xml"
    tree.write_text(
        '<root BTCPP_format="4" main_tree_to_execute="Robot">\n'
        '  <BehaviorTree ID="Robot">\n'
        "    <Sequence>\n"
        '      <RobotMvoe target="table_front"/>\n'
        "    </Sequence>\n"
        "  </BehaviorTree>\n"
        "</root>\n"
    )
    result = hrc_drake("validate", _scenario_with_trees(tmp_path, tree))
    assert result.returncode == 2
    assert "Traceback" not in result.stderr
    assert f"{tree}:4:" in result.stderr
    assert "did you mean 'RobotMove'?" in result.stderr


def test_validate_reports_places_the_scenario_does_not_have(tmp_path):
    tree = tmp_path / "nowhere.xml"
    tree.write_text(
        '<root BTCPP_format="4"><BehaviorTree ID="Robot">\n'
        '<RobotMove target="nowhere"/>\n'
        "</BehaviorTree></root>\n"
    )
    result = hrc_drake("validate", _scenario_with_trees(tmp_path, tree))
    assert result.returncode == 2
    assert f"{tree}:2:" in result.stderr
    assert "port 'target'" in result.stderr
    assert "unknown location 'nowhere'" in result.stderr


def _scenario_with_trees(tmp_path, robot_tree) -> Path:
    robot_tree = Path(robot_tree)
    if not robot_tree.is_absolute():
        robot_tree = CELL.parent / "trees" / robot_tree
    scenario = tmp_path / "scenario.yaml"
    scenario.write_text(
        CELL.read_text().replace("name: test_cell", "name: cli_test")
        + f"trees:\n  robot: {{file: {robot_tree}}}\n"
    )
    return scenario


def test_list_names_the_shared_subtrees_and_a_users_cell_includes_a_copy(tmp_path):
    """A user's cell used the bundled CallPersonAndWait by including it by the absolute path
    of a checkout: `list` now says where the shared SubTrees are and how to use them, and a
    copy included as it says is what validate loads."""
    listed = hrc_drake("list").stdout.splitlines()
    (heading,) = [line for line in listed if line.startswith("shared SubTrees (in ")]
    common = Path(heading.removeprefix("shared SubTrees (in ").split(";")[0])
    assert (
        "  call_person.xml    CallPerson, CallPersonAndWait," in listed[listed.index(heading) + 1]
    )
    (tmp_path / "common").mkdir()
    (tmp_path / "common" / "call_person.xml").write_text((common / "call_person.xml").read_text())
    cell = ROOT / "tests" / "motion" / "cells" / "set_down_into_a_part"
    for name in ("cell.yaml", "human.xml"):
        (tmp_path / name).write_text((cell / name).read_text())
    (tmp_path / "robot.xml").write_text(
        '<root BTCPP_format="4" main_tree_to_execute="Robot">\n'
        '  <include path="common/call_person.xml"/>\n'
        '  <BehaviorTree ID="Robot">\n'
        '    <SubTree ID="CallPersonAndWait" reason="help"/>\n'
        "  </BehaviorTree>\n"
        "</root>\n"
    )
    result = hrc_drake("validate", tmp_path / "cell.yaml")
    assert result.returncode == 0, result.stderr
    assert "trees robot: robot.xml" in result.stdout
