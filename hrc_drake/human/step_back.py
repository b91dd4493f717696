"""Stepping back before turning with what the hands carry: turned on the spot, a box held
in front sweeps its far corners round further ahead than the hands hold it, through a shelf
it was just taken from. People step back from a shelf before they turn with a box; where
there is no room to, the carry is refused, saying where."""

from math import atan2, cos, inf, sin

import numpy as np

from hrc_drake.human.aiming import Unreachable
from hrc_drake.human.furniture import Furniture
from hrc_drake.human.going_in import DEPTH_LIMIT, swept_depth
from hrc_drake.human.grasp import CarryArms
from hrc_drake.human.navigation import NavigationMap
from hrc_drake.human.performer import Performer
from hrc_drake.human.rotations import wrap_angle
from hrc_drake.human.segments import MIN_TURN, STEP_BACK_ROUNDING, StepBackSegment, TurnSegment

STEP_BACK_MOST = 0.5
"""m: the farthest the person steps back (in two steps) before turning with what the hands
carry."""


def stepped_back(
    performer: Performer, carry: CarryArms, furniture: Furniture, pose, path, t: float
) -> StepBackSegment | None:
    """Two steps straight back before turning towards the path with what the hands carry,
    as far as its turn needs to keep it out of the furniture (None: it is out turning where
    the person stands). A tote taken off a rack's board, held where it was drawn out of the
    rack, swept 2.5 cm into an upright as the person turned on the spot to walk away (a
    user's cell); people step back from a shelf before they turn with a box. Unreachable
    where no step back there is room for keeps it within DEPTH_LIMIT."""
    x, y, yaw = pose
    if len(path) < 2 or abs(_first_turn((x, y), yaw, path[1])) <= MIN_TURN:
        return None
    best = (inf, 0.0, "")
    for distance in np.arange(0.0, STEP_BACK_MOST + 1e-9, STEP_BACK_ROUNDING):
        spot = (x - distance * cos(yaw), y - distance * sin(yaw))
        if distance and not _room_behind(performer.navigation, (x, y), spot, yaw):
            break
        depth, where = _turning_depth(performer, carry, furniture, spot, yaw, path[1])
        best = min(best, (depth, distance, where))
        if depth <= 0.0:
            break
    depth, distance, where = best
    if depth > DEPTH_LIMIT:
        stepped = f"even stepped back {distance:.2f} m" if distance else "no room to step back"
        raise Unreachable(
            f"what the hands hold would go {100 * depth:.1f} cm into '{where}' at the walk's "
            f"start (turning on the spot): {stepped}"
        )
    if distance == 0.0:
        return None
    return StepBackSegment.between(performer, t, (x, y), yaw, distance, carry)


def _room_behind(navigation: NavigationMap | None, start, spot, yaw: float) -> bool:
    """Whether the person can step back from `start` to `spot`, facing `yaw`, and stand
    and turn there no deeper into the cell's geometry than where they stand."""
    if navigation is None:
        return True
    return navigation.walkable(start, spot) and _stand_depth(navigation, spot, yaw) <= _stand_depth(
        navigation, start, yaw
    )


def _stand_depth(navigation: NavigationMap, spot, yaw: float) -> float:
    problem = navigation.stand_problem(*spot, yaw)
    return 0.0 if problem is None else problem.depth


def _turning_depth(performer: Performer, carry, furniture, spot, yaw: float, toward):
    """How deep what the hands `carry` goes into the furniture as the person turns on the
    spot at `spot` from `yaw` to face the point `toward`, and into what."""
    turn = yaw + _first_turn(spot, yaw, toward)
    return swept_depth(
        performer, TurnSegment.between(performer, 0.0, spot, yaw, turn, carry), furniture
    )


def _first_turn(spot, yaw: float, toward) -> float:
    """How far the person turns at `spot` from `yaw` to face the point `toward`."""
    return wrap_angle(atan2(toward[1] - spot[1], toward[0] - spot[0]) - yaw)
