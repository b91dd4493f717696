"""Bad scenario files: `hrc-drake validate` answers each with one line naming the file,
the line and the field, and exit status 2 (none of these cases simulates)."""

from pathlib import Path

import pytest

from tests.corpus.corpus_helpers import (
    GOOD_TREE,
    Case,
    assert_one_line_error,
    expected_place,
    write_workspace,
)

MODELS = Path(__file__).resolve().parents[2] / "models"
DIRECTIVES_LOOP = """\
directives:
  - add_directives: {file: "file://{dir}/loop.yaml"}
"""
DIRECTIVES_UNKNOWN_WELD = """\
directives:
  - add_model: {name: bin, file: package://hrc_drake_models/cell/bin.sdf}
  - add_weld: {parent: world, child: bni::body}
"""

OWN_TABLE = """\
<?xml version="1.0"?>
<sdf version="1.9">
  <model name="table">
    <link name="body">
      <collision name="top">
        <pose>0 0 0.45 0 0 0</pose>
        <geometry><box><size>1.2 0.8 0.9</size></box></geometry>
      </collision>
    </link>
  </model>
</sdf>
"""
"""A model of the user's own, beside the scenario."""

ALIAS_BOMB = "".join(
    f"  lol{i}: &a{i} [{', '.join([f'*a{i - 1}' if i else 'lol'] * 9)}]\n" for i in range(9)
)
"""A "billion laughs": nine lists of nine aliases of the list before, 9**9 values expanded."""

GOOD_TREE_WITH_WEIGHTS = GOOD_TREE.replace(
    '<SubTree ID="Reach" at="pick_spot"/>\n    </Sequence>',
    '<WeightedRandom weights="{w}"><AlwaysSuccess/><AlwaysFailure/></WeightedRandom>\n'
    "    </Sequence>",
)

