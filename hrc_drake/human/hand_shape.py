"""The hand's shape about its grasp frame: how far it reaches in a direction (beside, below
or above what the palm is on), measured on the skeleton's collision box of the hand."""

from functools import lru_cache

import numpy as np
from pydrake.math import RotationMatrix

from hrc_drake.human.body import HumanBody


def hand_half_breadth(body: HumanBody) -> float:
    """Half the hand's breadth (its collision box across the palm), from the skeleton."""
    (hand,) = body.skeleton.body("right_hand").collisions
    return hand.shape.size[0] / 2


def hand_below(body: HumanBody, R: RotationMatrix | None, side: str) -> float:
    """How far the `side` hand reaches below its grasp frame when that has the world
    orientation `R` (None: any; the farthest, fingers straight down)."""
    return hand_extent(body, R, (0.0, 0.0, -1.0), side)


def hand_extent(body: HumanBody, R: RotationMatrix | None, direction, side: str) -> float:
    """How far the `side` hand reaches from its grasp frame along the world `direction` (a
    unit vector) when the frame has the world orientation `R` (None: any orientation). The
    hands are mirror images: the grasp frame lies off the palm, so a left hand's back is
    where a right hand's palm would be."""
    corners = _hand_corners(body, side)
    if R is None:
        return float(np.max(np.linalg.norm(corners, axis=1)))
    return float(np.max(np.asarray(direction) @ (R.matrix() @ corners.T)))


@lru_cache(maxsize=16)
def _hand_corners(body: HumanBody, side: str) -> np.ndarray:
    """The corners of the `side` hand's collision box in its grasp frame."""
    (hand,) = body.skeleton.body(f"{side}_hand").collisions
    q = body.standing_pose()
    X_GH = body.frame_pose(f"{side}_hand_grasp", q).inverse() @ body.frame_pose(f"{side}_hand", q)
    half = np.asarray(hand.shape.size) / 2
    signs = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)])
    return np.array([X_GH @ (np.asarray(hand.shape.xyz) + sign * half) for sign in signs])
