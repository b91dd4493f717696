"""Free objects never hang in the air and never sink into a surface."""

import pytest
from pydrake.math import RigidTransform

from hrc_drake.workpieces.messages import Despawn, Spawn
from tests.workpieces.workpieces_rig import (
    PART_HEIGHT,
    TABLE_TOP,
    WORK_TABLE_XY,
    build_rig,
    config_with,
)

X, Y = WORK_TABLE_XY
ON_TABLE = TABLE_TOP + PART_HEIGHT / 2
COMMANDS = [
    (0.0, Spawn(seq=1, type="part", pose=RigidTransform([X, Y, TABLE_TOP - 0.01]))),
    (0.1, Spawn(seq=2, type="part", pose=RigidTransform([X + 0.3, Y, 1.5]))),
    (0.2, Spawn(seq=3, type="part", pose=RigidTransform([X + 0.02, Y, ON_TABLE]))),
    (1.0, Despawn(seq=4, object_id=1)),
]


@pytest.fixture(scope="module")
def run():
    rig = build_rig(config_with(), {"human_tree": COMMANDS})
    return {t: rig.advance(t) for t in (0.05, 0.3, 0.9, 1.5)}


def height(status, object_id: int) -> float:
    return status.object(object_id).pose.translation()[2]


def test_an_object_placed_into_the_table_is_put_on_it(run):
    assert height(run[0.05], 1) == pytest.approx(ON_TABLE)
    assert run[0.05].object(1).support == "work_table"


def test_an_object_in_the_air_falls_and_lands_on_the_table(run):
    falling = run[0.3].object(2)
    assert falling.support is None and falling.velocity.translational()[2] < -1.0
    assert TABLE_TOP < height(run[0.3], 2) < 1.5
    assert height(run[0.9], 2) == pytest.approx(ON_TABLE)
    assert run[0.9].object(2).support == "work_table"
    assert not run[0.9].object(2).velocity.get_coeffs().any()


def test_an_object_placed_into_another_rests_on_it_and_falls_when_it_goes(run):
    assert height(run[0.3], 3) == pytest.approx(ON_TABLE + PART_HEIGHT)
    assert run[0.3].object(3).support == "object:1"
    assert height(run[1.5], 3) == pytest.approx(ON_TABLE)
    assert run[1.5].object(3).support == "work_table"
