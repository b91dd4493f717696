"""Grasps from an object's geometry: which hands, where the palms go, how it is carried.

A part that fits in one hand and is light is taken with the right hand, the palm on its
right-hand face and the fingers round it (a thin one: the palm on its top, the forearm
turned in); anything else with both hands, the palms on the two faces that face the
person's sides (a thin one: on its top beside those faces). An attribute `grasp`
(`one_hand` or `both_hands`) overrides the choice; a `fragile` object always gets both
hands. While held, the arms keep a carry posture solved for the object's size: as people
carry a box, close to the body at the waist, the upper arms hanging and the elbows bent
(docs/realism.md).

Hand frames: the grasp frame lies just off the palm (skeleton `_frames`), so a grasp frame
put on a face is a palm touching it, not sinking in. With the arms hanging every hand frame
has x forward, y to the left and z up; the fingers point along -z; the left palm faces -y
and the right palm +y (both towards the body's midline).
"""

import math
from dataclasses import dataclass
from functools import lru_cache

import numpy as np
from pydrake.math import RotationMatrix

from hrc_drake.human.body import FrameTask, HumanBody
from hrc_drake.human.hand_shape import hand_half_breadth
from hrc_drake.human.keyed_clips import HOLD, pose_vector
from hrc_drake.human.messages import BOTH_HANDS, ONE_HAND, Grasp, Hold

ONE_HAND_WIDTH = 0.09
"""m: the widest a part may be across to be held in one hand, fingers round it."""
ONE_HAND_MASS = 1.0
"""kg: heavier parts are taken with both hands."""
GRASP_ATTRIBUTE = "grasp"
BELOW_ELBOWS = 0.05
"""m: both hands carry this far below elbow height (the shoulder's height less the upper
arm's length): the load at the waist, the upper arms hanging at the sides and the elbows
bent about 85 degrees (docs/realism.md: carrying as people carry)."""
TRUNK_CLEARANCE = 0.125
"""m: from the pelvis axis to the near face of an object carried in both hands: close to
the body, 2 cm in front of the belly (0.105 m for the default adult, between the hips and
the chest)."""
LOWEST_CARRY = 0.8
"""m: a tall object's bottom stays at least this high, clear of the swinging thighs."""
ONE_HAND_CARRY = (0.3, -0.12, 0.98)
"""Where the right palm carries a part, in the standing body's frame (x forward, y left)."""
ARM_JOINTS = ("shoulder", "elbow", "wrist")
ORIENTATION_WEIGHT = 0.3
"""The hands' orientation counts less than their position in the IK."""


def grasp_hands(size, mass: float, attributes: dict) -> str:
    """One hand or both, from the object's box extents (x, y, z), mass and attributes."""
    chosen = attributes.get(GRASP_ATTRIBUTE)
    if chosen in ("one_hand", "both_hands"):
        return ONE_HAND if chosen == "one_hand" else BOTH_HANDS
    small = min(size[0], size[1]) <= ONE_HAND_WIDTH and mass <= ONE_HAND_MASS
    return ONE_HAND if small and not attributes.get("fragile", False) else BOTH_HANDS


def _across(grasp: Grasp, heading: float) -> tuple[np.ndarray, float, float]:
    """The object's horizontal axis that points most to the person's left (a unit vector
    in the world) and the object's extents across it and along the other axis."""
    turn = grasp.yaw - heading
    x_is_forward = abs(math.cos(turn)) >= abs(math.sin(turn))
    axis_yaw = grasp.yaw + (math.pi / 2 if x_is_forward else 0.0)
    axis = np.array([math.cos(axis_yaw), math.sin(axis_yaw), 0.0])
    left = np.array([-math.sin(heading), math.cos(heading), 0.0])
    axis = axis if axis @ left >= 0 else -axis
    width, depth = (grasp.size[1], grasp.size[0]) if x_is_forward else grasp.size[:2]
    return axis, width, depth


def hold_of(grasp: Grasp, heading: float) -> Hold:
    """What the hands hold once they have taken `grasp` facing `heading`."""
    _, width, depth = _across(grasp, heading)
    return Hold(grasp.hands, (depth, width, grasp.size[2]))


