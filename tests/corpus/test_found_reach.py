"""The robot's moves to targets made from what a NextObject finds are checked for reach
against every object the scenario places where it looks: a user's kitting cell (#26) took
parts off shelf boards the robot cannot reach, validate said ok, and the run failed the
RobotMove 50 times ("no collision-free inverse kinematics solution"). One line per move
with objects the robot cannot reach; the objects it reaches, and offsets another branch of
a Fallback sets for what it finds there, are not judged."""

from tests.corpus.corpus_helpers import (
    FOUND_GRASP,
    GOOD_SCENARIO,
    MOVE,
    Case,
    assert_one_line_error,
    expected_place,
    write_workspace,
)

TAKE = FOUND_GRASP


def scenario(far="[0.0, 1.0, 0.93]", types="") -> str:
    """The corpus's scenario with object `types` added and two parts on its work table: one
    where the robot's `pick_spot` is, one at `far` (by default 1 m from the robot's base
    axis, beyond the iisy 3's reach)."""
    parts = (
        f"{types}  objects:\n"
        "    - {type: part, pose: {translation: [-0.2, 0.42, 0.93]}}\n"
        f"    - {{type: part, pose: {{translation: {far}}}}}\nsafety:\n"
    )
    return GOOD_SCENARIO.replace("safety:\n", parts, 1)


def test_a_found_part_the_robot_cannot_reach_is_named_at_the_move(tmp_path, hrc_drake):
    case = Case(
        "robot.xml",
        MOVE,
        MOVE + TAKE,
        (
            "/RobotMove::",
            "port 'target': {grasp} from part in area 'table' at (0.00, 1.00, 0.93) made by "
            "OffsetPose (robot.xml:",
            ") at (0.00, 1.00, 0.96): out of reach with the tool pointing down: 1.00 m from "
            "its base axis",
        ),
        '<RobotMove target="{grasp}"/>',
        {"scenario.yaml": scenario()},
    )
    status, _, err = hrc_drake("validate", write_workspace(tmp_path, case))
    line = assert_one_line_error(status, err, expected_place(tmp_path, case), *case.says)
    assert "(-0.20, 0.42" not in line  # the part it reaches is not named


def test_offsets_set_for_what_another_branch_finds_are_not_judged(tmp_path, hrc_drake):
    """A Fallback finds a tote (none lies on the table) and sets a high offset for it, or a
    part and a low one: the part is judged with its own offset alone, 1 m above it out of
    reach."""
    tote = "    tote: {shape: box, size: [0.3, 0.4, 0.15], mass: 1.5, capacity: 4}\n"
    tree = (
        "<Fallback><Sequence>"
        '<NextObject area="table" filter="type=tote" object_id="{p}" pose="{where}"/>'
        '<SetBlackboard output_key="up" value="0;0;1.0"/></Sequence><Sequence>'
        '<NextObject area="table" filter="type=part" object_id="{p}" pose="{where}"/>'
        '<SetBlackboard output_key="up" value="0;0;0.03"/></Sequence></Fallback>'
        '<OffsetPose input="{where}" offset="{up}" output="{grasp}"/>'
        '<RobotMove target="{grasp}"/>'
    )
    case = Case(
        "robot.xml",
        MOVE,
        MOVE + tree,
        (),
        None,
        {"scenario.yaml": scenario("[0.1, 0.42, 0.93]", tote)},
    )
    status, _, err = hrc_drake("validate", write_workspace(tmp_path, case))
    assert status == 0, err


def test_the_parts_a_move_cannot_reach_are_one_line_at_the_move(tmp_path, hrc_drake):
    """A user's wrong shelf gave 36 lines, one per part and move: each move now says it once,
    naming the first part and where the others lie."""
    third = "    - {type: part, pose: {translation: [0.3, 1.0, 0.93]}}\nsafety:\n"
    case = Case(
        "robot.xml",
        MOVE,
        MOVE + TAKE,
        (
            "port 'target': {grasp} from part in area 'table' at (0.00, 1.00, 0.93) made by ",
            "; nor 1 more of its targets, at (0.30, 1.00, 0.96)",
        ),
        '<RobotMove target="{grasp}"/>',
        {"scenario.yaml": scenario().replace("safety:\n", third, 1)},
    )
    status, _, err = hrc_drake("validate", write_workspace(tmp_path, case))
    assert_one_line_error(status, err, expected_place(tmp_path, case), *case.says)


def test_a_part_the_tree_makes_where_the_robot_cannot_reach_is_named_at_the_move(
    tmp_path, hrc_drake
):
    """A user's machine made its parts with a SpawnObject at a location 0.4 m too far from
    the robot: validate judged only the parts lying there at the start (none), said ok, and
    the run failed the RobotMove 4 times. The part it makes is judged as one lying there."""
    made = '<SpawnObject type="part" pose="0.0;1.0;0.93" object_id="{made}"/>' + TAKE
    case = Case(
        "robot.xml",
        MOVE,
        MOVE + made,
        (
            "/RobotMove::",
            "port 'target': {grasp} from part made at '0.0;1.0;0.93' (SpawnObject at ",
            "in area 'table' at (0.00, 1.00, 0.93) made by OffsetPose (robot.xml:",
            ") at (0.00, 1.00, 0.96): out of reach with the tool pointing down: 1.00 m from "
            "its base axis",
        ),
        '<RobotMove target="{grasp}"/>',
        {"scenario.yaml": scenario(far="[0.2, 0.42, 0.93]")},  # both parts within reach
    )
    status, _, err = hrc_drake("validate", write_workspace(tmp_path, case))
    assert_one_line_error(status, err, expected_place(tmp_path, case), *case.says)
