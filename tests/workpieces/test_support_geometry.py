"""Support surfaces derived from the cell models, footprint overlaps, collision filtering."""

import numpy as np
import pytest
from pydrake.geometry import Role
from pydrake.math import RigidTransform, RollPitchYaw

from hrc_drake.workpieces.geometry import Solid, footprint, overlaps
from hrc_drake.workpieces.surfaces import FLOOR, cell_surfaces
from tests.workpieces.workpieces_rig import BELT_TOP, CONVEYOR_Y, TABLE_TOP, build_rig, config_with


@pytest.fixture(scope="module")
def rig():
    return build_rig(config_with())


def highest(surfaces, name: str):
    return max((s for s in surfaces if s.name == name), key=lambda s: s.height)


def test_cell_surfaces_are_the_top_faces_of_static_collision_boxes(rig):
    surfaces = cell_surfaces(rig.plant, rig.scene_graph)
    table = highest(surfaces, "work_table")
    assert table.height == pytest.approx(TABLE_TOP)
    np.testing.assert_allclose(table.bounds[0], [-0.6, 0.5])
    np.testing.assert_allclose(table.bounds[1], [0.6, 1.3])
    belt = [s for s in surfaces if s.name == "conveyor" and s.height == pytest.approx(BELT_TOP)]
    assert len(belt) == 1 and belt[0].bounds[0][1] == pytest.approx(CONVEYOR_Y - 0.2)
    assert highest(surfaces, FLOOR).height == pytest.approx(0.0)
    assert all(s.name != "part_small" for s in surfaces)  # free bodies are no supports


def test_touching_footprints_do_not_overlap_but_turned_ones_do():
    box = Solid("box", (0.2, 0.1, 0.1))
    left = footprint(box, RigidTransform([0.0, 0.0, 0.0]))
    assert not overlaps(left, footprint(box, RigidTransform([0.2, 0.0, 0.0])))
    turned = RigidTransform(RollPitchYaw(0, 0, np.pi / 4), [0.2, 0.0, 0.0])
    assert overlaps(left, footprint(box, turned))
    assert overlaps(left, None)


def test_workpieces_are_collision_filtered_against_the_plant_and_each_other(rig):
    inspector = rig.scene_graph.model_inspector()
    mine = rig.workpieces.geometry_set()
    mine_ids = inspector.GetGeometryIds(mine)
    others = [g for g in inspector.GetAllGeometryIds(Role.kProximity) if g not in mine_ids]
    assert len(mine_ids) == 6 and others
    for a in mine_ids:
        assert all(inspector.CollisionFiltered(a, b) for b in [*others, *mine_ids] if b != a)


def test_unused_slots_are_parked_far_apart_below_the_floor(rig):
    query = rig.query()
    positions = [query.GetPoseInWorld(f).translation() for f in rig.workpieces.frame_ids]
    assert all(p[2] <= -1000.0 for p in positions)
    gaps = [np.linalg.norm(a - b) for i, a in enumerate(positions) for b in positions[i + 1 :]]
    assert min(gaps) >= 10.0
    assert rig.status().objects == ()