HAND_AXES = {
    "sides_fingers_down": np.eye(3),
    "sides_fingers_forward": np.array([[0, 0, -1], [0, 1, 0], [1, 0, 0]], dtype=float),
    "top_fingers_in": RotationMatrix.MakeZRotation(math.radians(60.0)).matrix()
    @ np.array([[0, 0, -1], [1, 0, 0], [0, -1, 0]], dtype=float),
}
"""Hand orientations in the person's heading frame (columns: the hand frame's x, y, z):
palms on an object's sides, reaching down to it or holding it in front; the right palm down
on a thin part's top, the forearm turned in (pronated) and the fingers 60 degrees in from
straight ahead, as a hand lies flat on a table in front of the body. With the fingers
straight ahead the forearm turned in to its limit and the trunk bent aside to roll the hand
the rest: a right hand putting a board into a bin ahead bent the trunk 25 degrees to the
left, and the free arm went 6 cm into the table beside the person (a user's cell); turned
in 60 degrees, 16 and clear of it. Further in, the shoulder's rotation reaches its limit
carrying the part at the waist. The left hand's are their mirror images (the same for
palms on an object's sides)."""
MIRROR = np.diag([1.0, -1.0, 1.0])
"""The person's left-right mirror (the heading frame's y flipped)."""


def facing(heading: float, hand: str, side: str = "right") -> RotationMatrix:
    """The `side` hand's frame in the world for the orientation `hand` (a HAND_AXES key)."""
    axes = HAND_AXES[hand] if side == "right" else MIRROR @ HAND_AXES[hand] @ MIRROR + 0.0
    return RotationMatrix.MakeZRotation(heading) @ RotationMatrix(axes)


FINGERS_DOWN = 0.1
"""m: an object at least twice this tall is taken with the fingers pointing down its sides
(they end above its bottom: the fingertips reach 0.53 hand lengths below the grasp frame);
a lower one with the fingers pointing forward, the hand's breadth upright."""
GRIP_ABOVE_SUPPORT = 0.05
"""m: with the fingers forward the grasp frame is at least this high above the object's
bottom, so the hand's lower edge (half its breadth, 4.5 cm for the default adult, below
the frame) stays clear of what the object stands on."""


PINCHED_BELOW = 0.03
"""m: a part lower than this is taken from above, the palm down on its top and the fingers
round its edges (both hands: PALM_IN_FROM_EDGE in from its two side faces). Held from the
side, the hand's breadth upright, the palm stays GRIP_ABOVE_SUPPORT above what the part
stands on: more than 2 cm (the realism audit's limit) above a lower part's top (a 1.5 cm
circuit board was held 3.5 cm under the palm and pushed along beside the hand, a user's
cell; an 8 mm cardboard sheet 4.2 cm under both palms, taken and carried, a user's
palletizing cell)."""


def grip_style(hands: str, height: float) -> str:
    """How the hands take an object this tall (a HAND_AXES key)."""
    if height < PINCHED_BELOW:
        return "top_fingers_in"
    return "sides_fingers_down" if height / 2 >= FINGERS_DOWN else "sides_fingers_forward"


GRIP_BELOW_TOP = 0.07
"""m: with the fingers down an object's sides the grasp frame is this far below its top: the
wrist (8.5 cm above the frame) then stands 1.5 cm over the top edge and the forearm (a
capsule of 3.6 cm radius, its axis 2 cm off the palm) goes at most a few millimetres past
the face's plane there. With the palms at the middle of a 0.2 m carton's sides the wrists
were beside the faces and the forearms went 1.2 cm into the carton taken (collaboration,
seed 15); gripped higher still (6.5 cm below the top or less), IK left the hands 2 cm short
of a carton on a crate on a pallet."""


def grip_lift(hands: str, height: float) -> float:
    """How far above an object's centre its grasp frame is: a tall object is gripped high
    enough that the forearms clear its top, a low one near its top with the hand's edge
    clear of the surface below, a thin one on its top."""
    style = grip_style(hands, height)
    if style == "top_fingers_in":
        return height / 2 + PALM_GAP
    if style == "sides_fingers_down":
        return height / 2 - GRIP_BELOW_TOP
    return max(GRIP_ABOVE_SUPPORT - height / 2, 0.0)


