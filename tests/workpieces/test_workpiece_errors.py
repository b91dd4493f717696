"""Commands that cannot be carried out end with a clear outcome; the simulation carries on."""

import dataclasses

import pytest
from pydrake.math import RigidTransform

from hrc_drake.areas import Area
from hrc_drake.messages import FAILED, REJECTED, SUCCEEDED
from hrc_drake.workpieces.messages import LEFT_HAND, ROBOT_HOLDER, Attach, Despawn, Detach, Spawn
from tests.workpieces.workpieces_rig import (
    PART,
    PART_HEIGHT,
    TABLE_TOP,
    TOOL_DOWN,
    WORK_TABLE_XY,
    build_rig,
    config_with,
    part_on_table,
)

X, Y = WORK_TABLE_XY
ON_TABLE = RigidTransform([X + 0.3, Y, TABLE_TOP + PART_HEIGHT / 2])
CUP_ON_PART = RigidTransform(TOOL_DOWN, [X, Y, TABLE_TOP + PART_HEIGHT])
COMMANDS = [
    Spawn(seq=1, type="part", pose=ON_TABLE),
    Spawn(seq=2, type="part", pose=ON_TABLE),
    Attach(seq=3, holder=ROBOT_HOLDER, object_id=99),
    Detach(seq=4, holder=ROBOT_HOLDER, object_id=1),
    Detach(seq=5, holder=ROBOT_HOLDER),
    Attach(seq=6, holder="tentacle"),
    Attach(seq=7, holder=LEFT_HAND, object_id=1),
    Spawn(seq=8, type="widget", pose=ON_TABLE),
    Despawn(seq=9, object_id=2),
    Spawn(seq=10, type="part", area="table"),
    Attach(seq=11, holder=ROBOT_HOLDER, object_id=1, max_mass=0.1),
    Attach(seq=12, holder=ROBOT_HOLDER, max_mass=3.0),
]
EXPECTED = {
    1: (SUCCEEDED, ""),
    2: (FAILED, "capacity reached: 2 objects of type 'part' exist"),
    3: (FAILED, "no object 99"),
    4: (FAILED, "object 1 is not held by robot (it is free)"),
    5: (FAILED, "robot holds nothing"),
    6: (REJECTED, "unknown holder 'tentacle'; known: robot, left_hand, right_hand, both_hands"),
    7: (FAILED, "there is no left_hand: the person's hands pose is not connected"),
    8: (REJECTED, "unknown object type 'widget'; known: part"),
    9: (SUCCEEDED, ""),
    10: (SUCCEEDED, ""),
    11: (FAILED, "object 1 weighs 0.4 kg, more than 0.1 kg"),
    12: (SUCCEEDED, ""),
}


@pytest.fixture(scope="module")
def results():
    """One command every 0.1 s; the result of each is read just before the next."""
    config = config_with(
        types={"part": dataclasses.replace(PART, capacity=2)}, objects=[part_on_table()]
    )
    table = Area.from_polygon([[X - 0.5, Y - 0.3], [X - 0.3, Y - 0.3], [X - 0.3, Y + 0.3]])
    timed = [(0.1 * c.seq, c) for c in COMMANDS]
    rig = build_rig(
        config, {"robot_tree": timed}, tool=lambda t: CUP_ON_PART, areas={"table": table}
    )
    return {c.seq: rig.advance(0.1 * c.seq + 0.05) for c in COMMANDS}


@pytest.mark.parametrize("seq", sorted(EXPECTED))
def test_each_command_has_a_clear_outcome(results, seq):
    result = results[seq].results_of("robot_tree").last
    assert result.seq == seq
    assert (result.outcome, result.reason) == EXPECTED[seq]


def test_the_simulation_carries_on_after_failures(results):
    assert results[1].results_of("robot_tree").last.object_id == 2
    assert results[9].object(2) is None
    spawned = results[10].object(results[10].results_of("robot_tree").last.object_id)
    assert spawned.support == "work_table"
    assert spawned.pose.translation()[2] == pytest.approx(TABLE_TOP + PART_HEIGHT / 2)
    assert results[12].object(1).holder == ROBOT_HOLDER
    assert results[12].free_slots == {"part": 0}