S = "scenario.yaml"
CASES = {
    # --- the schema: fields, types, YAML ---
    "missing name": Case(
        S, "name: corpus\n", "", ("name: required field is missing",), "description"
    ),
    "wrong type": Case(
        S, "duration: 0.2", "duration: five", ("duration: 'five' is not a float",), "five"
    ),
    "unknown field": Case(S, "duration:", "durration:", ("did you mean 'duration'?",), "durration"),
    "unknown field, none close": Case(
        S,
        "workpieces:\n",
        "workpieces:\n  initial: []\n",
        ("workpieces.initial: unknown field (known: conveyors, derive_surfaces, grids, ",),
        "initial",
    ),
    "unknown field of a Drake struct": Case(
        S, "{time_step:", "{timestep:", ("plant.timestep: unknown field",), "timestep"
    ),
    "unknown nested field": Case(
        S, "  v_h: 1.6", "  vh: 1.6", ("safety.vh: unknown field",), "vh:"
    ),
    "malformed yaml": Case(S, "seed: 0", "seed: [0", ("malformed YAML",)),
    "tab indentation": Case(S, "  height: 1.75", "\theight: 1.75", ("malformed YAML",)),
    "list for mapping": Case(S, "human:\n  height", "human:\n  - height", ("malformed YAML",)),
    "document is a list": Case(S, "name: corpus\n", "- name: corpus\n", ("malformed YAML",)),
    "scalar for mapping": Case(
        S,
        "  ready: [0, -45",
        "  ready: 0\n  x: [0, -45",
        ("configurations_deg.ready: expected a list",),
        "ready: 0",
    ),
    "mapping for number": Case(
        S, "seed: 0", "seed: {a: 1}", ("seed: expected a single int",), "seed:"
    ),
    "bool word for float": Case(
        S, "  mass: 75.0", "  mass: yes", ("human.mass: 'yes' is not a float",), "mass: yes"
    ),
    "duplicate key": Case(
        S, "seed: 0\n", "seed: 0\nseed: 3\n", ("seed: given twice (first on line 3)",), "seed: 3"
    ),
    "duplicate nested key": Case(
        S, "  v_h: 1.6\n", "  v_h: 1.6\n  v_h: 2.0\n", ("safety.v_h: given twice",), "v_h: 2.0"
    ),
    "location defined twice": Case(
        S,
        "  door:",
        "  pick_spot: {translation: [0, 0, 0]}\n  door:",
        ("locations.pick_spot: given twice",),
        "pick_spot: {translation: [0, 0, 0]}",
    ),
    "area defined twice": Case(
        S,
        "  table: [[-0.6",
        "  table: [[0, 0], [1, 0], [0, 1]]\n  table: [[-0.6",
        ("areas.table: given twice",),
        "table: [[-0.6",
    ),
    "alias bomb": Case(
        S,
        "parameters:\n",
        f"parameters:\n{ALIAS_BOMB}",
        ("parameters.lol5: its aliases expand it to more than 100000 values (an alias bomb?)",),
        "lol5:",
    ),
    "alias of itself": Case(
        S,
        "parameters:\n",
        "parameters:\n  loop: &loop [1, *loop]\n",
        ("parameters.loop[1]: an alias refers to itself",),
        "loop:",
    ),
    "nested too deeply": Case(
        S, "duration: 0.2", f"duration: {'[' * 3000}{']' * 3000}", ("nested too deeply",)
    ),
    # --- numbers: finite, in range ---
    "time_step inf": Case(
        S,
        "time_step: 0.001",
        "time_step: .inf",
        ("plant.time_step: must be a finite number",),
        "time_step",
    ),
    "time_step 10 s": Case(
        S, "time_step: 0.001", "time_step: 10", ("plant.time_step: must lie within",), "time_step"
    ),
    "time_step zero": Case(
        S, "time_step: 0.001", "time_step: 0", ("plant.time_step: must lie within",), "time_step"
    ),
    "time_step negative": Case(
        S,
        "time_step: 0.001",
        "time_step: -0.001",
        ("plant.time_step: must lie within",),
        "time_step",
    ),
    "unknown contact approximation": Case(
        S,
        "{time_step: 0.001}",
        "{time_step: 0.001, discrete_contact_approximation: sapp}",
        ("plant",),
        "sapp",
    ),
    "unknown integration scheme": Case(
        S,
        "name: corpus\n",
        "name: corpus\nsimulator: {integration_scheme: rk9}\n",
        ("simulator.integration_scheme: unknown value 'rk9'",),
        "rk9",
    ),
    "human period zero": Case(
        S,
        "  height: 1.75\n",
        "  height: 1.75\n  period: 0\n",
        ("human.period: must be positive",),
        "  period: 0",
    ),
    "duration zero": Case(
        S, "duration: 0.2", "duration: 0", ("duration: must be positive",), "duration"
    ),
    "duration negative": Case(
        S, "duration: 0.2", "duration: -5", ("duration: must be positive",), "duration"
    ),
    "duration nan": Case(
        S, "duration: 0.2", "duration: .nan", ("duration: must be a finite number",), "duration"
    ),
    "duration inf": Case(
        S, "duration: 0.2", "duration: .inf", ("duration: must be a finite number",), "duration"
    ),
    "seed negative": Case(S, "seed: 0", "seed: -1", ("seed: must lie within 0..",), "seed"),
    "seed too large": Case(
        S, "seed: 0", "seed: 99999999999999999999999", ("seed: must lie within",), "seed"
    ),
    "seed fraction": Case(S, "seed: 0", "seed: 1.5", ("seed: '1.5' is not an int",), "seed"),
    "motion period zero": Case(
        S,
        "motion: {period: 0.01",
        "motion: {period: 0",
        ("robot.motion.period: must be positive",),
        "motion: {period: 0,",
    ),
    "tool speed negative": Case(
        S,
        "tool_speed_limit: 1.0",
        "tool_speed_limit: -1",
        ("robot.motion.tool_speed_limit: must be positive",),
        "tool_speed_limit",
    ),
    "safety period zero": Case(
        S, "  period: 0.01", "  period: 0", ("safety.period: must be positive",), "  period: 0"
    ),
    "safety v_h negative": Case(
        S, "  v_h: 1.6", "  v_h: -1", ("safety.v_h: must not be negative",), "v_h"
    ),
    "safety v_h rule unknown": Case(
        S,
        "  v_h: 1.6",
        "  v_h_rule: iso13856\n  v_h: 1.6",
        ("safety.v_h_rule: unknown value 'iso13856' (did you mean 'iso13855'?)",),
        "v_h_rule",
    ),
    "safety min_scale above 1": Case(
        S,
        "  min_scale: 0.05",
        "  min_scale: 2",
        ("safety.min_scale: must lie within 0..1",),
        "min_scale",
    ),
    "sensing time inf": Case(
        S,
        "  sensing_time: 0.08",
        "  sensing_time: .inf",
        ("safety.sensing_time: must be a finite number",),
        "sensing_time",
    ),
    "tree period zero": Case(
        S, "period: 0.05}", "period: 0}", ("trees.robot.period: must be positive",), "period: 0}"
    ),
    "visualization period negative": Case(
        S,
        "  period: 0.05\n",
        "  period: -1\n",
        ("visualization.period: must be positive",),
        "period: -1",
    ),
    "translation inf": Case(
        S,
        "translation: [2.0, 3.0, 0.0]",
        "translation: [2.0, .inf, 0.0]",
        ("locations.door.translation[1]: must be a finite number",),
        ".inf",
    ),
    "configuration nan": Case(
        S,
        "ready: [0, -45, 90, 0, 45, 0]",
        "ready: [0, -45, .nan, 0, 45, 0]",
        ("robot.configurations_deg.ready[2]: must be a finite number",),
        ".nan",
    ),
    # --- Drake's schema: transforms and tags ---
    "translation of two": Case(
        S,
        "translation: [-0.2, 0.42, 0.93]",
        "translation: [-0.2, 0.42]",
        ("locations.pick_spot.translation: needs 3 numbers, got 2",),
        "[-0.2, 0.42]",
    ),
    "translation of four": Case(
        S,
        "translation: [0.0, 0.0, 0.8]",
        "translation: [0.0, 0.0, 0.8, 1]",
        ("robot.base_pose.translation: needs 3 numbers, got 4",),
        "0.8, 1",
    ),
    "rpy of two": Case(
        S,
        "deg: [0, 0, -90]",
        "deg: [0, -90]",
        ("locations.door.rotation.deg: needs 3 numbers, got 2",),
        "deg: [0, -90]",
    ),
    "mistyped rpy tag": Case(
        S,
        "!Rpy {deg",
        "!Rpyy {deg",
        ("locations.door.rotation: unknown tag '!Rpyy'", "!Rpy"),
        "!Rpyy",
    ),
    "text in translation": Case(
        S,
        "translation: [0.0, 0.0, 0.8]",
        "translation: [0.0, a, 0.8]",
        ("robot.base_pose.translation[1]: 'a' is not a float",),
        "[0.0, a, 0.8]",
    ),
    "unknown field in rpy": Case(
        S,
        "!Rpy {deg: [0, 0, -90]}",
        "!Rpy {deg: [0, 0, -90], yaw: 1}",
        ("locations.door.rotation.yaw: unknown field",),
        "yaw: 1",
    ),
    "random location": Case(
        S,
        "deg: [0, 0, -90]",
        "deg: !UniformVector {min: [0, 0, 0], max: [0, 0, 90]}",
        ("locations.door: must be a fixed pose",),
        "  door:",
    ),
    "random vector of two": Case(
        S,
        "deg: [0, 0, -90]",
        "deg: !UniformVector {min: [0, 0], max: [0, 0, 90]}",
        ("locations.door.rotation.deg.min: needs 3 numbers, got 2",),
        "UniformVector",
    ),
    "unknown vector tag": Case(
        S,
        "translation: [2.0, 3.0, 0.0]",
        "translation: !Vector [2.0, 3.0, 0.0]",
        ("locations.door.translation: unknown tag '!Vector' (!DeterministicVector, ",),
        "!Vector",
    ),
    # --- names the scenario refers to ---
    "unknown variant": Case(
        S,
        "variant: lbr_iisy3_r760",
        "variant: lbr_iisy3_r770",
        ("robot.variant: unknown robot variant 'lbr_iisy3_r770' (did you mean 'lbr_iisy3_r760'?)",),
        "variant",
    ),
    "unknown tool": Case(
        S,
        "  base_pose:",
        "  tool: hammer\n  base_pose:",
        ("robot.tool: unknown tool 'hammer'",),
        "hammer",
    ),
    "unknown initial configuration": Case(
        S,
        "  base_pose:",
        "  initial_configuration: raedy\n  base_pose:",
        ("robot.initial_configuration: unknown configuration 'raedy' (did you mean 'ready'?)",),
        "raedy",
    ),
    "configuration of three joints": Case(
        S,
        "ready: [0, -45, 90, 0, 45, 0]",
        "ready: [0, -45, 90]",
        ("robot.configurations_deg.ready: needs 6 joint angles, got 3",),
        "ready:",
    ),
    "location named like an area": Case(
        S,
        "  door:",
        "  table: {translation: [0, 0, 0]}\n  door:",
        ("areas.table: 'table' is already a name in locations",),
        "  table: [[",
    ),
    "parameter named like a location": Case(
        S,
        '  speed: "0.5"',
        '  speed: "0.5"\n  door: "x"',
        ("parameters.door: 'door' is already a name in locations",),
        'door: "x"',
    ),
    "parameter the tree cannot read": Case(
        S,
        'speed: "0.5"',
        'speed: "fast"',
        ("parameters.speed: a tree cannot read it: cannot convert 'fast'",),
        "fast",
    ),
    "parameter out of the range of the port that reads it": Case(
        S,
        'speed: "0.5"',
        'speed: "50"',
        (
            "parameters.speed: must be within 0..1, got 50 (a percentage? 0.5 is the fraction): "
            "SetRobotVelocity 'SetRobotVelocity::2' reads it as velocity (",
            "robot.xml:4)",
        ),
        'speed: "50"',
    ),
    "weights parameter that does not fit the children": Case(
        S,
        'speed: "0.5"',
        'speed: "0.5"\n  w: "6;1;1"',
        ("parameters.w: needs 2 weights, one per child, got 3: 6;1;1: WeightedRandom",),
        'w: "6;1;1"',
        {"robot.xml": GOOD_TREE_WITH_WEIGHTS},
    ),
    "tree port value out of its range": Case(
        S,
        "  robot: {file: robot.xml, period: 0.05}",
        "  robot: {file: robot.xml, period: 0.05, ports: {SetRobotVelocity: {velocity: '2'}}}",
        ("trees.robot.ports.SetRobotVelocity.velocity: must be within 0..1, got 2",),
        "ports:",
    ),
    "parameter not quoted": Case(
        S,
        'speed: "0.5"',
        "speed: 0.5",
        ("parameters.speed: '0.5' is not text: put it in quotes",),
        "speed: 0.5",
    ),
    "name as a number": Case(
        S, "name: corpus", "name: 42", ("name: '42' is not text: put it in quotes",), "name: 42"
    ),
    "parameter as mapping": Case(
        S,
        'speed: "0.5"',
        "speed: {a: 1}",
        ("parameters.speed: expected a single str",),
        "speed: {a: 1}",
    ),
    # --- areas ---
    "self-intersecting area": Case(
        S,
        "table: [[-0.6, 0.3], [0.6, 0.3], [0.6, 1.1], [-0.6, 1.1]]",
        "table: [[-0.6, 0.3], [0.6, 1.1], [0.6, 0.3], [-0.6, 1.1]]",
        ("areas.table: not a valid polygon: its edges cross",),
        "  table: [[",
    ),
    "area with 3-D points": Case(
        S,
        "table: [[-0.6, 0.3], [0.6, 0.3]",
        "table: [[-0.6, 0.3, 0], [0.6, 0.3]",
        ("areas.table[0]: a point needs exactly [x, y]",),
        "0.3, 0]",
    ),
    "area of two points": Case(
        S,
        "table: [[-0.6, 0.3], [0.6, 0.3], [0.6, 1.1], [-0.6, 1.1]]",
        "table: [[-0.6, 0.3], [0.6, 0.3]]",
        ("areas.table: not a valid polygon: a polygon needs at least 3 points",),
        "  table: [[",
    ),
    "area of zero size": Case(
        S,
        "table: [[-0.6, 0.3], [0.6, 0.3], [0.6, 1.1], [-0.6, 1.1]]",
        "table: [[0, 0], [1, 0], [2, 0]]",
        ("areas.table: not a valid polygon: the polygon has zero area",),
        "  table: [[",
    ),
    "area with a short point": Case(
        S,
        "table: [[-0.6, 0.3], [0.6, 0.3]",
        "table: [[-0.6], [0.6, 0.3]",
        ("areas.table[0]: a point needs exactly [x, y]",),
        "[-0.6]",
    ),
    # --- the person ---
    "person too tall": Case(
        S, "  height: 1.75", "  height: 3.0", ("human.height: must lie within",), "height"
    ),
    "person without mass": Case(
        S, "  mass: 75.0", "  mass: 0", ("human.mass: must be positive",), "mass: 0"
    ),
    "start of two values": Case(
        S,
        "start: [2.0, 2.0, 180.0]",
        "start: [2.0, 2.0]",
        ("human.start: needs [x, y, yaw_deg]",),
        "start:",
    ),
    # --- the cell's model directives ---
    "model file not found": Case(
        S,
        "cell/work_table.sdf",
        "cell/work_tabel.sdf",
        (
            "cell[2].add_model.file: model file ",
            "'package://hrc_drake_models/cell/work_tabel.sdf' not found",
        ),
        "work_tabel",
    ),
    "model file given as a path beside the scenario": Case(
        S,
        "package://hrc_drake_models/cell/work_table.sdf",
        "work_table.sdf",
        (
            "cell[2].add_model.file: model file 'work_table.sdf' not found (a model file is "
            "a URL, package://... or file:// and an absolute path: file:///",
            "/work_table.sdf beside the scenario)",
        ),  # a cell of our own: its machine, in machine.sdf beside the scenario
        "work_table.sdf",
        files={"work_table.sdf": (MODELS / "cell" / "work_table.sdf").read_text()},
    ),
    "own static model welded": Case(
        S,
        "package://hrc_drake_models/cell/work_table.sdf}\n  - add_weld:\n",
        '"file://{dir}/table.sdf"}\n  - add_weld:  # the weld of a static model\n',
        (
            "cell[3]: ",
            "model 'work_table' is static in its file (<static>true</static>), which welds it "
            "to the world already: remove this add_weld or the <static> tag",
        ),
        "# the weld of a static model",
        files={"table.sdf": OWN_TABLE.replace("<link", "<static>true</static><link")},
    ),
    "unknown package": Case(
        S,
        "package://hrc_drake_models/cell/floor.sdf",
        "package://nowhere/floor.sdf",
        ("cell[0].add_model.file: model file 'package://nowhere/floor.sdf' not found",),
        "nowhere",
    ),
    "weld to unknown model": Case(
        S,
        "child: floor::body",
        "child: flor::body",
        ("cell[1].add_weld.child: unknown model 'flor'",),
        "flor::body",
    ),
    "weld to unscoped frame": Case(
        S,
        "child: floor::body",
        "child: floor",
        ("cell[1].add_weld.child: 'floor' is not a scoped frame name",),
        "child: floor}",
    ),
    "weld to missing frame": Case(
        S,
        "child: floor::body",
        "child: floor::nobody",
        ("cell[1]: GetFrameByName(): There is no Frame named 'nobody' anywhere in the model",),
        "floor::nobody",
    ),
    "random weld pose": Case(
        S,
        "X_PC: {translation: [0.0, 0.7, 0.0]}",
        "X_PC: {translation: !UniformVector {min: [0, 0, 0], max: [1, 1, 0]}}",
        ("cell[3].add_weld.X_PC: must be a fixed pose",),
        "X_PC",
    ),
    "model name used twice": Case(
        S,
        "{name: work_table,",
        "{name: floor,",
        ("cell[2].add_model.name: model name 'floor' is used twice",),
        "name: floor, file: package://hrc_drake_models/cell/work",
    ),
    "model named like the robot": Case(
        S,
        "{name: work_table,",
        "{name: iisy,",
        ("cell[2].add_model.name: model name 'iisy' is used twice",),
        "name: iisy",
    ),
    "model without a name": Case(
        S,
        "{name: work_table, file",
        "{file",
        ("cell[2].add_model.name: a model needs a name",),
        "- add_model: {file",
    ),
    "directives file not found": Case(
        S,
        "cell:\n",
        'cell:\n  - add_directives: {file: "file://{dir}/missing.yaml"}\n',
        ("cell[0].add_directives.file: directives file", "not found"),
        "missing.yaml",
    ),
    "directives file includes itself": Case(
        S,
        "cell:\n",
        'cell:\n  - add_directives: {file: "file://{dir}/loop.yaml"}\n',
        (
            "{dir}/loop.yaml:2: directives[0].add_directives.file: ",
            "directives files include each other in a loop: loop.yaml -> loop.yaml",
        ),
        None,
        {"loop.yaml": DIRECTIVES_LOOP},
    ),
    "included directives weld to unknown model": Case(
        S,
        "cell:\n",
        'cell:\n  - add_directives: {file: "file://{dir}/inner.yaml"}\n',
        ("{dir}/inner.yaml:3: directives[1].add_weld.child: unknown model 'bni'",),
        None,
        {"inner.yaml": DIRECTIVES_UNKNOWN_WELD},
    ),
    "unknown directive": Case(
        S,
        "  - add_weld: {parent: world, child: floor::body}",
        "  - add_wled: {parent: world, child: floor::body}",
        ("cell[1].add_wled: unknown field (did you mean 'add_weld'?)",),
        "add_wled",
    ),
    # --- workpieces and trees ---
    "unknown shape": Case(
        S,
        "{shape: box,",
        "{shape: cube,",
        ("workpieces.types.part.shape: unknown shape 'cube'",),
        "cube",
    ),
    "unknown agent": Case(
        S,
        "  robot: {file: robot.xml",
        "  robott: {file: robot.xml",
        ("trees.robott: unknown agent 'robott' (did you mean 'robot'?)",),
        "robott",
    ),
    "tree file not found": Case(
        S,
        "{file: robot.xml",
        "{file: robto.xml",
        ("trees.robot.file: tree file 'robto.xml' not found",),
        "robto",
    ),
    "tree file is a directory": Case(
        S, "{file: robot.xml", "{file: .", ("trees.robot.file: tree file '.' not found",), "file: ."
    ),
    "tree port value the port cannot read": Case(
        S,
        "  robot: {file: robot.xml, period: 0.05}",
        "  robot: {file: robot.xml, period: 0.05, ports: {OffsetPose: {offset: up}}}",
        ("trees.robot.ports.OffsetPose.offset: unknown location 'up'",),
        "ports:",
    ),
    "tree port of no node": Case(
        S,
        "  robot: {file: robot.xml, period: 0.05}",
        "  robot: {file: robot.xml, period: 0.05, ports: {Offset: {offset: 0;0;1}}}",
        ("trees.robot.ports.Offset.offset: no node named 'Offset' in the robot's tree",),
        "ports:",
    ),
    "tree port a node lacks": Case(
        S,
        "  robot: {file: robot.xml, period: 0.05}",
        "  robot: {file: robot.xml, period: 0.05, ports: {OffsetPose: {ofset: 0;0;1}}}",
        ("'OffsetPose' has no input port 'ofset' (it has: input, offset, orientation)",),
        "ports:",
    ),
    # --- the falsify: search space ---
    **{
        name: Case(
            S, "visualization:\n", f"falsify:\n  parameters:\n{text}\nvisualization:\n", says, at
        )
        for name, text, says, at in (
            (
                "falsify range reversed",
                "    s: {bind: parameters.speed,\n        low: 0.5,\n        high: 0.2}",
                ("falsify.parameters.s.high: must be above low (0.5), got 0.2",),
                "high: 0.2",
            ),
            (
                "falsify range and choices",
                "    s: {bind: parameters.speed, low: 0.2, high: 0.5, choices: ['0.3']}",
                ("falsify.parameters.s: give either low and high or choices, not both",),
                "s: {",
            ),
            (
                "falsify range without its end",
                "    s: {bind: parameters.speed, low: 0.2}",
                ("falsify.parameters.s: give low and high (a range) or choices",),
                "s: {",
            ),
            (
                "falsify step too long",
                "    s: {bind: parameters.speed, low: 0.2, high: 0.5,\n        step: 0.4}",
                ("falsify.parameters.s.step: must fit within low..high, got 0.4",),
                "step: 0.4",
            ),
            (
                "falsify step not positive",
                "    s: {bind: parameters.speed, low: 0.2, high: 0.5,\n        step: 0}",
                ("falsify.parameters.s.step: must be positive, got 0.0",),
                "step: 0}",
            ),
            (
                "falsify unknown blackboard entry",
                "    s: {bind: parameters.sped, low: 0.2, high: 0.5}",
                (
                    "falsify.parameters.s.bind: parameters.sped: 'parameters' has no entry 'sped' "
                    "(did you mean 'speed'?)",
                ),
                "sped",
            ),
            (
                "falsify unknown field",
                "    s: {bind: safety.vh, low: 0.2, high: 0.5}",
                ("falsify.parameters.s.bind: safety.vh: unknown field 'vh' (did you mean 'v_h'?)",),
                "safety.vh",
            ),
            (
                "falsify binds a section",
                "    s: {bind: safety, low: 0.2, high: 0.5}",
                ("falsify.parameters.s.bind: safety: only number, boolean and text fields",),
                "bind: safety",
            ),
            (
                "falsify binds the seed",
                "    s: {bind: seed, low: 0, high: 5, step: 1}",
                ("falsify.parameters.s.bind: cannot search 'seed'",),
                "bind: seed",
            ),
            (
                "falsify unknown tree node",
                "    s: {bind: trees.robot.ports.Offset.offset, choices: ['0;0;1']}",
                (
                    "falsify.parameters.s.choices[0]: trees.robot.ports.Offset.offset=0;0;1: no "
                    "node named 'Offset' in the robot's tree (did you mean 'OffsetPose'?)",
                ),
                "Offset.offset",
            ),
            (
                "falsify value the tree cannot read",
                "    s: {bind: parameters.speed,\n        choices: ['0.3',\n          fast]}",
                ("falsify.parameters.s.choices[1]: parameters.speed=fast: a tree cannot read it",),
                "fast",
            ),
            (
                "falsify range end out of the field's range",
                "    tall: {bind: human.height, low: 1.6,\n        high: 2.4}",
                ("falsify.parameters.tall.high: human.height=2.4: must lie within 1.45..1.95 m",),
                "high: 2.4",
            ),
            (
                "falsify whole-number field",
                "    n: {bind: robot.motion.ik_attempts, low: 1, high: 5}",
                ("falsify.parameters.n.step: 'robot.motion.ik_attempts' is a whole number",),
                "ik_attempts, low",
            ),
            (
                "falsify choice with a comma",
                "    s: {bind: parameters.speed, choices: ['0.3,0.4']}",
                ("falsify.parameters.s.choices[0]: a choice cannot hold ','",),
                "0.3,0.4",
            ),
            (
                "falsify unknown sampler",
                "    s: {bind: parameters.speed, low: 0.2, high: 0.5}\n  sampler: grid",
                ("falsify.sampler: unknown sampler 'grid'; known: tpe, cmaes, random",),
                "sampler: grid",
            ),
            (
                "falsify batch zero",
                "    s: {bind: parameters.speed, low: 0.2, high: 0.5}\n  batch: 0",
                ("falsify.batch: must be positive, got 0",),
                "batch: 0",
            ),
        )
    },
    "falsify without parameters": Case(
        S,
        "visualization:\n",
        "falsify: {sampler: tpe}\nvisualization:\n",
        ("falsify.parameters: required field is missing",),
        "falsify:",
    ),
    "falsify with no parameter": Case(
        S,
        "visualization:\n",
        "falsify: {parameters: {}}\nvisualization:\n",
        ("falsify.parameters: name at least one parameter to search",),
        "falsify:",
    ),
}