PALM_GAP = 0.008
"""m: palms close on an object's faces this far off them: the hands are aimed by IK to a
centimetre or so, and a palm a little off the face holds it (the realism audit allows 2 cm)
where one a little in would be in it; and the forearm (a capsule of 3.6 cm radius, its axis
2 cm off the palm) then reaches less than a centimetre past the face's plane (5 mm off, it
went 1.1 cm into collaboration's carton taken from the pallet's far side, seed 0)."""
PALM_FROM_NEAR_FACE = 0.055
"""m: palms on the side faces of a deep object hold it this far from its near face, no
further forward: the wrist (8.5 cm behind the grasp frame) then stands 3 cm behind that
face, where the forearm (thicker than the hand, its axis 2 cm off the palm) is clear of the
object."""


def palm_back(hands: str, depth: float) -> float:
    """How far behind an object's centre palms on its side faces hold it (the object's
    extent `depth` along the person's heading; one hand: not at all)."""
    return max(depth / 2 - PALM_FROM_NEAR_FACE, 0.0) if hands == BOTH_HANDS else 0.0


def palm_targets(grasp: Grasp, heading: float) -> dict:
    """Where each taking hand's grasp frame goes (position, orientation) to take `grasp`:
    on the faces that face the person's sides (one hand: the right one only), towards the
    person's end of them."""
    axis, width, depth = _across(grasp, heading)
    return _holding(grasp.hands, grasp.center, heading, axis, (depth, width, grasp.size[2]))


def release_targets(hold: Hold, center, heading: float) -> dict:
    """Where each holding hand's grasp frame goes to put the held object's centre at
    `center` (facing `heading`)."""
    left = np.array([-math.sin(heading), math.cos(heading), 0.0])
    return _holding(hold.hands, center, heading, left, hold.size)


def _holding(hands: str, center, heading: float, left, size) -> dict:
    """The palms on the side faces of an object of `size` (its extents along the faces,
    across them, up) whose centre is at `center`, `left` the faces' normal towards the
    person's left (a thin part in one hand: the palm on its top): the palms back along the
    faces, towards the person, as far as `palm_back`, and turned with the faces (held to the
    person's heading, a palm 45° to the face of a part turned 135° went 1.02 cm into it with
    its edge, a user's cell)."""
    depth, width, height = size
    toward = np.array([left[1], -left[0], 0.0])  # along the faces, ahead for `left` ahead
    if toward @ [math.cos(heading), math.sin(heading), 0.0] < 0:
        toward = -toward
    held = np.asarray(center, dtype=float) - palm_back(hands, depth) * toward
    held = held + [0.0, 0.0, grip_lift(hands, height)]
    style = grip_style(hands, height)
    return palms_on(hands, held, left, width, style, math.atan2(toward[1], toward[0]))


def reach_target(body: HumanBody, point, heading: float) -> dict:
    """The right hand reaching to `point` on a surface: the hand level, fingers forward,
    its little-finger edge resting on the point rather than the fingers sinking in."""
    position = np.asarray(point, dtype=float) + [0.0, 0.0, hand_half_breadth(body)]
    return {"right": (position, facing(heading, "sides_fingers_forward"))}


def outward(side: str, R: RotationMatrix) -> np.ndarray:
    """The direction a palm on an object's face moves to let go of it (away from the
    object: the left palm faces the hand frame's -y, the right one its +y)."""
    return (1.0 if side == "left" else -1.0) * R.matrix()[:, 1]


def spread(palms: dict) -> dict:
    """The direction from the midpoint of two palms holding an object (side: orientation) to
    each: outwards for palms facing each other on its side faces; for palms on its top,
    across it, as their grip turns the hand frames (HAND_AXES). Told apart by whether they
    face each other, in any frame (in the chest's, a palm on a box's side leans with the
    trunk: lifted from the floor, one looked as if it were on the box's top)."""
    if outward("left", palms["left"]) @ outward("right", palms["right"]) < 0.0:
        return {side: outward(side, R) for side, R in palms.items()}
    sign = {"left": 1.0, "right": -1.0}
    return {
        side: R @ (facing(0.0, "top_fingers_in", side).inverse() @ np.array([0.0, sign[side], 0.0]))
        for side, R in palms.items()
    }


