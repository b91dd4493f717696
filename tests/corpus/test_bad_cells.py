"""Mistakes only a run used to show (a node failing over and over, a person inside a table,
a 60 m box), which `hrc-drake validate` now finds before anything is simulated: each is one
line naming the file, the line and the field (or the tree's node and port), saying what was
probably meant, and exit status 2. On the code before these checks, validate passed every
one of them."""

import json
from dataclasses import replace
from pathlib import Path

import pytest

from tests.corpus.corpus_helpers import (
    GOOD_SCENARIO,
    GOOD_TREE,
    ROBOT_PUT_DOWN_INTO_THE_TABLE,
    Case,
    assert_one_line_error,
    expected_place,
    write_workspace,
)

S, T, H = "scenario.yaml", "robot.xml", "human.xml"
MODELS = Path(__file__).resolve().parents[2] / "models"
MOVE = '<RobotMove target="{above}"/>'
PERSON = """\
<root BTCPP_format="4" main_tree_to_execute="Human">
  <BehaviorTree ID="Human">
    <Sequence>
      <ActorMovement target="door"/>
      <ActorAnimation animation_name="wave"/>
    </Sequence>
  </BehaviorTree>
</root>
"""
ROBOT_TREE = "  robot: {file: robot.xml, period: 0.05}\n"
OBJECTS = "  objects:\n"
PART_ON_TABLE = "    - {type: part, pose: {translation: [0.0, 0.6, 0.93]}}\n"

A_SHELF = (
    "human:\n",
    "  - add_model: {name: shelf, file: package://hrc_drake_models/cell/shelf.sdf}\n"
    "  - add_weld: {parent: world, child: shelf::body, X_PC: {translation: [3.0, 0.55, 0.0]}}\n"
    "human:\n",
)
"""Our shelf (boards at 0.1, 0.6, 1.1 and 1.6 m), its front 0.35 m beyond y = 0."""
A_SHELF_FRONT = (
    "locations:\n",
    "locations:\n  shelf_front: {translation: [3.0, 0.0, 0.0], rotation: !Rpy {deg: [0, 0, 90]}}\n",
)
"""Where the person stands facing the shelf, 0.35 m from it."""

A_TOTE_ON_THE_TABLE = (
    "safety:\n",
    "    tote: {shape: box, size: [0.3, 0.4, 0.15], mass: 1.5, capacity: 4}\n"
    f"{OBJECTS}    - {{type: tote, pose: {{translation: [0.0, 0.6, 0.976]}}}}\n"
    "safety:\n",
)
"""A tote (0.4 m deep) on the work table."""

A_SHELF_BEFORE_THE_ROBOT = (
    "  - add_model: {name: shelf, file: package://hrc_drake_models/cell/shelf.sdf}\n"
    "  - add_weld: {parent: world, child: shelf::body, X_PC: {translation: [0.5, 0.0, 0.0]}}\n"
    "human:\n"
)
"""Our shelf along the robot's x axis, its 1.1 m board where the tool is in the iisy 3's home
(the tool's tip at x = 0.37 m, z = 0.96 m)."""

ON_A_PEDESTAL = GOOD_SCENARIO.replace(
    "variant: lbr_iisy3_r760", "variant: lbr_iisy15_r930"
).replace(
    "cell:\n",
    "cell:\n  - add_model: {name: pedestal, file: package://hrc_drake_models/cell/robot_pedestal.sdf}\n"
    "  - add_weld: {parent: world, child: pedestal::body}\n",
)
"""The corpus's cell with an iisy 15 on its pedestal (its first link turns 9 mm above it)."""

ISLAND = "".join(
    f"  - add_model: {{name: {name}, file: package://hrc_drake_models/cell/work_table.sdf}}\n"
    f"  - add_weld: {{parent: world, child: {name}::body, X_PC: {{translation: {xyz}{turn}}}}}\n"
    for name, xyz, turn in (
        ("left_table", [-1.0, 1.7, 0.0], ", rotation: !Rpy {deg: [0, 0, 90]}"),
        ("right_table", [1.0, 1.7, 0.0], ", rotation: !Rpy {deg: [0, 0, 90]}"),
        ("back_table", [0.0, 2.7, 0.0], ""),
    )
)
"""Three more work tables that close a square with the corpus's work table round (0, 1.7)."""


def two_fences(gap: float) -> str:
    """Two fences (2 m long) in a line along y = 2.5 between the person's start (2, 2) and
    the door (2, 3), `gap` apart from x = 1.9 on: the way round them is 5 m or more."""
    return "".join(
        f"  - add_model: {{name: {name}, file: package://hrc_drake_models/cell/fence.sdf}}\n"
        f"  - add_weld: {{parent: world, child: {name}::body, "
        f"X_PC: {{translation: [{x}, 2.5, 0]}}}}\n"
        for name, x in (("fence_a", 0.9), ("fence_b", 2.9 + gap))
    )


def person(old: str, new: str, says: tuple[str, ...], at: str, changes=(), files=None) -> Case:
    """The corpus scenario (with its texts `changes`d, old -> new, and `files` beside it)
    with a person whose tree (PERSON) has `old` replaced by `new`."""
    tree = PERSON.replace(old, new)
    assert tree != PERSON
    trees = f"{ROBOT_TREE}  human: {{file: {H}}}\n"
    written = {H: tree, **(files or {})}
    if changes:
        scenario = GOOD_SCENARIO
        for before, after in changes:
            assert before in scenario
            scenario = scenario.replace(before, after, 1)
        written[S] = scenario.replace(ROBOT_TREE, trees)
    return Case(S, ROBOT_TREE, trees, says, at, written, H)


