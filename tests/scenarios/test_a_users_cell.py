"""A cell written from the README as a new user would (issue #26): an iisy on a pedestal
between a side table with a tray (its left) and a conveyor (its right), a work table
1.5 m in front of it. The person assembles beyond the work table and now and then walks to
a place by the tray table that its author put exactly 0.3 m from the table's edge (the old
navigation map's clearance line) and back. The walk back went straight through the work
table, pelvis 0.34 m inside it, and `hrc-drake validate` said nothing.
"""

from pathlib import Path

import pytest
from pydrake.systems.analysis import Simulator

from hrc_drake.builder import build_diagram
from hrc_drake.cli import main
from hrc_drake.evaluation.realism import realism_metrics
from hrc_drake.scenario import load_scenario
from tests.scenarios.realism_checks import assert_within_the_audit_limits

CELL = """\
name: users_cell
description: An iisy between a tray table and a conveyor; a person at a work table in front.
seed: 0
duration: 40.0
robot:
  variant: lbr_iisy3_r760
  base_pose: {translation: [0.0, 0.0, 0.8]}
  tool: vacuum_gripper
cell:
  - add_model: {name: floor, file: package://hrc_drake_models/cell/floor.sdf}
  - add_weld: {parent: world, child: floor::body}
  - add_model: {name: robot_pedestal, file: package://hrc_drake_models/cell/robot_pedestal.sdf}
  - add_weld: {parent: world, child: robot_pedestal::body}
  - add_model: {name: tray_table, file: package://hrc_drake_models/cell/side_table.sdf}
  - add_weld: {parent: world, child: tray_table::body, X_PC: {translation: [0.0, 0.6, 0.0]}}
  - add_model: {name: conveyor, file: package://hrc_drake_models/cell/conveyor.sdf}
  - add_weld: {parent: world, child: conveyor::body, X_PC: {translation: [0.0, -0.75, 0.0]}}
  - add_model: {name: work_table, file: package://hrc_drake_models/cell/work_table.sdf}
  - add_weld:
      parent: world
      child: work_table::body
      X_PC: {translation: [1.5, 0.0, 0.0], rotation: !Rpy {deg: [0, 0, 90]}}
human:
  start: [2.25, 0.0, 180.0]
trees:
  human: {file: person.xml}
locations:
  work_spot: {translation: [2.25, 0.0, 0.0], rotation: !Rpy {deg: [0, 0, 180]}}
  tray_spot: {translation: [0.0, 1.2, 0.0], rotation: !Rpy {deg: [0, 0, -90]}}
"""
PERSON = """\
<root BTCPP_format="4" main_tree_to_execute="Person">
  <BehaviorTree ID="Person">
    <Repeat num_cycles="-1">
      <Sequence>
        <ActorMovement target="tray_spot"/>
        <Sleep msec="500"/>
        <ActorMovement target="work_spot"/>
        <Sleep msec="500"/>
      </Sequence>
    </Repeat>
  </BehaviorTree>
</root>
"""
RUN = 18.0
"""Seconds: to the tray table and back."""


@pytest.fixture(scope="module")
def cell(tmp_path_factory) -> Path:
    folder = tmp_path_factory.mktemp("users_cell")
    (folder / "person.xml").write_text(PERSON)
    (folder / "cell.yaml").write_text(CELL)
    return folder / "cell.yaml"


def test_validate_names_the_place_without_room_to_turn(cell, capsys):
    assert main(["validate", str(cell)]) == 2
    error = capsys.readouterr().err.strip()
    line = 1 + CELL.splitlines().index(next(t for t in CELL.splitlines() if "tray_spot" in t))
    assert error.startswith(f"hrc-drake: error: {cell}:{line}: locations.tray_spot: ")
    assert "turning on the spot" in error and "tray_table" in error


def test_the_person_walks_round_the_work_table_and_keeps_out_of_everything(cell):
    """The place by the tray table moves to the nearest place with room; the walks there
    and back go round the work table: the run stays within every audit limit."""
    diagram = build_diagram(load_scenario(cell))
    simulator = Simulator(diagram)
    context = simulator.get_context()
    tray_visits = 0
    for k in range(1, round(RUN) + 1):
        simulator.AdvanceTo(float(k))
        x, y, _ = diagram.GetOutputPort("human_status").Eval(context).base_pose
        tray_visits += abs(x) < 0.1 and y > 1.2
    assert tray_visits >= 2, "the person never reached the tray table"
    assert_within_the_audit_limits(realism_metrics(diagram.GetOutputPort("realism").Eval(context)))