@pytest.mark.parametrize("name", CASES)
def test_bad_scenario_is_one_located_line(name, tmp_path, hrc_drake):
    case = CASES[name]
    scenario = write_workspace(tmp_path, case)
    status, _, err = hrc_drake("validate", scenario)
    where = expected_place(tmp_path, case) if case.at else str(tmp_path)
    assert_one_line_error(
        status, err, where, *(s.replace("{dir}", str(tmp_path)) for s in case.says)
    )


def test_the_good_scenario_validates(tmp_path, hrc_drake):
    status, out, err = hrc_drake("validate", write_workspace(tmp_path))
    assert status == 0, err
    assert "ok (corpus; trees robot: robot.xml)" in out


UNREADABLE = {
    "binary": (b"\x89PNG\r\n\x1a\n\x00\x00\x00\rIHDR\xff\xfe", "is not UTF-8 text"),
    "UTF-16": ("name: corpus\n".encode("utf-16"), "is not UTF-8 text"),
    "NUL bytes": (b"name: corpus\n\x00\x00\n", "malformed YAML"),
    "empty": (b"", "the file is empty"),
    "only a comment": (b"# nothing here\n", "the file is empty"),
}


@pytest.mark.parametrize("kind", UNREADABLE)
def test_unreadable_scenario_file(kind, tmp_path, hrc_drake):
    data, says = UNREADABLE[kind]
    path = tmp_path / "scenario.yaml"
    path.write_bytes(data)
    status, _, err = hrc_drake("validate", path)
    assert_one_line_error(status, err, str(path), says)