def own_clip(name: str) -> str:
    """A clip of the scenario's own: the built-in wave under another name."""
    clip = json.loads((MODELS / "human" / "animations" / "wave.json").read_text())
    return json.dumps({**clip, "name": name})


CASES = {
    # --- the robot's targets, as its tree resolves them ---
    "location out of reach, through a SubTree and OffsetPose": Case(
        S,
        "pick_spot: {translation: [-0.2, 0.42, 0.93]}",
        "pick_spot: {translation: [-0.2, 0.95, 0.93]}",
        (
            "tree 'Reach', node 'Reach::",
            "/RobotMove::",
            "port 'target': the value OffsetPose (robot.xml:11) made from location 'pick_spot' "
            "at (-0.20, 0.95, 1.03): out of reach with the tool pointing down: 0.97 m from its "
            "base axis at z = 1.03 m, where the lbr_iisy3_r760 reaches 0.",
            "m closer)",
        ),
        MOVE,
        found_in=T,
    ),
    "literal target out of reach": Case(
        T,
        MOVE,
        f'{MOVE}<RobotMoveLinear target="0.9;-0.3;1.0"/>',
        (
            "port 'target': '0.9;-0.3;1.0' at (0.90, -0.30, 1.00): out of reach with the tool "
            "pointing down: 0.95 m from its base axis at z = 1.00 m, where",
        ),
        "0.9;-0.3;1.0",
    ),
    "target under the table": Case(
        T,
        MOVE,
        f'{MOVE}<RobotMoveLinear target="0.3;0.5;0.6"/>',
        (
            "port 'target': '0.3;0.5;0.6' at (0.30, 0.50, 0.60): unreachable with the tool "
            "pointing down: the link_2, link_3, link_4, link_5 and link_6 would touch work_table",
        ),
        "0.3;0.5;0.6",
    ),
    "target inside the table": Case(
        S,
        "pick_spot: {translation: [-0.2, 0.42, 0.93]}",
        "pick_spot: {translation: [-0.2, 0.42, 0.78]}",
        (
            "port 'target': the value OffsetPose (robot.xml:11) made from location 'pick_spot' "
            "at (-0.20, 0.42, 0.88): unreachable with the tool pointing down: the "
            "vacuum_gripper would touch work_table there",
        ),
        MOVE,
        found_in=T,
    ),
    "a rotation that turns the tool up": Case(
        S,
        "pick_spot: {translation: [-0.2, 0.42, 0.93]}",
        "pick_spot: {translation: [-0.2, 0.42, 0.93], rotation: !Rpy {deg: [0, 0, 90]}}",
        (
            "port 'target': the value OffsetPose (robot.xml:11) made from location 'pick_spot' "
            "at (-0.20, 0.42, 1.03): ",
            "with the tool turned as given",
            "(this rotation points the tool up: for the tool pointing down give "
            "!Rpy {deg: [180, 0, 0]}, or no rotation)",
        ),
        MOVE,
        found_in=T,
    ),
    "an object made inside the table": Case(
        T,
        MOVE,
        f'{MOVE}<SpawnObject type="part" pose="0.3;0.6;0.88"/>',
        ("port 'pose': '0.3;0.6;0.88' at (0.30, 0.60, 0.88) lies 0.020 m inside work_table",),
        "0.3;0.6;0.88",
    ),
    "an object type none of which can be made": Case(
        S,
        "capacity: 4}",
        "capacity: 0}",
        ("port 'type': object type 'part' has capacity 0: none can ever be made",),
        '<SpawnObject type="part"',
        {T: GOOD_TREE.replace(MOVE, f'{MOVE}<SpawnObject type="part" area="table"/>')},
        T,
    ),
    "unknown configuration": Case(
        T,
        MOVE,
        f'{MOVE}<RobotMoveJoints configuration="raedy"/>',
        ("port 'configuration': unknown configuration 'raedy' (did you mean 'ready'?)",),
        "raedy",
    ),
    "unknown object type": Case(
        T,
        MOVE,
        f'{MOVE}<SpawnObject type="prat" pose="pick_spot"/>',
        ("port 'type': unknown object type 'prat' (did you mean 'part'?); known: part",),
        "prat",
    ),
    "unknown object type in a filter": Case(
        T,
        MOVE,
        f'{MOVE}<NextObject area="table" filter="type=prat" object_id="{{id}}"/>',
        ("port 'filter': unknown object type 'prat' (did you mean 'part'?)",),
        "prat",
    ),
    "unknown area to spawn in": Case(
        T,
        MOVE,
        f'{MOVE}<SpawnObject type="part" area="tabel"/>',
        ("port 'area': unknown area 'tabel' (did you mean 'table'?)",),
        "tabel",
    ),
    # --- the person's tree ---
    "unknown animation": person(
        'animation_name="wave"',
        'animation_name="assemble"',
        (
            "port 'animation_name': no animation named 'assemble'; the person's clips: carry, "
            "hand_over, idle, inspect,",
        ),
        "assemble",
    ),
    "animation near a known one": person(
        'animation_name="wave"',
        'animation_name="wav"',
        ("no animation named 'wav' (did you mean 'wave'?)",),
        "wav",
    ),
    "animation near one of the scenario's own clips": person(
        'animation_name="wave"',
        'animation_name="strech"',
        ("no animation named 'strech' (did you mean 'stretch'?)", "stretch, turn_left"),
        "strech",
        changes=[("human:\n", "human:\n  clips: [stretch.json]\n")],
        files={"stretch.json": own_clip("stretch")},
    ),
    "walking with a clip that does not walk": person(
        '<ActorMovement target="door"/>',
        '<ActorMovement target="door" animation_name="inspect"/>',
        ("'inspect' is not a walking animation (the person walks with: carry, walk)",),
        "inspect",
    ),
    "a place to walk to inside the table": person(
        '<ActorMovement target="door"/>',
        '<OffsetPose input="door" offset="-2;-2.3;0" output="{spot}"/>\n'
        '      <ActorMovement target="{spot}"/>',
        (
            "port 'target': the value OffsetPose (human.xml:4) made from location 'door': "
            "(0.00, 0.70) lies within the floor outline of "
            "work_table: the nearest place with room to stand and turn is [0.00, 1.43]",
        ),
        '<ActorMovement target="{spot}"',
    ),
    "a pick from a place to stand inside the table (judged from where the walk ends)": replace(
        person(
            '<ActorAnimation animation_name="wave"/>',
            '<ActorMovement target="in_table"/>'
            '<NextObject area="table" filter="type=part" object_id="{p}" pose="{at}"/>'
            '<ActorPick object_id="{p}"/>',
            (
                "locations.in_table: (0.00, 1.00) lies within the floor outline of work_table: "
                "the nearest place with room to stand and turn is [0.00, 1.43]",
            ),
            "ActorMovement",
            changes=[
                ("safety:\n", f"{OBJECTS}{PART_ON_TABLE}safety:\n"),
                (
                    "locations:\n",
                    "locations:\n  in_table: {translation: [0.0, 1.0, 0.0], "
                    "rotation: !Rpy {deg: [0, 0, -90]}}\n",
                ),
            ],
        ),
        at="in_table:",
        found_in=S,
    ),
    "a place to walk to without room to turn": person(
        '<ActorMovement target="door"/>',
        '<OffsetPose input="door" offset="-2;-1.75;0" output="{spot}"/>\n'
        '      <ActorMovement target="{spot}"/>',
        (
            "port 'target': the value OffsetPose (human.xml:4) made from location 'door': "
            "a person at (0.00, 1.25) facing -90°, turning on the spot, reaches 0.18 m into "
            "work_table: the nearest place with room to stand and turn is [0.00, 1.43]",
        ),
        '<ActorMovement target="{spot}"',
    ),
    "a place to walk to closed in by tables": person(
        '<ActorMovement target="door"/>',
        '<ActorMovement target="0;1.7;0"/>',
        (
            "port 'target': '0;1.7;0': no walk from the person's start [2.00, 2.00] to "
            "[0.00, 1.70] keeps clear of the cell (the gaps on the way are narrower than a "
            "walking person, or the robot's inner working space closes them)",
        ),
        "0;1.7;0",
        changes=[("human:\n", f"{ISLAND}human:\n")],
    ),
    "a place to walk to closed in by tables but for gaps a little too narrow": person(
        '<ActorMovement target="door"/>',
        '<ActorMovement target="0;1.7;0"/>',
        (
            "port 'target': '0;1.7;0': no walk from the person's start [2.00, 2.00] to "
            "[0.00, 1.70] keeps clear of the cell (the gap between 'right_table' and "
            "'back_table' is 0.70 m, 0.76 m needed)",
        ),
        "0;1.7;0",
        changes=[("human:\n", f"{ISLAND.replace('[0.0, 2.7, 0.0]', '[0.0, 3.4, 0.0]')}human:\n")],
    ),
    "a walk round a gap a little too narrow": person(
        '<ActorMovement target="door"/>',
        '<ActorMovement target="2.0;1.9;0"/>\n      <ActorMovement target="door"/>',
        (
            "port 'target': location 'door': the walk from [2.00, 1.90] to [2.00, 3.00] "
            "goes round: 5.5 m for 1.1 m straight; the gap between 'fence_a' and 'fence_b' "
            "is 0.70 m, 0.76 m needed",
        ),
        '<ActorMovement target="door"/>',
        changes=[("human:\n", f"{two_fences(0.7)}human:\n")],
    ),
    "a place to stand without room to turn": Case(
        S,
        "door: {translation: [2.0, 3.0, 0.0]",
        "door: {translation: [0.0, 1.3, 0.0]",
        (
            "locations.door: a person at (0.00, 1.30) facing -90°, turning on the spot, "
            "reaches 0.13 m into work_table: the nearest place with room to stand and turn is "
            "[0.00, 1.43]",
        ),
        "door:",
    ),
    # --- the robot's start and configurations ---
    "the robot's base moved away from its target": Case(
        S,
        "base_pose: {translation: [0.0, 0.0, 0.8]}",
        "base_pose: {translation: [0.0, -0.5, 0.8]}",
        (
            "port 'target': the value OffsetPose (robot.xml:11) made from location 'pick_spot' "
            "at (-0.20, 0.42, 1.03): out of reach with the tool pointing down: 0.94 m from its "
            "base axis at z = 1.03 m, where the lbr_iisy3_r760 reaches 0.52 m (move it 0.42 m "
            "closer)",
        ),
        MOVE,
        found_in=T,
    ),
    "a robot on the table, its base in the table top": Case(
        S,
        "base_pose: {translation: [0.0, 0.0, 0.8]}",
        "base_pose: {translation: [0.0, 0.7, 0.88]}",
        (
            "robot.base_pose: the robot's base at (0.00, 0.70, 0.88) lies 0.020 m below the top "
            "of work_table (to stand on it: z = 0.900)",
        ),
        "base_pose:",
    ),
    "configuration beyond a joint limit": Case(
        S,
        "ready: [0, -45, 90, 0, 45, 0]",
        "ready: [0, -45, 200, 0, 45, 0]",
        (
            "robot.configurations_deg.ready: outside the joint limits: joint 3 at 200° "
            "(limits -150 to 150°)",
        ),
        "ready:",
    ),
    "configuration in the table": Case(
        S,
        "ready: [0, -45, 90, 0, 45, 0]",
        "ready: [-90, -45, 90, 0, 45, 0]",
        (
            "robot.configurations_deg.ready: the link_6 and vacuum_gripper would touch "
            "work_table there",
        ),
        "ready:",
    ),
    "configuration in the table, the arm on its pedestal": Case(
        S,
        "ready: [0, -45, 90, 0, 45, 0]",
        "ready: [-90, -45, 90, 0, 45, 0]",
        (
            "robot.configurations_deg.ready: the vacuum_gripper would touch work_table there",
        ),  # not the first link, which always turns just above the pedestal
        "ready:",
        files={
            S: ON_A_PEDESTAL.replace(
                "ready: [0, -45, 90, 0, 45, 0]", "ready: [-90, -45, 90, 0, 45, 0]"
            )
        },
    ),
    "the robot's start, its home, in a shelf": Case(
        S,
        "human:\n",
        A_SHELF_BEFORE_THE_ROBOT,
        (
            "robot.initial_configuration: home, where the robot starts: the link_2, link_6 "
            "and vacuum_gripper would touch shelf there",
        ),  # every move of the run failed: "the robot starts closer to the cell than ..."
        "variant:",
        files={
            S: GOOD_SCENARIO.replace("human:\n", A_SHELF_BEFORE_THE_ROBOT, 1).replace(
                "ready: [0, -45, 90, 0, 45, 0]", "ready: [180, -45, 90, 0, 45, 0]"
            )
        },
    ),
    # --- the cell at the start ---
    "person starts inside the table": Case(
        S,
        "start: [2.0, 2.0, 180.0]",
        "start: [0.0, 0.8, 180.0]",
        (
            "human.start: (0.00, 0.80) lies within the floor outline of work_table: the "
            "nearest place with room to stand and turn is [0.00, 1.43]",
        ),
        "start:",
    ),
    "object inside the table": Case(
        S,
        "safety:\n",
        f"{OBJECTS}    - {{type: part, pose: {{translation: [0.0, 0.6, 0.88]}}}}\nsafety:\n",
        (
            "workpieces.objects[0].pose: the part at (0.00, 0.60, 0.88) starts 0.050 m inside "
            "work_table (to rest on it, raise its centre 0.050 m to z = 0.930)",
        ),
        "translation: [0.0, 0.6, 0.88]",
    ),
    "objects inside each other": Case(
        S,
        "safety:\n",
        f"{OBJECTS}{PART_ON_TABLE * 2}safety:\n",
        (
            "workpieces.objects[0].pose: the part at (0.00, 0.60, 0.93) starts 0.060 m inside "
            "the part at (0.00, 0.60, 0.93)",
        ),
        "translation: [0.0, 0.6, 0.93]",
    ),
    # --- magnitudes ---
    "sizes in millimetres": Case(
        S,
        "size: [0.08, 0.08, 0.06]",
        "size: [80, 80, 60]",
        (
            "workpieces.types.part.size: [80, 80, 60] m is larger than a workcell (sizes are in "
            "metres: [0.08, 0.08, 0.06] for millimetres?)",
        ),
        "size: [80",
    ),
    "mass in grams": Case(
        S,
        "mass: 0.3",
        "mass: 300",
        (
            "workpieces.types.part.mass: 300 kg is more than a person may lift (23 kg, the "
            "NIOSH load constant)",
            "0.3 for grams?",
        ),
        "mass: 300",
    ),
    "belt speed in mm/s": Case(
        S,
        "safety:\n",
        "  conveyors:\n    belt: {start: [1, -1, 0.9], end: [2, -1, 0.9], speed: 250}\nsafety:\n",
        ("workpieces.conveyors.belt.speed: 250 m/s is faster than any belt", "0.25 for mm/s?"),
        "speed: 250",
    ),
    "location in millimetres": Case(
        S,
        "translation: [2.0, 3.0, 0.0]",
        "translation: [2000, 3000, 0]",
        (
            "locations.door.translation: [2000, 3000, 0] lies 3000 m from the origin",
            "[2, 3, 0] for millimetres?",
        ),
        "2000",
    ),
    "an object put down inside the table": person(
        '<ActorAnimation animation_name="wave"/>',
        '<ActorMovement target="0.3;1.6;0"/><ActorPlace target="0.3;0.6;0.88"/>',
        ("port 'target': '0.3;0.6;0.88' at (0.30, 0.60, 0.88) lies 0.020 m inside work_table",),
        "ActorPlace",
    ),
    "a place out of reach from where the walk ends": person(
        '<ActorAnimation animation_name="wave"/>',
        '<ActorPlace target="0.3;0.9;0.95"/>',
        (
            "port 'target': '0.3;0.9;0.95' at (0.30, 0.90, 0.95) is 2.70 m from where the "
            "person stands (location 'door', ActorMovement at ",
            "walk closer first",
        ),
        "ActorPlace",
    ),
    "a pick of what lies in an area out of reach from where the walk ends": person(
        '<ActorAnimation animation_name="wave"/>',
        '<NextObject area="table" filter="type=part" object_id="{p}" pose="{at}"/>'
        '<ActorPick object_id="{p}"/>',
        (
            "port 'object_id': part in area 'table' (NextObject at ",
            "at (0.00, 0.60, 0.93) is 3.12 m from where the person stands (location 'door', "
            "ActorMovement at ",
            "walk closer first",
        ),
        "ActorPick",
        changes=[("safety:\n", f"{OBJECTS}{PART_ON_TABLE}safety:\n")],
    ),
    "a pick of what lies in an area the hands cannot get to from where the walk ends": person(
        '<ActorAnimation animation_name="wave"/>',
        '<ActorMovement target="across"/>'
        '<NextObject area="table" filter="type=part" object_id="{p}" pose="{at}"/>'
        '<ActorPick object_id="{p}"/>',
        (
            "port 'object_id': part in area 'table' (NextObject at ",
            "at (0.00, 0.60, 0.93), taken where the person stands (location 'across', "
            "ActorMovement at ",
            "): target 1.22 m away, out of reach without walking",
        ),
        "ActorPick",
        changes=[
            ("safety:\n", f"{OBJECTS}{PART_ON_TABLE}safety:\n"),
            (
                "locations:\n",
                "locations:\n  across: {translation: [0.0, 1.8, 0.0], "
                "rotation: !Rpy {deg: [0, 0, -90]}}\n",
            ),
        ],
    ),
    "a pick off a shelf's bottom board the head cannot stoop to": person(
        '<ActorAnimation animation_name="wave"/>',
        '<ActorMovement target="shelf_front"/>'
        '<NextObject area="bottom_board" filter="type=carton" object_id="{c}" pose="{at}"/>'
        '<ActorPick object_id="{c}"/>',
        (
            "port 'object_id': carton in area 'bottom_board' (NextObject at ",
            "at (3.00, 0.47, 0.20), taken where the person stands (location 'shelf_front', "
            "ActorMovement at ",
            "): the head would go ",
            " cm into 'shelf' ",
        ),
        "ActorPick",
        changes=[
            A_SHELF,
            (
                "safety:\n",
                "    carton: {shape: box, size: [0.3, 0.25, 0.2], mass: 2.0, capacity: 4}\n"
                f"{OBJECTS}    - {{type: carton, pose: {{translation: [3.0, 0.47, 0.201]}}}}\n"
                "safety:\n",
            ),
            A_SHELF_FRONT,
            (
                "areas:\n",
                "areas:\n  bottom_board: [[2.6, 0.35], [3.4, 0.35], [3.4, 0.75], [2.6, 0.75]]\n",
            ),
        ],
    ),
    "a pick off a shelf's board whose tote would be in the shelf in the carry posture": person(
        '<ActorAnimation animation_name="wave"/>',
        '<ActorMovement target="shelf_front"/>'
        '<NextObject area="top_board" filter="type=tote" object_id="{t}" pose="{at}"/>'
        '<ActorPick object_id="{t}"/>',
        (
            "port 'object_id': tote in area 'top_board' (NextObject at ",
            "at (3.00, 0.55, 1.16), taken where the person stands (location 'shelf_front', "
            "ActorMovement at ",
            "): what the hands hold would go ",
            " cm into 'shelf' ",
            "no way to take it from where the person stands",
        ),
        "ActorPick",
        changes=[
            A_SHELF,
            (
                "safety:\n",
                "    tote: {shape: box, size: [0.36, 0.26, 0.12], mass: 1.2, capacity: 4}\n"
                f"{OBJECTS}    - {{type: tote, pose: {{translation: [3.0, 0.55, 1.161], "
                "rotation: !Rpy {deg: [0, 0, 90]}}}\n"
                "safety:\n",
            ),
            A_SHELF_FRONT,
            (
                "areas:\n",
                "areas:\n  top_board: [[2.6, 0.35], [3.4, 0.35], [3.4, 0.75], [2.6, 0.75]]\n",
            ),
        ],
    ),
    "a pick of object 1, a tray on a shelf's board, the arm in the shelf from at ease": person(
        '<ActorAnimation animation_name="wave"/>',
        '<ActorMovement target="shelf_front"/><ActorPick object_id="1"/>',
        (
            "port 'object_id': object 1 (the tray of workpieces.objects[0]) at (3.00, 0.55, "
            "1.12), taken where the person stands (location 'shelf_front', ActorMovement at ",
            "): the right arm would go ",
            " cm into 'shelf' ",
            "no way to do it from where the person stands",
        ),
        "ActorPick",
        changes=[
            A_SHELF,
            (
                "safety:\n",
                "    tray: {shape: box, size: [0.5, 0.36, 0.04], mass: 0.8, capacity: 4}\n"
                f"{OBJECTS}    - {{type: tray, pose: {{translation: [3.0, 0.55, 1.12]}}}}\n"
                "safety:\n",
            ),
            A_SHELF_FRONT,
        ],
    ),
    "a put-down past a shelf board's back edge of the tote carried there": person(
        '<ActorAnimation animation_name="wave"/>',
        '<NextObject area="table" filter="type=tote" object_id="{t}" pose="{at}"/>'
        '<ActorMovement target="table_front"/><ActorPick object_id="{t}"/>'
        '<ActorMovement target="shelf_front"/><ActorPlace target="3.0;0.8;0.676"/>',
        (
            "port 'target': '3.0;0.8;0.676' at (3.00, 0.80, 0.68), put down where the person "
            "stands (location 'shelf_front', ActorMovement at ",
            "): where it is put is 5.0 cm off the top of 'shelf', nothing but the floor under it",
        ),
        "ActorPlace",
        changes=[
            A_SHELF,
            A_TOTE_ON_THE_TABLE,
            A_SHELF_FRONT,
            (
                "locations:\n",
                "locations:\n  table_front: {translation: [0.0, 1.45, 0.0], "
                "rotation: !Rpy {deg: [0, 0, -90]}}\n",
            ),
        ],
    ),
    "a drop into a bin's floor of a part none lie where it is found at the start": person(
        '<ActorAnimation animation_name="wave"/>',
        '<NextObject area="table" filter="type=part" object_id="{p}" pose="{at}"/>'
        '<ActorPick object_id="{p}" hand="right"/>'
        '<ActorMovement target="bin_front"/><ActorPlace target="1.0;3.1;0.072"/>',
        (
            "port 'target': '1.0;3.1;0.072' at (1.00, 3.10, 0.07), put down where the person "
            "stands (location 'bin_front', ActorMovement at ",
            "): the right arm would go ",
            " cm into 'bin' ",
        ),
        "ActorPlace",
        changes=[
            (
                "human:\n",
                "  - add_model: {name: bin, file: package://hrc_drake_models/cell/bin.sdf}\n"
                "  - add_weld: {parent: world, child: bin::body, "
                "X_PC: {translation: [1.0, 3.1, 0]}}\n"
                "human:\n",
            ),
            (
                "locations:\n",
                "locations:\n  bin_front: {translation: [1.0, 2.6, 0.0], "
                "rotation: !Rpy {deg: [0, 0, 90]}}\n",
            ),
        ],
    ),
    "a put-down into the table of a part the tree makes": person(
        '<ActorAnimation animation_name="wave"/>',
        '<SpawnObject type="part" pose="0.2;0.85;0.93" object_id="{p}"/>'
        '<ActorMovement target="table_front"/><ActorPick object_id="{p}"/>'
        '<ActorPlace target="-0.2;0.85;0.9"/>',
        (
            "port 'target': '-0.2;0.85;0.9' at (-0.20, 0.85, 0.90), put down where the person "
            "stands (location 'table_front', ActorMovement at ",
            "): what the hands hold would be 3.0 cm into 'work_table' where it is put",
        ),
        "ActorPlace",
        changes=[
            (
                "locations:\n",
                "locations:\n  table_front: {translation: [0.0, 1.45, 0.0], "
                "rotation: !Rpy {deg: [0, 0, -90]}}\n",
            ),
        ],
    ),
    "a put-down target a parameter gives, at the parameter's line": replace(
        person(
            '<ActorAnimation animation_name="wave"/>',
            '<SpawnObject type="part" pose="0.2;0.85;0.93" object_id="{p}"/>'
            '<ActorMovement target="table_front"/><ActorPick object_id="{p}"/>'
            '<ActorPlace target="{put_spot}"/>',
            (
                "parameters.put_spot: parameter 'put_spot' at (-0.20, 0.85, 0.90), put down "
                "where the person stands (location 'table_front', ActorMovement at ",
                "): what the hands hold would be 3.0 cm into 'work_table' where it is put: "
                "ActorPlace 'ActorPlace::",
            ),
            'put_spot: "',
            changes=[
                (
                    "locations:\n",
                    "locations:\n  table_front: {translation: [0.0, 1.45, 0.0], "
                    "rotation: !Rpy {deg: [0, 0, -90]}}\n",
                ),
                ('  speed: "0.5"\n', '  speed: "0.5"\n  put_spot: "-0.2;0.85;0.9"\n'),
            ],
        ),
        found_in=None,
    ),
    "a part the robot lets go of inside the table": ROBOT_PUT_DOWN_INTO_THE_TABLE,
    "a move holding a part that the tool alone makes, the part not": replace(
        ROBOT_PUT_DOWN_INTO_THE_TABLE,
        new=ROBOT_PUT_DOWN_INTO_THE_TABLE.new.replace(
            '<RobotMove target="0.2;0.42;1.03"/>', '<RobotMove target="0.2;0.42;0.945"/>'
        ).replace("0.2;0.42;0.93", "0.2;0.42;0.96"),
        says=(
            "port 'target': '0.2;0.42;0.945' at (0.20, 0.42, 0.94): with the part it holds, "
            "unreachable with the tool pointing down: the vacuum_gripper (or the part it "
            "holds) would touch work_table there",
        ),
        at='target="0.2;0.42;0.945"',
    ),
    "a put-down whose tote would be in the board above where it is put": person(
        '<ActorAnimation animation_name="wave"/>',
        '<NextObject area="table" filter="type=tote" object_id="{t}" pose="{at}"/>'
        '<ActorMovement target="table_front"/><ActorPick object_id="{t}"/>'
        '<ActorMovement target="shelf_back"/><ActorPlace target="3.0;0.6;1.06"/>',
        (
            "port 'target': '3.0;0.6;1.06' at (3.00, 0.60, 1.06), put down where the person "
            "stands (location 'shelf_back', ActorMovement at ",
            "): what the hands hold would be ",
            " cm into 'shelf' where it is put",
        ),
        "ActorPlace",
        changes=[
            A_SHELF,
            A_TOTE_ON_THE_TABLE,
            (
                "locations:\n",
                "locations:\n  table_front: {translation: [0.0, 1.45, 0.0], "
                "rotation: !Rpy {deg: [0, 0, -90]}}\n"
                "  shelf_back: {translation: [3.0, -0.2, 0.0], rotation: !Rpy {deg: [0, 0, 90]}}\n",
            ),
        ],
    ),
    "a reach out of reach from the person's start": person(
        '<ActorMovement target="door"/>',
        '<ActorReach target="0.0;0.6;1.0"/><ActorMovement target="door"/>',
        (
            "port 'target': '0.0;0.6;1.0' at (0.00, 0.60, 1.00) is 2.44 m from where the "
            "person stands (the person's start)",
        ),
        "ActorReach",
    ),
    "area in millimetres": Case(
        S,
        "table: [[-0.6, 0.3], [0.6, 0.3], [0.6, 1.1], [-0.6, 1.1]]",
        "table: [[-600, 300], [600, 300], [600, 1100], [-600, 1100]]",
        ("areas.table: its corners lie up to 1100 m from the origin", "in millimetres?"),
        "table: [[-600",
    ),
    "belt end in millimetres": Case(
        S,
        "safety:\n",
        "  conveyors:\n    belt: {start: [1, -1, 0.9], end: [2000, -1, 0.9]}\nsafety:\n",
        ("workpieces.conveyors.belt.end: [2000, -1, 0.9] lies 2000 m from the origin",),
        "2000",
    ),
    "angle in radians": Case(
        S,
        "deg: [0, 0, -90]",
        "deg: [0, 0, -1.5708]",
        (
            "locations.door.rotation.deg[2]: -1.5708 looks like radians; the angle is in degrees: "
            "-90 for -1.5708 rad?",
        ),
        "-1.5708",
    ),
    "person facing in radians": Case(
        S,
        "start: [2.0, 2.0, 180.0]",
        "start: [2.0, 2.0, 3.1416]",
        ("human.start[2]: 3.1416 looks like radians", "180 for 3.1416 rad?"),
        "start:",
    ),
    "configuration in radians": Case(
        S,
        "ready: [0, -45, 90, 0, 45, 0]",
        "ready: [0, -0.785, 1.571, 0, 0.785, 0]",
        (
            "robot.configurations_deg.ready: [0, -0.785, 1.571, 0, 0.785, 0] looks like radians; "
            "the angles are degrees: [0, -45, 90, 0, 45, 0]?",
        ),
        "ready:",
    ),
    "person height in centimetres": Case(
        S,
        "height: 1.75",
        "height: 175",
        ("human.height: must lie within", "(lengths are in metres: 1.75 for centimetres?)"),
        "height: 175",
    ),
}


