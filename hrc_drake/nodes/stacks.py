"""Objects lying on others, as the trees' nodes see them: which of a stack is taken next
(`covered`: not one with another on it) and where a box put down goes (onto what lies at
its target, not into it)."""

import numpy as np
from pydrake.math import RigidTransform

from hrc_drake.workpieces import messages as wp
from hrc_drake.workpieces.geometry import Solid, footprint, overlaps

COVER_OVERLAP = 0.01
"""m: an object counts as lying on another when their outlines overlap by more than this (the
support a piece keeps is what it landed on; boxes that stand side by side touch)."""


def covered(objects) -> dict[int, int]:
    """The ids of the objects another free object lies on, each with the id of one lying
    on it."""
    by_id = {obj.id: obj for obj in objects}
    pairs = [(obj, by_id.get(wp.object_id_of_support(obj.support))) for obj in objects]
    return {
        below.id: obj.id
        for obj, below in pairs
        if obj.holder is None
        and below is not None
        and overlaps(_outline(obj), _outline(below), COVER_OVERLAP)
    }


def on_top_of_what_lies_there(point, held: wp.ObjectStatus, objects) -> np.ndarray:
    """`point`, where `held`'s centre is to go, raised onto the top of the free objects it
    would come down on (`on_top_of`)."""
    others = [
        (_solid(obj), obj.pose) for obj in objects if obj.holder is None and obj.id != held.id
    ]
    return on_top_of(point, _solid(held), others)


def on_top_of(point, solid: Solid, others) -> np.ndarray:
    """`point`, where the centre of a `solid` is to go, raised onto the top of the `others`
    (solids and their poses) it would come down on: those level with it whose outlines are
    within half its narrower extent of the point. `hrc-drake validate` plans a put-down
    where the run puts it (it planned a tote put where another lay inside that one)."""
    point = np.array(point, dtype=float)
    reach, half = np.ptp(solid.outline(), axis=0).min() / 2, solid.height / 2
    for _ in others:  # each pass may lift it onto one more object of a stack
        tops = [
            top
            for bottom, top, near in (_extent_at(*other, point, reach) for other in others)
            if near and bottom < point[2] + half and top > point[2] - half
        ]
        if not tops:
            break
        point[2] = max(tops) + half
    return point


def _extent_at(
    solid: Solid, pose: RigidTransform, point, reach: float
) -> tuple[float, float, bool]:
    """The bottom and top heights of `solid` at `pose`, and whether `point` is within
    `reach` of its outline on the floor."""
    center = pose.translation()
    level = RigidTransform([point[0], point[1], center[2]])
    beside = solid.signed_distance_to((pose.inverse() @ level).translation())
    half = solid.height / 2
    return center[2] - half, center[2] + half, beside < reach


def _solid(obj: wp.ObjectStatus) -> Solid:
    return Solid(obj.shape, obj.size)


def _outline(obj: wp.ObjectStatus) -> np.ndarray:
    return footprint(_solid(obj), obj.pose)
