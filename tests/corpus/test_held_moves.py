"""The robot's free-space moves made holding a part are checked with the part hanging from
the tool, as the run plans them (the part kept as clear of the cell as the tool): a move to
a target made from what a NextObject finds (a place on a found pad), checked with the tool
alone, and a RobotMoveJoints to a named configuration, not checked at all, both passed
validate and failed in the run ("no collision-free ...", "target joint positions collide
with the cell", with the part the robot holds)."""

import numpy as np
import pytest

from hrc_drake.motion.errors import PlanningFailed
from hrc_drake.motion.messages import MoveJoints, MoveTo
from hrc_drake.motion.planner import MotionPlanner
from hrc_drake.nodes.robot import tool_pose
from hrc_drake.scenario.loading import load_scenario
from hrc_drake.scenario.robot_put_downs import hanging_from_the_tool
from hrc_drake.seeding import stream
from hrc_drake.tree_types import Pose
from hrc_drake.wiring import ROBOT_MOTION
from hrc_drake.workpieces.geometry import Solid
from tests.corpus import corpus_helpers as corpus

TAKE = corpus.FOUND_GRASP + '<RobotGrip/><RobotMoveLinear target="{above}"/>'
PAD_AT = (0.2, 0.42, 0.905)
LOW = [-64.5, -56.0, 64.3, 0, 81.6, 0]
"""Degrees: the iisy 3's tool pointing down 5 cm above the work table (top 0.9 m) at
(0.2, 0.42): the tool alone is clear of it, the 6 cm part hanging from it is not."""
TOUCHES = "the vacuum_gripper (or the part it holds) would touch work_table there"


def put_down(offset: str) -> str:
    """Take the part, then move over the pad the tree finds, `offset` above its centre."""
    return TAKE + (
        '<NextObject area="table" filter="type=pad" object_id="{d}" pose="{pad}"/>'
        f'<OffsetPose input="{{pad}}" offset="{offset}" output="{{drop}}"/>'
        '<RobotMove target="{drop}"/>'
    )


def scenario() -> str:
    """The corpus's scenario with a part at `pick_spot`, a 1 cm pad on the table at PAD_AT
    and the configuration `low`."""
    pad = "    pad: {shape: box, size: [0.1, 0.1, 0.01], mass: 0.1, capacity: 2}\n"
    objects = (
        f"{pad}  objects:\n"
        "    - {type: part, pose: {translation: [-0.2, 0.42, 0.93]}}\n"
        f"    - {{type: pad, pose: {{translation: {list(PAD_AT)}}}}}\nsafety:\n"
    )
    text = corpus.GOOD_SCENARIO.replace("safety:\n", objects, 1)
    return text.replace("    ready: [", f"    low: {LOW}\n    ready: [", 1)


def case(tree: str, says=(), at=None) -> corpus.Case:
    """The corpus's `Reach` subtree (run twice) doing `tree` and letting go of what it
    holds, so that the next run of it starts with the vacuum off."""
    new = corpus.MOVE + tree + "<RobotRelease/>"
    return corpus.Case("robot.xml", corpus.MOVE, new, says, at, {"scenario.yaml": scenario()})


def assert_says(tmp_path, hrc_drake, bad: corpus.Case) -> None:
    """validate finds the one mistake of `bad`, at its line."""
    status, _, err = hrc_drake("validate", corpus.write_workspace(tmp_path, bad))
    corpus.assert_one_line_error(status, err, corpus.expected_place(tmp_path, bad), *bad.says)


def test_a_move_to_a_found_target_is_checked_with_the_part_it_holds(tmp_path, hrc_drake):
    bad = case(
        put_down("0;0;0.045"),
        (
            "/RobotMove::",
            "port 'target': {drop} from pad in area 'table' at (0.20, 0.42, 0.91) made by "
            "OffsetPose (robot.xml:",
            ") at (0.20, 0.42, 0.95): with the part it holds, unreachable with the tool "
            f"pointing down: {TOUCHES}",
        ),
        '<RobotMove target="{drop}"/>',
    )
    assert_says(tmp_path, hrc_drake, bad)


def test_a_move_to_a_named_configuration_is_checked_with_the_part_it_holds(tmp_path, hrc_drake):
    bad = case(
        TAKE + '<RobotMoveJoints configuration="low"/>',
        (
            "/RobotMoveJoints::",
            f"port 'configuration': 'low': with the part it holds, {TOUCHES}",
        ),
        "<RobotMoveJoints",
    )
    assert_says(tmp_path, hrc_drake, bad)


@pytest.mark.parametrize(
    "tree",
    [put_down("0;0;0.1"), '<RobotMoveJoints configuration="low"/>' + TAKE],
    ids=["a found target high enough", "the configuration before the grip"],
)
def test_moves_the_part_makes_are_not_judged(tmp_path, hrc_drake, tree):
    status, _, err = hrc_drake("validate", corpus.write_workspace(tmp_path, case(tree)))
    assert status == 0, err


def test_the_run_refuses_what_validate_finds(tmp_path):
    """The run's planner, holding the part as validate has it hang, fails both moves; the
    arm alone makes them."""
    loaded = load_scenario(corpus.write_workspace(tmp_path, case("")))
    planner = MotionPlanner(loaded.station, loaded.robot.motion, stream(0, ROBOT_MOTION))
    part = hanging_from_the_tool(Solid.of(loaded.workpieces.types["part"]))
    over_the_pad, _ = tool_pose(Pose((PAD_AT[0], PAD_AT[1], PAD_AT[2] + 0.045)))
    start = loaded.station.initial_positions
    for command, refused in (
        (MoveTo(seq=1, pose=over_the_pad, free_tool_rotation=True), "no collision-free"),
        (MoveJoints(seq=2, configuration="low"), "collide with the cell"),
    ):
        assert planner.plan(command, start) is not None
        with pytest.raises(PlanningFailed, match=f"{refused}.*with the part the robot holds"):
            planner.plan(command, start, held=part)
    assert np.allclose(np.degrees(loaded.station.configuration("low")), LOW)