@pytest.mark.parametrize("name", CASES)
def test_a_mistake_a_run_would_find_is_one_located_line(name, tmp_path, hrc_drake):
    case = CASES[name]
    scenario = write_workspace(tmp_path, case)
    status, _, err = hrc_drake("validate", scenario)
    assert_one_line_error(status, err, expected_place(tmp_path, case), *case.says)


def test_a_reach_after_an_uncertain_walk_is_not_judged(tmp_path, hrc_drake):
    """Where a Fallback's first try walks (and may have failed half-way), where the person
    stands is not known before the run: validate says nothing rather than guess."""
    case = person(
        '<ActorAnimation animation_name="wave"/>',
        '<Fallback><Sequence><ActorMovement target="0.3;1.6;0"/><AlwaysFailure/></Sequence>'
        '<ActorPlace target="0.3;0.9;0.95"/></Fallback>',
        (),
        "ActorPlace",
    )
    status, _, err = hrc_drake("validate", write_workspace(tmp_path, case))
    assert status == 0, err


def test_a_put_down_onto_a_box_lying_at_the_target_is_planned_on_top_of_it(tmp_path, hrc_drake):
    """A cell of our own: a tote put down where another lies is put on top of it in the run
    (hrc_drake.nodes.stacks), but validate planned it at the target as given, inside the
    other, and said "what the hands hold would be 12.0 cm into 'object' where it is put"."""
    totes = (
        "safety:\n",
        "    tote: {shape: box, size: [0.36, 0.26, 0.12], mass: 1.2, capacity: 4}\n"
        f"{OBJECTS}    - {{type: tote, pose: {{translation: [-0.35, 0.95, 0.96]}}}}\n"
        "    - {type: tote, pose: {translation: [0.2, 0.95, 0.96]}}\n"
        "safety:\n",
    )
    places = (
        "locations:\n",
        "locations:\n  table_front: {translation: [0.0, 1.45, 0.0], "
        "rotation: !Rpy {deg: [0, 0, -90]}}\n",
    )
    left = ("areas:\n", "areas:\n  left: [[-0.6, 0.3], [-0.2, 0.3], [-0.2, 1.1], [-0.6, 1.1]]\n")
    case = person(
        '<ActorAnimation animation_name="wave"/>',
        '<NextObject area="left" filter="type=tote" object_id="{t}" pose="{at}"/>'
        '<ActorMovement target="table_front"/><ActorPick object_id="{t}"/>'
        '<ActorPlace target="0.2;0.95;0.96"/>',
        (),
        "ActorPlace",
        changes=[totes, places, left],
    )
    status, _, err = hrc_drake("validate", write_workspace(tmp_path, case))
    assert status == 0, err