PALM_IN_FROM_EDGE = 0.05
"""m: two palms on a thin object's top lie this far in from its side faces: the hand (9 cm
across the palm for the default adult) on it, its heel at the edge."""


def palms_on(hands: str, center, left, width: float, style: str, yaw: float) -> dict:
    """The palms (grip `style`, the fingers forward along `yaw`) on an object `width`
    across `left` held at `center`: PALM_GAP off its faces, or on its top, one hand at the
    centre, two PALM_IN_FROM_EDGE in from those faces (one hand: the right)."""
    if style == "top_fingers_in" and hands == ONE_HAND:
        return {"right": (center, facing(yaw, style))}
    half = width / 2 - PALM_IN_FROM_EDGE if style == "top_fingers_in" else width / 2 + PALM_GAP
    right = {"right": (center - left * half, facing(yaw, style))}
    if hands == ONE_HAND:
        return right
    return {"left": (center + left * half, facing(yaw, style, "left")), **right}


def object_center_in_holder(hold: Hold) -> tuple[float, float, float]:
    """Where the held object's centre sits in its holder's frame (hrc_drake.workpieces: the
    palms' midpoint for both hands, a level frame at the palm for one): beside the palm,
    below it when the object is gripped near its top, ahead of the palms when they hold a
    deep object towards its near face."""
    below = -grip_lift(hold.hands, hold.size[2])
    if hold.hands == ONE_HAND:
        on_top = grip_style(hold.hands, hold.size[2]) == "top_fingers_in"
        return (0.0, 0.0 if on_top else hold.size[1] / 2, below)
    return (palm_back(hold.hands, hold.size[0]), 0.0, below)


@lru_cache(maxsize=64)
def arm_indices(body: HumanBody, sides: tuple[str, ...]) -> np.ndarray:
    """The joint indices of the `sides` arms, read-only: looked up once per body and sides
    (planning one command asks hundreds of times, 90 us each by name)."""
    indices = np.array(
        [
            i
            for i, name in enumerate(body.joint_names)
            if any(name.startswith(f"{side}_{joint}") for side in sides for joint in ARM_JOINTS)
        ]
    )
    indices.flags.writeable = False
    return indices


@dataclass(frozen=True, eq=False)
class CarryArms:
    """The arm joints of a carry posture: laid over any pose, they keep the held object in
    front of the chest whatever the legs and trunk do."""

    indices: np.ndarray
    values: np.ndarray
    hands: tuple[str, ...]
    """The sides whose hands hold the object (the other arm is free)."""
    size: tuple[float, float, float]
    """The held object's extents along the person's forward, sideways and up directions."""

    @property
    def hold(self) -> Hold:
        """What the hands hold, as a put-down is told it."""
        return Hold(BOTH_HANDS if len(self.hands) == 2 else ONE_HAND, self.size)

    def over(self, q: np.ndarray, weight: float = 1.0) -> np.ndarray:
        """`q` with its arms moved `weight` of the way to the carry posture."""
        if weight <= 0.0:
            return q
        held = q.copy()
        held[self.indices] += weight * (self.values - q[self.indices])
        return held


def held_corners(body: HumanBody, carry: CarryArms, q: np.ndarray) -> np.ndarray:
    """The corners (8 x 3) of the object held in the carry's hands at q, placed as the
    workpieces place it (hrc_drake.workpieces.world.holder_frames): level, at the palms'
    midpoint facing away from the body (both hands) or at the grasp point facing the
    person's heading (one hand), its centre where `object_center_in_holder` says."""
    hands = [body.frame_pose(f"{side}_hand_grasp", q).translation() for side in carry.hands]
    if len(hands) == 2:
        across = (hands[0] - hands[1])[:2]
        yaw = math.atan2(across[1], across[0]) - math.pi / 2
    else:
        yaw = q[body.index("base_yaw")]
    R = RotationMatrix.MakeZRotation(yaw).matrix()
    return box_corners(
        np.mean(hands, axis=0) + R @ object_center_in_holder(carry.hold), yaw, carry.size
    )


