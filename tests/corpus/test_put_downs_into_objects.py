"""A user's palletizing cell (palletizing_cell/: an iisy stacks cartons off the belt onto
the pallet, two layers of four, touching, a SubTree per slot) had two mistakes validate
missed: a slot 10 cm from its neighbour and a second-layer slot at the first layer's height.
The run refused each at the move after minutes of simulation ("... would be 5.0 cm into
carton 2 resting there"); validate now says where the part the robot lets go of lies inside
a carton an earlier put-down left, or one lying there at the start, whichever way either is
turned (the run turns what it holds to fit beside the objects)."""

import shutil
from pathlib import Path

import pytest
from pydrake.math import RigidTransform

from hrc_drake.motion.errors import PlanningFailed
from hrc_drake.motion.messages import MoveTo
from hrc_drake.motion.model import RestingObject
from hrc_drake.motion.planner import MotionPlanner
from hrc_drake.nodes.robot import tool_pose
from hrc_drake.scenario.loading import load_scenario
from hrc_drake.scenario.robot_put_downs import hanging_from_the_tool
from hrc_drake.seeding import stream
from hrc_drake.tree_types import Pose
from hrc_drake.wiring import ROBOT_MOTION
from hrc_drake.workpieces.geometry import Solid
from tests.corpus import corpus_helpers as corpus

PALLETIZING = Path(__file__).resolve().parent / "palletizing_cell"
BESIDE = Path(__file__).resolve().parents[1] / "motion" / "cells" / "carton_beside_carton"
SLOT_3_NEAR = (
    "cell.yaml",
    "slot_3: {translation: [0.95, -0.2, 0.299]}",
    "slot_3: {translation: [0.75, 0.0, 0.299]}",
)
"""The first mistake: slot_3 10 cm from slot_2 (the cartons 30 cm long)."""
SLOT_6_LOW = (
    "cell.yaml",
    "slot_6: {translation: [0.65, 0.0, 0.449]}",
    "slot_6: {translation: [0.65, 0.0, 0.299]}",
)
"""The second: slot_6, over slot_2 in the second layer, at the first layer's height."""
PUT_DOWN = '<RobotMoveLinear target="{slot}"/>'
"""The Stack subtree's move that sets the carton down, with its top at the slot."""
LIMIT = "turned any way about the tool's axis (limit 1 cm): move the target beside it or onto it"


def cell(tmp_path: Path, source: Path = PALLETIZING, *changes: tuple[str, str, str]) -> Path:
    """`source`'s cell in `tmp_path` with each (file, old, new) change made; its scenario."""
    for path in source.iterdir():
        shutil.copy(path, tmp_path / path.name)
    for name, old, new in changes:
        text = (tmp_path / name).read_text()
        assert old in text, f"{name} lacks {old!r}"
        (tmp_path / name).write_text(text.replace(old, new, 1))
    return tmp_path / "cell.yaml"


def inline(robot_xml: str) -> str:
    """The palletizing tree with each slot's steps written out in the main Sequence, the
    slot a literal of its moves, as a user writes a pattern without a SubTree."""
    body = robot_xml.split('<BehaviorTree ID="Stack">\n    <Sequence>\n')[1]
    steps = body.split("    </Sequence>")[0]
    main = robot_xml.split('<BehaviorTree ID="Stack">')[0]
    for slot in range(1, 9):
        main = main.replace(
            f'<SubTree ID="Stack" slot="slot_{slot}"/>', steps.replace("{slot}", f"slot_{slot}")
        )
    return main + "</root>\n"


def assert_says(tmp_path, hrc_drake, scenario: Path, at: str, *says: str) -> None:
    """validate finds one mistake, at the tree's line holding `at`."""
    status, _, err = hrc_drake("validate", scenario)
    lines = (tmp_path / "robot.xml").read_text().splitlines()
    line = next(i for i, text in enumerate(lines, 1) if at in text)
    corpus.assert_one_line_error(status, err, f"{tmp_path / 'robot.xml'}:{line}:", *says)


@pytest.mark.parametrize(
    "change, says",
    [
        (
            SLOT_3_NEAR,
            "location 'slot_3' (robot.xml:6) at (0.75, 0.00, 0.30): the carton the robot lets go "
            "of there (its top at the tool) would lie 10.0 cm inside the carton put down at "
            f"location 'slot_2' (robot.xml:5), {LIMIT}",
        ),
        (
            SLOT_6_LOW,
            "location 'slot_6' (robot.xml:9) at (0.65, 0.00, 0.30): the carton the robot lets go "
            "of there (its top at the tool) would lie 15.0 cm inside the carton put down at "
            f"location 'slot_2' (robot.xml:5), {LIMIT}",
        ),
    ],
    ids=["a slot 10 cm from its neighbour", "a second-layer slot at the first layer's height"],
)
def test_a_slot_into_a_carton_put_down_before_is_found(tmp_path, hrc_drake, change, says):
    scenario = cell(tmp_path, PALLETIZING, change)
    assert_says(tmp_path, hrc_drake, scenario, PUT_DOWN, "/RobotMoveLinear::", says)