def test_a_stacks_bottom_tray_is_judged_with_the_trays_above_it_gone(tmp_path, hrc_drake):
    """A user's kitting cell (#26): a small woman takes empty trays off a stack of three on
    the floor, one at a time as NextObject offers them, top first. validate planned the bottom
    tray's pick with the top tray still there (only the one right on it left out) and said
    the tray she lifts "would go 9.8 cm into 'tote at (2.00, 0.90, 0.25)'"."""
    totes = (
        "safety:\n",
        "    tote: {shape: box, size: [0.3, 0.4, 0.1], mass: 1.2, capacity: 4}\n"
        f"{OBJECTS}    - {{type: tote, pose: {{translation: [2.0, 0.9, 0.05]}}}}\n"
        "    - {type: tote, pose: {translation: [2.0, 0.9, 0.15]}}\n"
        "    - {type: tote, pose: {translation: [2.0, 0.9, 0.25]}}\n"
        "safety:\n",
    )
    places = (
        "locations:\n",
        "locations:\n  stack_front: {translation: [2.0, 1.45, 0.0], "
        "rotation: !Rpy {deg: [0, 0, -90]}}\n",
    )
    stack = ("areas:\n", "areas:\n  stack: [[1.7, 0.6], [2.3, 0.6], [2.3, 1.2], [1.7, 1.2]]\n")
    case = person(
        '<ActorAnimation animation_name="wave"/>',
        '<ActorMovement target="stack_front"/>'
        '<NextObject area="stack" filter="type=tote" object_id="{t}" pose="{at}"/>'
        '<ActorPick object_id="{t}"/>',
        (),
        "ActorPick",
        changes=[totes, places, stack],
    )
    scenario = write_workspace(tmp_path, case)
    small_woman = ("--set", "human.percentile=5", "--set", "human.sex=female")
    status, _, err = hrc_drake("validate", scenario, *small_woman)
    assert status == 0, err