def test_a_file_that_cannot_be_read(hrc_drake):
    """/proc/self/mem is a file no plain read succeeds on (an I/O error, as for a file
    without read permission: the same OSError path)."""
    status, _, err = hrc_drake("validate", "/proc/self/mem")
    assert_one_line_error(status, err, "/proc/self/mem: cannot read the scenario file")


def test_a_scenario_that_is_a_directory_or_missing(tmp_path, hrc_drake):
    status, _, err = hrc_drake("validate", tmp_path)
    assert_one_line_error(status, err, f"{tmp_path}: no such scenario file")
    status, _, err = hrc_drake("validate", "bsae")
    assert_one_line_error(status, err, "did you mean 'base'?")


def test_validate_checks_the_scenario_as_set_on_the_command_line(tmp_path, hrc_drake):
    """`--set` gives validate the scenario a run with the same `--set` simulates (a person of
    another size checked before a sweep over sizes, #26): a speed set as a percentage is
    found there, as in the file."""
    scenario = write_workspace(tmp_path)
    status, _, err = hrc_drake("validate", scenario, "--set", "parameters.speed=50")
    assert_one_line_error(status, err, "must be within 0..1, got 50 (a percentage?")
    status, _, err = hrc_drake("validate", scenario, "--set", "parameters.speed=0.5,0.8")
    assert_one_line_error(status, err, "validate: --set takes one value per field")
