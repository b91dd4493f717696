"""The bad-input corpus's good scenario, its tree, and how a case is tried and judged.

Every case starts from the same small, valid scenario (and its robot tree), changes one
thing, runs one `hrc-drake` command in this process, and expects what the README
promises: exit status 2, exactly one line on stderr, `hrc-drake: error: ` and no
traceback, with the file, line and field (or node and port, or option) in it.
"""

from dataclasses import dataclass, field
from pathlib import Path

GOOD_SCENARIO = """\
name: corpus
description: The bad-input corpus's scenario.
seed: 0
duration: 0.2
plant: {time_step: 0.001}
robot:
  variant: lbr_iisy3_r760
  base_pose: {translation: [0.0, 0.0, 0.8]}
  configurations_deg:
    ready: [0, -45, 90, 0, 45, 0]
  motion: {period: 0.01, tool_speed_limit: 1.0}
cell:
  - add_model: {name: floor, file: package://hrc_drake_models/cell/floor.sdf}
  - add_weld: {parent: world, child: floor::body}
  - add_model: {name: work_table, file: package://hrc_drake_models/cell/work_table.sdf}
  - add_weld:
      parent: world
      child: work_table::body
      X_PC: {translation: [0.0, 0.7, 0.0]}
human:
  height: 1.75
  mass: 75.0
  start: [2.0, 2.0, 180.0]
workpieces:
  types:
    part: {shape: box, size: [0.08, 0.08, 0.06], mass: 0.3, capacity: 4}
safety:
  period: 0.01
  v_h: 1.6
  min_scale: 0.05
  sensing_time: 0.08
trees:
  robot: {file: robot.xml, period: 0.05}
parameters:
  speed: "0.5"
areas:
  table: [[-0.6, 0.3], [0.6, 0.3], [0.6, 1.1], [-0.6, 1.1]]
locations:
  pick_spot: {translation: [-0.2, 0.42, 0.93]}
  door: {translation: [2.0, 3.0, 0.0], rotation: !Rpy {deg: [0, 0, -90]}}
visualization:
  period: 0.05
  record: false
"""

GOOD_TREE = """\
<root BTCPP_format="4" main_tree_to_execute="Robot">
  <BehaviorTree ID="Robot">
    <Sequence>
      <SetRobotVelocity velocity="{speed}"/>
      <SubTree ID="Reach" at="pick_spot"/>
      <SubTree ID="Reach" at="pick_spot"/>
    </Sequence>
  </BehaviorTree>
  <BehaviorTree ID="Reach">
    <Sequence>
      <OffsetPose input="{at}" offset="0;0;0.1" output="{above}"/>
      <RobotMove target="{above}"/>
    </Sequence>
  </BehaviorTree>
</root>
"""


MOVE = '<RobotMove target="{above}"/>'
"""The good tree's move that the robot's cases extend."""
FOUND_GRASP = (
    '<NextObject area="table" filter="type=part" object_id="{p}" pose="{where}"/>'
    '<OffsetPose input="{where}" offset="0;0;0.03" output="{grasp}"/>'
    '<RobotMove target="{grasp}"/>'
)
"""The robot's move to the top of a part a NextObject finds on the work table."""


@dataclass
class Case:
    """One bad input: in `file` ("scenario.yaml" or "robot.xml") replace `old` by `new`;
    the error names the line holding `at` (a text of the changed file, or of `found_in`;
    None: no line) and contains every string of `says`. `files` are written beside (name ->
    text or bytes)."""

    file: str
    old: str
    new: str
    says: tuple[str, ...]
    at: str | None = None
    files: dict = field(default_factory=dict)
    found_in: str | None = None


def write_workspace(directory: Path, case: Case | None = None) -> Path:
    """The good scenario and tree in `directory`, with the case's change; returns the
    scenario's path."""
    texts = {"scenario.yaml": GOOD_SCENARIO, "robot.xml": GOOD_TREE}
    if case is not None:
        assert case.old in texts[case.file], f"the good {case.file} lacks {case.old!r}"
        texts[case.file] = texts[case.file].replace(case.old, case.new, 1)
        texts.update(case.files)
    for name, text in texts.items():
        data = text if isinstance(text, bytes) else text.replace("{dir}", str(directory))
        (directory / name).write_bytes(data if isinstance(data, bytes) else data.encode())
    return directory / "scenario.yaml"


def expected_place(directory: Path, case: Case) -> str:
    """`file:line:` of the case's `at` text, or `file` alone without one."""
    path = directory / (case.found_in or case.file)
    if case.at is None:
        return str(path)
    lines = path.read_text().splitlines()
    line = next(i for i, text in enumerate(lines, 1) if case.at in text)
    return f"{path}:{line}:"


def assert_one_line_error(status: int, err: str, *says: str, exit_status: int = 2) -> str:
    """The promise: the exit status, one line, our prefix, no traceback, the details."""
    assert status == exit_status, err
    assert "Traceback" not in err
    lines = err.splitlines()
    assert len(lines) == 1, err
    assert lines[0].startswith("hrc-drake: error: "), lines[0]
    assert "hrc-drake: error: hrc-drake" not in lines[0]
    for text in says:
        assert text in lines[0], f"{text!r} not in {lines[0]!r}"
    return lines[0]


MAIN_TREE_END = '    </Sequence>\n  </BehaviorTree>\n  <BehaviorTree ID="Reach">'
"""Where the good tree's main Sequence ends: a case's steps run once there, not in each of
the two runs of `Reach`."""
ROBOT_PUT_DOWN_INTO_THE_TABLE = Case(
    "robot.xml",
    MAIN_TREE_END,
    '<OffsetPose input="pick_spot" offset="0;0;0.1" output="{above}"/>'
    '<SpawnObject type="part" pose="pick_spot" object_id="{p}"/>'
    '<OffsetPose input="pick_spot" offset="0;0;0.03" output="{grasp}"/>'
    '<RobotMove target="{above}"/>'
    '<RobotMoveLinear target="{grasp}"/><RobotGrip/><RobotMoveLinear target="{above}"/>'
    '<RobotMove target="0.2;0.42;1.03"/><RobotMoveLinear target="0.2;0.42;0.93"/>'
    f"<RobotRelease/>\n{MAIN_TREE_END}",
    (
        "port 'target': '0.2;0.42;0.93' at (0.20, 0.42, 0.93): the part the robot lets go of "
        "there (its top at the tool) would be 3.0 cm into work_table (limit 1 cm; ",
        "raise the target to z = 0.960",
    ),
    'target="0.2;0.42;0.93"',
)
"""The robot takes a part it makes on the work table (top 0.9 m) and lets go of it with its
top at 0.93 m: the target given as the 6 cm part's centre puts it 3 cm into the table (a
user's `drop_spot`). Once, after the two runs of `Reach`: in `Reach`, the second part was let
go of into the first, which validate says too."""