def test_a_part_the_robot_lets_go_of_on_the_table_is_not_judged(tmp_path, hrc_drake):
    """The robot's put-down of the corpus's case with the part's top 5 mm over where it
    rests on the table: the part drops 5 mm, as a user's cell lets go of its parts."""
    case = ROBOT_PUT_DOWN_INTO_THE_TABLE
    case = replace(case, new=case.new.replace("0.2;0.42;0.93", "0.2;0.42;0.965"))
    status, _, err = hrc_drake("validate", write_workspace(tmp_path, case))
    assert status == 0, err


def test_an_object_the_person_would_go_into_is_named(tmp_path, hrc_drake):
    """A packing cell of our own (#26): stooping to a carton on a shelf's middle board, the
    head of a tall man would go into the carton on the board above, standing 5 cm out past
    its front edge; validate said "into 'object'". It names the object and where it lies,
    as the run refuses the pick. (A small woman's head went into the carton flush with the
    edge only as validate planned her body with a 1.75 m person's clips; the run, her own
    clips, takes the carton within the audit's limits.)"""
    case = person(
        '<ActorAnimation animation_name="wave"/>',
        '<ActorMovement target="shelf_front"/>'
        '<NextObject area="shelf" filter="type=carton" object_id="{c}" pose="{at}"/>'
        '<ActorPick object_id="{c}"/>',
        (),
        "ActorPick",
        changes=[
            A_SHELF,
            (
                "safety:\n",
                "    carton: {shape: box, size: [0.3, 0.2, 0.2], mass: 0.6, capacity: 4}\n"
                f"{OBJECTS}    - {{type: carton, pose: {{translation: [3.0, 0.45, 0.70]}}}}\n"
                "    - {type: carton, pose: {translation: [3.0, 0.40, 1.20]}}\n"
                "safety:\n",
            ),
            (
                "locations:\n",
                "locations:\n  shelf_front: {translation: [3.0, -0.05, 0.0], "
                "rotation: !Rpy {deg: [0, 0, 90]}}\n",
            ),
            ("areas:\n", "areas:\n  shelf: [[2.6, 0.35], [3.4, 0.35], [3.4, 0.75], [2.6, 0.75]]\n"),
        ],
    )
    scenario = write_workspace(tmp_path, case)
    status, _, err = hrc_drake("validate", scenario, "--set", "human.percentile=95")
    assert_one_line_error(
        status, err, expected_place(tmp_path, case), "into 'carton at (3.00, 0.40, 1.20)'"
    )


def test_a_walk_through_a_gap_wide_enough_is_not_judged(tmp_path, hrc_drake):
    """The fences 0.8 m apart: the person walks straight through, and validate says
    nothing (nor of the walk back)."""
    case = person(
        '<ActorMovement target="door"/>',
        '<ActorMovement target="door"/>\n      <ActorMovement target="2.0;2.0;0"/>',
        (),
        "ActorMovement",
        changes=[("human:\n", f"{two_fences(0.8)}human:\n")],
    )
    status, _, err = hrc_drake("validate", write_workspace(tmp_path, case))
    assert status == 0, err
