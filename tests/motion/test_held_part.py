"""What the robot holds is kept clear of the cell as the tool is: a free-space move carries a
part over a box on the table, not through it; a part still on the table is lifted first.

The check that the part passes clear is made outside the planner: the part's corners, from
the tool's pose along the planned path, against the box's outline and top."""

import numpy as np
import pytest
from pydrake.geometry import Box
from pydrake.math import RigidTransform, RollPitchYaw

from hrc_drake.motion.errors import PlanningFailed
from hrc_drake.motion.messages import MoveLinear, MoveTo
from hrc_drake.motion.model import HeldPart
from tests.motion.motion_helpers import build_station, make_scenario

VARIANT = "lbr_iisy11_r1300"
BOX_AT = (0.0, 0.9)
BOX_OUTLINE = ((-0.1, 0.1), (0.75, 1.05))
"""x and y extents of box_small (0.3 x 0.2, turned 90°) on the table at BOX_AT."""
BOX_TOP = 1.1
TABLE_TOP = 0.9
DOWN = RollPitchYaw(np.pi, 0.0, 0.0)
SIZE = (0.12, 0.12, 0.25)
PART = HeldPart(Box(*SIZE), RigidTransform([0.0, 0.0, SIZE[2] / 2]))
"""A 25 cm part hanging from the cup (the tool's z points out of it, down)."""


@pytest.fixture(scope="module")
def planner():
    return build_station(make_scenario(VARIANT, box_at=BOX_AT)).motion.planner


def posture(planner, x: float, z: float) -> np.ndarray:
    pose = RigidTransform(DOWN, [x, BOX_AT[1], z])
    home = np.array(planner.model.variant.home)
    return planner.ik.solve(pose, home, False, np.random.default_rng(0), 16)


def lowest_over_the_box(planner, path) -> float:
    """The part's lowest corner wherever its corners' span overlaps the box's outline
    (inf when it never passes over the box)."""
    corners = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)])
    corners = corners * np.array(SIZE) / 2
    lowest = np.inf
    for t in np.linspace(0.0, path.duration, 400):
        X_WP = planner.model.tool_pose(path.position(t)) @ PART.X_TP
        world = np.array([X_WP @ corner for corner in corners])
        spans = zip(world[:, 0:2].min(axis=0), world[:, 0:2].max(axis=0), BOX_OUTLINE, strict=True)
        if all(low < high_box and high > low_box for low, high, (low_box, high_box) in spans):
            lowest = min(lowest, float(world[:, 2].min()))
    return lowest


def test_a_held_part_is_carried_over_a_box_the_tool_alone_clears(planner):
    start, target = posture(planner, -0.35, 1.3), RigidTransform(DOWN, [0.35, BOX_AT[1], 1.3])
    blind = planner.plan(MoveTo(seq=1, pose=target), start)
    assert lowest_over_the_box(planner, blind) < BOX_TOP - 0.03, "the straight move must clip it"

    carried = planner.plan(MoveTo(seq=1, pose=target), start, held=PART)
    assert lowest_over_the_box(planner, carried) > BOX_TOP + planner.options.clearance
    end = planner.model.tool_pose(carried.end).translation()
    assert np.linalg.norm(end - target.translation()) < 1e-3


def test_a_part_still_on_the_table_is_lifted_before_a_free_move(planner):
    on_the_table = posture(planner, -0.35, TABLE_TOP + SIZE[2])
    target = RigidTransform(DOWN, [0.35, BOX_AT[1], 1.3])
    with pytest.raises(PlanningFailed, match="part the robot holds starts closer.*MoveLinear"):
        planner.plan(MoveTo(seq=1, pose=target), on_the_table, held=PART)
    lift = RigidTransform(DOWN, [-0.35, BOX_AT[1], 1.3])
    assert planner.plan(MoveLinear(seq=2, pose=lift), on_the_table, held=PART) is not None


def test_a_target_the_held_part_cannot_reach_says_the_part_is_why(planner):
    start = posture(planner, -0.35, 1.3)
    into_the_box = RigidTransform(DOWN, [0.0, BOX_AT[1], BOX_TOP + 0.15])
    assert planner.plan(MoveTo(seq=1, pose=into_the_box), start) is not None
    with pytest.raises(PlanningFailed, match="with the part the robot holds"):
        planner.plan(MoveTo(seq=1, pose=into_the_box), start, held=PART)