def box_corners(center, yaw: float, size) -> np.ndarray:
    """The corners (8 x 3) of a level box of `size` (along its own x, y, z) turned by `yaw`
    about its `center`."""
    R = RotationMatrix.MakeZRotation(yaw).matrix()
    return np.asarray(center) + (BOX_CORNERS * np.asarray(size) / 2) @ R.T


BOX_CORNERS = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)])
"""A box's corners, in units of its half extents."""


def carry_arms(body: HumanBody, hold: Hold) -> CarryArms:
    return _carry_arms(body, hold.hands, tuple(round(v, 4) for v in hold.size))


@lru_cache(maxsize=64)
def _carry_arms(body: HumanBody, hands: str, size: tuple) -> CarryArms:
    """Solved once per object size: palms on the object's faces, at the waist in front of
    the belly."""
    depth, width, height = size
    if hands == ONE_HAND:
        targets = {"right": (np.array(ONE_HAND_CARRY), facing(0.0, grip_style(hands, height)))}
    else:
        forward = TRUNK_CLEARANCE + depth / 2 - palm_back(hands, depth)
        elbows = body.sizes["shoulder_height"] - body.sizes["upper_arm"]
        z = max(elbows - BELOW_ELBOWS, LOWEST_CARRY + height / 2 + grip_lift(hands, height))
        style = "top_fingers_in" if height < PINCHED_BELOW else "sides_fingers_forward"
        targets = palms_on(
            hands, np.array([forward, 0.0, z]), np.array([0.0, 1.0, 0.0]), width, style, 0.0
        )
    q = pose_vector(body, HOLD)
    free = arm_indices(body, tuple(targets))
    solved = body.solve(q, hand_tasks(targets), free, iterations=100, posture_weight=1e-4)
    return CarryArms(free, solved[free], tuple(targets), size)


def _palm_down(R: RotationMatrix | None) -> bool:
    """Whether a hand frame at R has its palm (its y axis) facing down or up, as on a top."""
    return R is not None and abs(R.matrix()[2, 1]) > 0.5


def hand_tasks(
    targets: dict, orientation_weight: float = ORIENTATION_WEIGHT, turn_in_palm: bool = False
) -> list[FrameTask]:
    """IK tasks putting each side's grasp frame at its (position, orientation) target; with
    `turn_in_palm` only the palm's normal is held (the fingers point where the arm can put
    them, the palm flat on the face it targets)."""
    weights = (orientation_weight, 0.0, orientation_weight) if turn_in_palm else None
    return [
        FrameTask(
            f"{side}_hand_grasp",
            position,
            rotation,
            rotation_weights=weights or (orientation_weight,) * 3,
            rotation_axes=rotation if turn_in_palm else None,
            turns_forearm=side if _palm_down(rotation) else "",
        )
        for side, (position, rotation) in targets.items()
    ]


LEVEL_BELOW = 0.07
"""m: two palms taking an object lower than this are held level on its faces, the fingers
forward, where that keeps out of the cell. Free to turn about their normals, the arms point
the fingers down at what it stands on and the palms rise about 3.7 cm to clear it (a tray on
a 0.9 m table 0.45-0.6 m ahead): 4.8 cm above a 4 cm tray, and a user's pick failed; level,
1.4-1.7 cm off it. Put-downs still turn them (level, a 4 cm tray put on a trolley from the
carry posture put the left arm 3.7 cm into it, as `hrc-drake validate` plans it)."""


def palms_level_first(hands: dict, carry: CarryArms | None, takes: bool) -> tuple[bool, ...]:
    """Whether the palms aimed at `hands` (side: target) to take (`takes`) what `carry` holds
    are held level, in the order they are tried (LEVEL_BELOW)."""
    low = takes and carry is not None and carry.size[2] < LEVEL_BELOW
    return (True, False) if len(hands) == 2 and low else (False,)
