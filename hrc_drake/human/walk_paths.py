"""The path a walk follows, shaped for walking: waypoints without legs too short to walk,
cut where a corner is too sharp to walk round (hrc_drake.human.planning walks each stretch
and turns on the spot between them)."""

from math import atan2, hypot

import numpy as np

from hrc_drake.human.rotations import wrap_angle
from hrc_drake.human.walking import CORNER_RADIUS, walkable_turn

MIN_LEG = 0.3
"""m: shorter legs between waypoints are dropped."""


def without_short_legs(path: list, walkable=None) -> list:
    """The path without waypoints closer than MIN_LEG to the point before them (the goal
    stays): a short leg would make the person swing round on the spot while walking. A
    waypoint stays where the leg past it would not be `walkable` (a, b)."""
    kept = [path[0]]
    for point, after in zip(path[1:-1], path[2:], strict=True):
        short = hypot(point[0] - kept[-1][0], point[1] - kept[-1][1]) < MIN_LEG
        if not short or (walkable is not None and not walkable(kept[-1], after)):
            kept.append(point)
    goal = path[-1]
    if hypot(goal[0] - kept[-1][0], goal[1] - kept[-1][1]) > 1e-3:
        kept.append(goal)
    return kept


def cut_at_sharp_corners(path: list) -> list[list]:
    """The path cut at its sharp corners: walked through round a corner, the stance foot
    would have to twist further than a hip turns, so the person stops there and turns on
    the spot. A corner is sharp beyond SHARP_CORNER where the heading can turn over
    2 * CORNER_RADIUS, and in proportion beyond less where a short leg leaves less room
    (the heading turns over half the shorter leg on either side)."""
    stretches, current = [], [path[0]]
    for before, corner, after in zip(path, path[1:], path[2:], strict=False):
        current.append(corner)
        turn = wrap_angle(
            atan2(after[1] - corner[1], after[0] - corner[0])
            - atan2(corner[1] - before[1], corner[0] - before[0])
        )
        room = min(CORNER_RADIUS, hypot(*np.subtract(corner, before)) / 2)
        room = min(room, hypot(*np.subtract(after, corner)) / 2)
        if not walkable_turn(turn, room):
            stretches.append(current)
            current = [corner]
    current.append(path[-1])
    return [*stretches, current] if len(path) > 1 else []
