"""Aim pick, place, reach and hand-over: IK on the human body along the clip.

The clip's pose at its key event (grasp, release, reached, extended) is corrected by IK so
each aiming hand's grasp frame is at its target (hrc_drake.human.grasp: palms on an
object's faces), with the feet where they stand; arms, trunk bend and pelvis height (a
squat) are free. The hands come to it from above and outside: first to a point above it,
the hands' lowest edge clear of the top of what they take, and, for palms on an object's
faces, a little wider apart (APPROACH), so that they close on the object rather than
sweeping through it, its neighbours or what it stands on. A target on a surface of the cell
(a table top, a shelf board, a pallet) is approached over the surface's edge: the hands
rise in front of the body, outside the edge, to above the surface, and only then move over
it; they leave it the same way. A clip that takes an object then carries it into the carry
posture: the palms stay on its faces while the object moves from where it was taken to where
it is carried (the hands turn about their palms' normal, IK at a few points of the way). A
clip that puts an object down starts from the carry posture, carries it above the target,
sets it down, and opens the hands outwards before they go back. The corrections are joint
offsets at key times of the clip, blended smoothly in between (`AimedMotion`).

The IK and the offsets' player are hrc_drake.human.aiming; the ways in and out (from above,
over a surface's edge, withdrawing) are hrc_drake.human.hand_ways, with an object held
(taking, putting down) hrc_drake.human.held_ways.
"""

import numpy as np

from hrc_drake.human.aiming import AimedMotion, Unreachable, forearms_level, hands_on, offset_to
from hrc_drake.human.body import HumanBody
from hrc_drake.human.clip import Clip
from hrc_drake.human.furniture import Furniture
from hrc_drake.human.grasp import CarryArms
from hrc_drake.human.hand_shape import hand_below, hand_half_breadth
from hrc_drake.human.hand_ways import (
    LEAVE_AT,
    Keys,
    approached,
    below_the_top,
    clearing,
    over_the_edge,
)
from hrc_drake.human.held_ways import carried_off, headroom, put_down
from hrc_drake.human.palm_room import room_beside

TARGETED = {
    "pick_floor": "grasp",
    "pick_table": "grasp",
    "place_floor": "release",
    "place_table": "release",
    "reach": "reached",
    "hand_over": "extended",
}
"""Clips that accept a target, and the event at which the hands arrive."""
ONTO_A_TOP = "place_table"
"""The clip that puts what the hands hold down onto a top at a table's height; the other
(place_floor) lets go over the floor, or a bin's floor (below what the furniture keeps:
hrc_drake.human.navigation.BAND; cooperation's scrap bin, 12 cm over its floor)."""
HOLD_AFTER_EVENT = 0.3
MAX_HORIZONTAL_REACH = 1.2
APPROACH_AT = 0.7
"""Fraction of the time to the event at which the hands are at the approach point."""
RISE_AT = 0.4
"""Fraction of the time to the event at which hands on their way to a surface have risen
above it, outside its edge."""
NO_FURNITURE = Furniture()
REST_GAP = 0.003
"""m: a hand resting on a surface keeps its lowest point this far above it."""
RESTING_PASSES = 4
"""Times a hand resting on a surface is moved by how far its lowest point is off."""


def hold_end_of(clip: Clip, event: str) -> float:
    """The clip time until which the hands stay on their targets after `event` (a grasp or
    a release): the clip's next event, or HOLD_AFTER_EVENT later."""
    later = sorted(t for t in clip.events.values() if t > clip.events[event])
    return later[0] if later else min(clip.events[event] + HOLD_AFTER_EVENT, clip.duration)


FLOOR_HEIGHT = 0.0
"""m: the floor's top, which every cell's floor model has at z = 0."""


def _floors(body: HumanBody, furniture: Furniture, hands: dict, reaching: bool) -> dict:
    """Per side, the height the hand's lowest point keeps above at its target, and whether
    it rests there: a reaching hand's edge on the point it reaches to, palms on an object's
    faces anywhere above the surface it stands on, the floor where no piece is under them
    (palms on a 0.12 m tote on the floor turned their fingers down its sides and a hand
    went 3.7 cm into the floor, a cell of our own)."""
    floors = {}
    for side, (position, _) in hands.items():
        support = furniture.support(position)
        if reaching:
            floors[side] = (position[2] - hand_half_breadth(body), True)
        else:
            floors[side] = (FLOOR_HEIGHT if support is None else support.high, False)
    return floors


