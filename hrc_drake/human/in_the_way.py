"""What stands in the person's way over the floor besides the cell (the robot at rest and
what it holds still): the robot's parts as boxes, the obstacles a walk goes round, and the
rest of a walk under way that might pass through them (hrc_drake.human.protocol asks when
the robot comes to rest mid-walk)."""

import numpy as np

from hrc_drake.human.activity import Activity
from hrc_drake.human.messages import Box
from hrc_drake.human.navigation import Obstacle, box_obstacle, in_band
from hrc_drake.human.walking import WalkSegment

ROBOT = "the robot at rest"
"""What a refusal calls the robot's parts."""


def robot_boxes(starts, spans, radii) -> list[Box]:
    """Boxes round the cylinders of capsules (starts and spans, parts × 3, and radii, as the
    safety monitor bounds the robot; its own shapes are cylinders): each in pieces no longer
    than its radius, so that the boxes round a slanted one stay close to it."""
    boxes = []
    for start, span, radius in zip(starts, spans, radii, strict=True):
        length = float(np.linalg.norm(span))
        pieces = max(1, int(np.ceil(length / radius)))
        piece = span / pieces
        along, up = float(np.hypot(piece[0], piece[1])), abs(float(piece[2]))
        yaw = float(np.arctan2(piece[1], piece[0])) if along > 1e-9 else 0.0
        level, upright = (along, up) / np.maximum(length / pieces, 1e-9)
        size = (along + 2 * radius * upright, 2 * radius, up + 2 * radius * level)
        if length < 1e-9:
            size = (2 * radius,) * 3
        for k in range(pieces):
            center = tuple((start + (k + 0.5) * piece).tolist())
            boxes.append(Box(center, yaw, size, name=ROBOT))
    return boxes


def in_the_way(boxes: tuple[Box, ...]) -> tuple[Obstacle, ...]:
    """The obstacles of the `boxes` that stand within the body's heights."""
    return tuple(o for o in map(box_obstacle, boxes) if in_band(o.low, o.high))


def rest_of_walk(activity: Activity, t: float) -> list[tuple[float, float]]:
    """The pelvis's path from where it is at t to the end of the activity's walks (empty
    when none is left)."""
    path = []
    for segment in activity.segments:
        if isinstance(segment, WalkSegment) and segment.over > t:
            along = segment.distance(max(t, segment.start))
            path.append(segment.point(along))
            path += [p for p, at in zip(segment.path, segment.lengths, strict=True) if at > along]
    return path