def test_the_pattern_written_out_without_a_subtree_is_judged_too(tmp_path, hrc_drake):
    scenario = cell(tmp_path, PALLETIZING, SLOT_3_NEAR)
    (tmp_path / "robot.xml").write_text(inline((tmp_path / "robot.xml").read_text()))
    assert_says(
        tmp_path,
        hrc_drake,
        scenario,
        '<RobotMoveLinear target="slot_3"/>',
        "port 'target': location 'slot_3' (robot.xml:",
        "would lie 10.0 cm inside the carton put down at location 'slot_2' (robot.xml:",
    )


def test_a_put_down_into_a_carton_lying_there_at_the_start_is_found(tmp_path, hrc_drake):
    """carton_beside_carton's slot 10 cm nearer the carton already on the pallet."""
    into = "s2: {translation: [0.65, 0.0, 0.299]}"
    scenario = cell(tmp_path, BESIDE, ("cell.yaml", "s2: {translation: [0.65, 0.1, 0.299]}", into))
    assert_says(
        tmp_path,
        hrc_drake,
        scenario,
        '<RobotMoveLinear target="s2"/>',
        "port 'target': location 's2' (robot.xml:",
        "would lie 10.0 cm inside the carton lying there at the start "
        f"(workpieces.objects[1].pose), {LIMIT}",
    )


TURNED = (
    "cell.yaml",
    "s2: {translation: [0.65, 0.1, 0.299]}",
    "s2: {translation: [0.9, -0.1, 0.299]}",
)
"""carton_beside_carton's slot 25 cm from the 30 cm carton's middle along its length: the
30 x 20 cm carton lies 5 cm inside it as the tool holds it, beside it turned a quarter turn,
as the run turns it."""


CLEARED = (
    (
        "cell.yaml",
        "areas:\n",
        "areas:\n  pallet: [[0.3, -0.8], [1.1, -0.8], [1.1, 0.4], [0.3, 0.4]]\n",
    ),
    (
        "robot.xml",
        '<SubTree ID="Stack" slot="slot_6"/>',
        '<CountObjects area="pallet" filter="" count="{n}"/><SubTree ID="Stack" slot="slot_6"/>',
    ),
)
"""The tree counts the cartons on the pallet before slot_6: it may wait for it to be cleared
(by the person), so what the put-downs before left is not known to lie there."""


@pytest.mark.parametrize(
    "source, changes, written_out",
    [
        (PALLETIZING, (), False),
        (PALLETIZING, (), True),
        (BESIDE, (), False),
        (BESIDE, (TURNED,), False),
        (PALLETIZING, (SLOT_6_LOW, *CLEARED), False),
    ],
    ids=[
        "the pattern",
        "the pattern written out",
        "a carton beside another",
        "fits turned",
        "the pallet may be cleared",
    ],
)
def test_cartons_set_down_touching_are_not_judged(
    tmp_path, hrc_drake, source, changes, written_out
):
    scenario = cell(tmp_path, source, *changes)
    if written_out:
        (tmp_path / "robot.xml").write_text(inline((tmp_path / "robot.xml").read_text()))
    status, _, err = hrc_drake("validate", scenario)
    assert (status, err) == (0, "")


def test_the_run_refuses_the_slot_validate_finds(tmp_path):
    """The run's planner, with the carton put down at slot_2 resting there and the next one
    hanging from the tool, refuses the free-space move over slot_3 10 cm from it (10 cm
    above the slot, as the tree moves): the message the run fails the user's cell with."""
    scenario = cell(tmp_path, PALLETIZING, SLOT_3_NEAR)
    loaded = load_scenario(scenario)
    planner = MotionPlanner(loaded.station, loaded.robot.motion, stream(0, ROBOT_MOTION))
    carton = Solid.of(loaded.workpieces.types["carton"])
    on_slot_2 = RestingObject(carton, RigidTransform([0.65, 0.0, 0.224]), "carton 2")
    over_slot_3, _ = tool_pose(Pose((0.75, 0.0, 0.399)))
    command = MoveTo(seq=1, pose=over_slot_3, free_tool_rotation=True)
    held = hanging_from_the_tool(carton)
    start = loaded.station.initial_positions
    with pytest.raises(PlanningFailed, match=r"cm into carton 2 resting there \(limit 1 cm\)"):
        planner.plan(command, start, held=held, objects=(on_slot_2,))