def _resting(
    body: HumanBody, q: np.ndarray, hands: dict, floors: dict, level: bool
) -> tuple[np.ndarray, dict]:
    """`hands_on` (`level`: two palms held level, not free to turn about their normals),
    each hand with a floor moved up until its lowest point is REST_GAP above it, or, resting
    there, up or down (IK leaves a hand tilted a little: on a surface a corner would dip into
    it, or the hand would hover); and the hands' targets so moved, which the ways in and out
    end at (lowered straight onto the targets as given, a tote put down on the floor went 3 cm
    below its place, the hands 3 cm into the floor, and came back up to it)."""
    turning = False if level else None
    solved = hands_on(body, q, hands, turning)
    for _ in range(RESTING_PASSES):
        off = {}
        for side, (floor, rests) in floors.items():
            error = floor + REST_GAP - _lowest(body, solved, side)
            off[side] = error if rests else max(error, 0.0)
        if all(abs(error) <= REST_GAP for error in off.values()):
            break
        hands = {
            side: (np.asarray(p) + [0.0, 0.0, off.get(side, 0.0)], R)
            for side, (p, R) in hands.items()
        }
        solved = hands_on(body, solved, hands, turning)
    return solved, hands


def _raised(body: HumanBody, q: np.ndarray, hands: dict, furniture: Furniture, heading: float):
    """q with the forearms level behind hands aimed at a surface of the cell above the
    shoulders (`forearms_level`), where they reach over its edge."""
    if all(furniture.support(position) is None for position, _ in hands.values()):
        return q
    return forearms_level(body, q, hands, heading)


def _lowest(body: HumanBody, q: np.ndarray, side: str) -> float:
    """The height of the `side` hand's lowest point at q."""
    X = body.frame_pose(f"{side}_hand_grasp", q)
    return X.translation()[2] - hand_below(body, X.rotation(), side)


def aim_clip(
    body: HumanBody,
    clip: Clip,
    placed_pose,
    hands: dict,
    heading: float,
    carry: CarryArms | None = None,
    takes: bool = False,
    furniture: Furniture = NO_FURNITURE,
    lowest: dict | None = None,
    level: bool = False,
) -> AimedMotion:
    """The joint offsets that make `clip` (placed in the world by `placed_pose`) put each
    hand's grasp frame at its target: `hands` maps a side to (position, orientation or
    None). `carry`: the carry posture of what the hands take (`takes`) or put down.
    `furniture`: the cell's surfaces, approached from above and over their edge; `lowest`
    (side: height): what a hand's lowest edge passes over on its way (the top of what it
    takes). `level`: two palms held level at their targets (grasp.LEVEL_BELOW).

    `placed_pose(q)` maps a clip pose to the world. Raises Unreachable with a reason.
    """
    event_name = TARGETED[clip.name]
    event = clip.events[event_name]
    hold_end = hold_end_of(clip, event_name)
    at_event = placed_pose(clip.sample(event))
    middle = np.mean([position for position, _ in hands.values()], axis=0)
    base = at_event[[body.index("base_x"), body.index("base_y")]]
    distance = float(np.linalg.norm(middle[:2] - base))
    if distance > MAX_HORIZONTAL_REACH:
        raise Unreachable(f"target {distance:.2f} m away, out of reach without walking")
    reaching = clip.name == "reach"
    floors = _floors(body, furniture, hands, reaching)
    on_target, hands = _resting(
        body, _raised(body, at_event, hands, furniture, heading), hands, floors, level
    )
    on_target = on_target - at_event
    approach_time = APPROACH_AT * event
    putting_down = carry is not None and not takes
    above = clearing(body, furniture, hands, lowest, base)
    room = room_beside(body, furniture, hands)
    roof = headroom(body, furniture, carry, middle, heading) if putting_down else np.inf
    near = approached(
        hands, heading, reaching, not putting_down, None if putting_down else above, room, roof
    )
    marks = (approach_time, event, hold_end)
    if putting_down:
        opened = approached(hands, heading, False, above=above, room=room)
        return put_down(
            body,
            clip,
            placed_pose,
            hands,
            carry,
            near,
            on_target,
            marks,
            opened,
            over_the_edge(body, furniture, hands, opened, base, heading, held=True),
            (furniture, heading),
        )
    near_offset = offset_to(body, placed_pose, clip, approach_time, on_target, near, on_target)
    edge = over_the_edge(body, furniture, hands, near, base, heading)
    keys = Keys(body, clip, placed_pose)
    keys.add(0.0, np.zeros_like(on_target))
    if edge is not None:
        keys.reach(RISE_AT * event, edge)
        keys.passage(approach_time, offset=near_offset)
    else:
        keys.add(approach_time, near_offset)
    keys.add(event, on_target)
    if takes:
        around = (furniture, heading)
        return carried_off(body, clip, placed_pose, hands, carry, on_target, marks, keys, around)
    keys.add(hold_end, on_target)
    if edge is not None:
        rest = clip.duration - hold_end
        keys.reach(hold_end + LEAVE_AT * rest, near)
        lowered = below_the_top(body, furniture, hands)
        keys.off_the_edge(edge, clip.duration, lowered)
    keys.add(clip.duration, np.zeros_like(on_target))
    return keys.motion(tuple(hands), (approach_time, hold_end))
