"""Room for the palms beside what they hold: how far a palm on an object's face can open
before the back of the hand meets something (`room_beside`, for the approach of
hrc_drake.human.hand_ways), and where a box is put down so that each palm has room beside
what stands next to it (`room_for_the_palms`)."""

import numpy as np

from hrc_drake.human.body import HumanBody
from hrc_drake.human.furniture import Furniture
from hrc_drake.human.grasp import (
    PALM_GAP,
    outward,
    release_targets,
)
from hrc_drake.human.hand_shape import hand_below, hand_extent, hand_half_breadth
from hrc_drake.human.hand_ways import EDGE_MARGIN
from hrc_drake.human.messages import Hold


def room_beside(body: HumanBody, furniture: Furniture, hands: dict) -> dict:
    """Per side, how far a palm on an object's face can open outwards before the back of the
    hand meets something (its thickness and a margin less than the free way)."""
    room = {}
    for side, (position, R) in hands.items():
        if R is None:
            continue
        reach = hand_below(body, R, side)
        free = furniture.room(position, outward(side, R), position[2] - reach, position[2] + reach)
        room[side] = max(free - hand_extent(body, R, outward(side, R), side) - EDGE_MARGIN, 0.0)
    return room


def room_for_the_palms(body: HumanBody, furniture: Furniture, hold: Hold, center, heading):
    """`center`, where the held object is to be put down, moved across its held faces so
    that what stands beside it leaves room for each palm on them: the palm's gap, the
    hand's thickness and a margin (a box put down against another would have the palm
    between them in the other box; people put it down a hand's width off). Moved only as
    far as the other side has room; unchanged where neither side has enough."""
    center = np.asarray(center, dtype=float)
    palms = release_targets(hold, center, heading)
    left = np.array([-np.sin(heading), np.cos(heading), 0.0])
    half_height = hold.size[2] / 2
    slack, breadth = {}, hand_half_breadth(body)
    for side, across in (("left", left), ("right", -left)):
        need, low, high, start = 0.0, center[2] - half_height, center[2] + half_height, center
        if side in palms:
            position, R = palms[side]
            need = PALM_GAP + hand_extent(body, R, across, side) + EDGE_MARGIN
            low = min(low, position[2] - hand_below(body, R, side))
            start = position - across * (hold.size[1] / 2 + PALM_GAP)
        free = furniture.clear_way(start, across, breadth, low, high) - hold.size[1] / 2
        slack[side] = free - need
    short, other = sorted(slack, key=slack.get)
    if slack[short] >= 0.0 or slack[other] <= 0.0:
        return center
    away = -left if short == "left" else left
    return center + min(-slack[short], slack[other]) * away
