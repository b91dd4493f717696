"""SceneGraph sees every object where the status says it is, and an empty slot's geometry
parked out of the way: through carrying, releasing, settling, despawning and removal at a
belt end."""

import numpy as np
from pydrake.common.schema import Transform

from hrc_drake.systems.workpieces import parked_pose
from hrc_drake.workpieces.config import REMOVE, ConveyorConfig, PlacedObject
from hrc_drake.workpieces.messages import Despawn
from tests.workpieces.workpieces_rig import (
    BELT_TOP,
    PART_HEIGHT,
    TABLE_TOP,
    WORK_TABLE_XY,
    build_rig,
    carry_to,
    config_with,
)

X, Y = WORK_TABLE_XY
REMOVING = ConveyorConfig(start=[-1.0, -1.5, BELT_TOP], end=[-0.6, -1.5, BELT_TOP], at_end=REMOVE)


def test_scene_poses_follow_the_objects_and_park_empty_slots():
    on_belt = PlacedObject(type="part", pose=Transform(translation=[-0.8, -1.5, BELT_TOP + 0.03]))
    on_table = PlacedObject(type="part", pose=Transform(translation=[X, Y, TABLE_TOP + 0.03]))
    resting = PlacedObject(type="part", pose=Transform(translation=[X - 0.3, Y, TABLE_TOP + 0.03]))
    config = config_with(objects=[on_table, on_belt, resting], conveyors={"removing": REMOVING})
    tool, commands = carry_to((X + 0.4, Y - 0.2, TABLE_TOP + PART_HEIGHT + 0.03))
    commands["robot_tree"] = [(2.0, Despawn(seq=1, object_id=3))]
    rig = build_rig(config, commands, tool)
    slots = rig.workpieces.geometry_ids
    seen = set()
    for t in np.arange(0.0, 4.5, 0.0137):
        status, query = rig.advance(t), rig.query()
        occupied = {}
        for obj in status.objects:
            occupied[obj.geometry_id] = obj.pose
            seen.add((obj.id, obj.holder, obj.support))
        for slot, geometry_id in enumerate(slots):
            expected = occupied.get(geometry_id, parked_pose(slot))
            np.testing.assert_allclose(
                query.GetPoseInWorld(geometry_id).GetAsMatrix34(),
                expected.GetAsMatrix34(),
                atol=1e-9,
                err_msg=f"slot {slot} at t={t:.4f}",
            )
    assert (1, "robot", None) in seen and (1, None, "work_table") in seen
    assert {obj.id for obj in status.objects} == {1}  # 2 left at the belt's end, 3 despawned
