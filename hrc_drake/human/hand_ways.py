"""The ways of the hands in and out of an aimed clip: to a point above the target and a
little wider apart before they close on it (`approached`), up beside the body and over the
edge of the surface the target is on (`over_the_edge`), from taking an object into the carry
posture (`carried_off`), from the carry posture to putting it down (`put_down`), and off a
surface when a reach is cut short (`withdrawal`). Each writes its postures as keys of one
clip (`Keys`): an offset at a clip time, or the hands put on waypoints by IK there
(hrc_drake.human.aiming); hrc_drake.human.targeting lays them out round the clip's event.
"""

import numpy as np
from pydrake.math import RotationMatrix
from shapely.geometry import MultiPoint

from hrc_drake.human.aiming import (
    WAYPOINT_TOLERANCE,
    AimedMotion,
    Unreachable,
    hands_on,
    offset_to,
)
from hrc_drake.human.body import HumanBody
from hrc_drake.human.clip import Clip
from hrc_drake.human.furniture import Furniture
from hrc_drake.human.grasp import (
    PALM_GAP,
    CarryArms,
    arm_indices,
    facing,
    hand_below,
    hand_extent,
    hand_half_breadth,
    hand_tasks,
    object_center_in_holder,
    outward,
    release_targets,
)
from hrc_drake.human.keyed_clips import minimum_jerk
from hrc_drake.human.messages import BOTH_HANDS, ONE_HAND, Hold
from hrc_drake.human.skeleton import SIDES

APPROACH = (0.06, 0.06)
"""m: where the hands come to before they close on the target: this far outwards (palms
on an object's faces; a reaching hand: back towards the body) and this far above it."""
LEAVE_AT = (0.3, 0.6, 0.8)
"""Fractions of the time from letting go to the clip's end at which hands leaving a surface
are back above their target, over the surface's edge again, and down below its top outside
the edge (from there they swing back to the body's sides)."""
LOWERED = 0.25
"""m: how far hands leaving a surface go straight down outside its edge: below its top,
before the clip's own arms take them back to the body's sides (on the way straight there,
a hand over the edge swung forward and down into a box standing at it: coexistence seed 9,
2 cm)."""
CLEARANCE = 0.02
"""m: the hands' lowest edge passes this far above what they pass over."""
EDGE_MARGIN = 0.015
"""m: hands rising to a surface stay this far outside its edge."""
TRUNK_FRONT = 0.15
"""m: from the pelvis axis to in front of the belly with a hand's half breadth (the belly
is 0.105 m in front for the default adult)."""
TRUNK_SIDE = 0.22
"""m: from the body's midline to beside the trunk, outside the shoulders (0.186 m)."""
WITHDRAWAL = 1.0
"""s: hands cut short on a surface take this long to leave it."""
PASSAGE_KEYS = 4
"""Keys (IK solutions) along a passage of the hands from one place to another."""
CARRY_SAMPLES = 8
"""Points of the way between the grasp and the carry posture at which the palms are put on
the object's faces by IK."""
HOLDING_SLIP = 0.02
"""m: palms whose spacing strays further than this from the held object's are off its faces
by more than about 1 cm each, past their 8 mm gap (the audit allows 2 cm)."""
WAY_BEND = 0.05
"""m: how far the held object's way may pass beside the straight one between its ends (it
runs in the chest's frame, which turns and leans with the trunk: coexistence seed 9's
box passed 3 cm outside it, over a stack)."""
CHEST = "chest"
"""The body the hands' way with a held object is laid out in."""
HOLDING_ORIENTATION = 1.0
"""Weight of the hands' orientation while they hold an object on its way: a palm that
tilts pokes its fingers into the object."""


def approached(
    hands: dict, heading: float, reaching: bool, opening: bool = True, above=None, room=None
) -> dict:
    """The hands' targets moved to where they come before closing on them: above, and
    (`opening`) outwards from an object's faces (a reaching hand: back towards the body);
    hands that hold what they put down stay on it. `above` (side: height) raises a hand
    further, so far that its grasp frame is at least that high; `room` (side: m) is as far
    as a palm can open outwards (a neighbouring object)."""
    out, up = APPROACH
    back = -np.array([np.cos(heading), np.sin(heading), 0.0])
    moved = {}
    for side, (position, R) in hands.items():
        away = back if reaching or R is None else outward(side, R)
        wide = min(out, (room or {}).get(side, out))
        point = np.asarray(position) + opening * wide * away + [0.0, 0.0, up]
        point[2] = max(point[2], (above or {}).get(side, -np.inf))
        moved[side] = (point, R)
    return moved


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
    slack = {}
    for side, across in (("left", left), ("right", -left)):
        need, low, high, start = 0.0, center[2] - half_height, center[2] + half_height, center
        if side in palms:
            position, R = palms[side]
            need = PALM_GAP + hand_extent(body, R, across, side) + EDGE_MARGIN
            low = min(low, position[2] - hand_below(body, R, side))
            start = position - across * (hold.size[1] / 2 + PALM_GAP)
        breadth = hand_half_breadth(body)
        free = furniture.clear_way(start, across, breadth, low, high) - hold.size[1] / 2
        slack[side] = free - need
    short, other = sorted(slack, key=slack.get)
    if slack[short] >= 0.0 or slack[other] <= 0.0:
        return center
    away = -left if short == "left" else left
    return center + min(-slack[short], slack[other]) * away


def clearing(body: HumanBody, furniture: Furniture, hands: dict, lowest) -> dict:
    """Per side, the height a hand's grasp frame keeps above what it is aimed at and its
    neighbours: its lowest edge CLEARANCE above `lowest` (side: height its lowest point
    passes over, e.g. the top of what it takes; default: its target's height less its
    reach below the frame), and above the surface the target is on."""
    heights = {}
    for side, (position, R) in hands.items():
        reach = hand_below(body, R, side)
        over = lowest.get(side, position[2] - reach) if lowest else position[2] - reach
        support = furniture.support(position)
        if support is not None:
            over = max(over, support.high)
        heights[side] = over + reach + CLEARANCE
    return heights


def over_the_edge(body, furniture: Furniture, hands: dict, near: dict, base, heading):
    """Where the hands rise to before they move over the surface their targets are on, and
    leave it by: above it with the hand's whole length, whichever way it points, just
    outside its edge (the hand's half breadth and a margin) back towards the body from
    their approach points; beside the trunk where that is in front of it. None when no
    target is over a surface of the cell."""
    forward = np.array([np.cos(heading), np.sin(heading), 0.0])
    left = np.array([-forward[1], forward[0], 0.0])
    R = facing(heading, "sides_fingers_down")
    clear, moved = {}, False
    for side, (position, orientation) in near.items():
        support = furniture.support(hands[side][0])
        inset = hand_extent(body, R, forward, side) + EDGE_MARGIN
        edge = None
        if support is not None:
            edge = furniture.behind_edge(support, position, -forward, inset)
        if edge is None:
            clear[side] = (position, orientation)
            continue
        ahead, aside = (edge - base) @ forward[:2], (edge - base) @ left[:2]
        if ahead < TRUNK_FRONT:
            sign = 1.0 if side == "left" else -1.0
            aside = sign * max(sign * aside, TRUNK_SIDE)
        height = max(position[2], support.high + hand_below(body, R, side) + CLEARANCE)
        point = np.array([*(base + ahead * forward[:2] + aside * left[:2]), height])
        clear[side], moved = (point, None), True
    return clear if moved else None


def withdrawal(body, furniture, clip, placed_pose, q, sides, heading) -> AimedMotion | None:
    """Offsets that take hands cut short on a surface (a cancelled reach) off it the way
    they came, over WITHDRAWAL seconds of `clip` (idle) from the pose `q`: up, over the
    edge beside the body, down. None when no hand is over a surface of the cell."""
    hands = {side: (body.frame_pose(f"{side}_hand_grasp", q).translation(), None) for side in sides}
    hands = {side: target for side, target in hands.items() if furniture.support(target[0])}
    if not hands:
        return None
    keys = Keys(body, clip, placed_pose)
    keys.add(0.0, q - placed_pose(clip.sample(0.0)))
    up = approached(
        hands, heading, False, opening=False, above=clearing(body, furniture, hands, None)
    )
    base = q[[body.index("base_x"), body.index("base_y")]]
    edge = over_the_edge(body, furniture, hands, up, base, heading)
    keys.reach(LEAVE_AT[0] * WITHDRAWAL, up)
    if edge is not None:
        keys.off_the_edge(edge, WITHDRAWAL * np.array(LEAVE_AT[1:]))
    keys.add(WITHDRAWAL, np.zeros_like(q))
    return keys.motion(tuple(hands), (0.0, 0.0))


class Keys:
    """The offsets of an aimed clip, key by key: each an offset at a clip time, or the hands
    put on targets by IK there; a passage moves the arms from one posture to the next over
    PASSAGE_KEYS keys, played straight through."""

    def __init__(self, body: HumanBody, clip: Clip, placed_pose):
        self.body, self.clip, self.placed_pose = body, clip, placed_pose
        self.times: list[float] = []
        self.offsets: list[np.ndarray] = []
        self.paths: list[tuple[int, int]] = []
        self.arms = arm_indices(body, SIDES)

    def add(self, time: float, offset: np.ndarray) -> None:
        self.times.append(time)
        self.offsets.append(offset)

    def reach(self, time: float, targets: dict) -> None:
        """A key with the hands on `targets` (fingers as the targets have them), if they
        reach them without stepping."""
        offset = self._solved(time, targets, self.offsets[-1])
        if offset is not None:
            self.add(time, offset)

    def passage(self, time: float, targets: dict | None = None, offset=None) -> None:
        """Keys from the last one to `time`, where the hands are on `targets` (or the pose
        has `offset`): the arms move from the one posture to the other whatever the clip's
        arms do meanwhile (a clip's own arm motion would drag the hands off their way)."""
        if offset is None:
            offset = self._solved(time, targets, self.offsets[-1])
            if offset is None:
                return
        first, arms = len(self.times) - 1, self.arms
        start_time, start = self.times[-1], self.offsets[-1]
        a = self._pose(start_time, start)[arms]
        b = self._pose(time, offset)[arms]
        times = np.linspace(start_time, time, PASSAGE_KEYS + 1)[1:]
        for k, t in enumerate(times, start=1):
            s = minimum_jerk(k / len(times))
            key = start + s * (offset - start)
            key[arms] = a + s * (b - a) - self._pose(t, 0.0)[arms]
            self.add(t, key)
        self.paths.append((first, len(self.times) - 1))

    def off_the_edge(self, edge: dict, times) -> None:
        """Keys that take the hands over a surface's `edge` (its waypoints) and then straight
        down outside it, at the two `times`."""
        self.passage(times[0], edge)
        self.reach(
            times[1], {side: (p - [0.0, 0.0, LOWERED], None) for side, (p, _) in edge.items()}
        )

    def _pose(self, time: float, offset) -> np.ndarray:
        return self.placed_pose(self.clip.sample(time)) + offset

    def _solved(self, time: float, targets: dict, start: np.ndarray):
        """The offset at `time` with the hands on `targets`: the arms start from where the
        last key has them, or else the whole body from the clip's pose (IK finds some
        postures only from one of them); None when neither reaches."""
        placed = self._pose(time, 0.0)
        following = placed + start
        following[self.arms] = self._pose(self.times[-1], self.offsets[-1])[self.arms]
        for q in (following, placed):
            try:
                return hands_on(self.body, q, targets, True, WAYPOINT_TOLERANCE) - placed
            except Unreachable:
                continue
        return None

    def motion(self, hands: tuple[str, ...], held: tuple[float, float]) -> AimedMotion:
        return AimedMotion(tuple(self.times), tuple(self.offsets), tuple(self.paths), hands, held)


def _between(start: dict, end: dict, s: float) -> dict:
    """Targets of the holding hands a fraction s of the way from their grasp frames `start`
    to `end` (in one frame): each hand turns about its palm's normal as the object turns, two
    palms keep their spacing about their midpoint, which moves straight."""
    sides = tuple(start)
    turned = {side: _slerp(start[side].rotation(), end[side].rotation(), s) for side in sides}
    if len(sides) == 1:
        (side,) = sides
        a, b = start[side].translation(), end[side].translation()
        return {side: (a + s * (b - a), turned[side])}
    a, b = (np.mean([X[side].translation() for side in sides], axis=0) for X in (start, end))
    width = float(np.linalg.norm(start["left"].translation() - start["right"].translation()))
    middle = a + s * (b - a)
    return {side: (middle + outward(side, R) * width / 2, R) for side, R in turned.items()}


def _slerp(a: RotationMatrix, b: RotationMatrix, s: float) -> RotationMatrix:
    return RotationMatrix(a.ToQuaternion().slerp(s, b.ToQuaternion()))


def _way(body, clip, placed_pose, times, start, end, trunk_from, trunk_to, arms, over=None):
    """Offsets at `times` (evenly spaced) on the way of the holding hands from `start` to
    `end` (grasp frames in the chest's frame at the first and last time): the way runs in
    the chest's frame, which rises and turns with the trunk, so the arms can follow it; the
    arms are solved to hold the object, the rest of the body eases from the offset
    `trunk_from` to `trunk_to`. With `over` (a world height), the palms' midpoint rises to
    it first, crosses at that height and lowers last (over what stands on the way), if the
    arms can hold the object up there: else it goes the straight way (lifted too high, a
    carton in both hands was 5.3 cm off a palm: collaboration seed 15)."""
    offsets, slipped = _held_way(
        body, clip, placed_pose, times, start, end, trunk_from, trunk_to, arms, over
    )
    if over is not None and slipped > HOLDING_SLIP:
        offsets, _ = _held_way(
            body, clip, placed_pose, times, start, end, trunk_from, trunk_to, arms
        )
    return offsets


def _held_way(body, clip, placed_pose, times, start, end, trunk_from, trunk_to, arms, over=None):
    """`_way`'s offsets, and how far the palms' spacing strays from the object's on it."""
    offsets, solved, slipped = [], None, 0.0
    for k, t in enumerate(times):
        s = k / (len(times) - 1)
        placed = placed_pose(clip.sample(t))
        q = placed + trunk_from + s * (trunk_to - trunk_from)
        if solved is not None:  # each point starts from the last: the arms follow the way
            q[arms] = solved[arms]
        chest = body.frame_pose(CHEST, q)
        local = _between(start, end, minimum_jerk(s if over is None else _crossing(s)))
        targets = {side: (chest @ p, chest.rotation() @ R) for side, (p, R) in local.items()}
        if over is not None:
            middle = np.mean([p for p, _ in targets.values()], axis=0)
            rise = _plateau(s) * max(over - middle[2], 0.0)
            targets = {side: (p + [0.0, 0.0, rise], R) for side, (p, R) in targets.items()}
        tasks = hand_tasks(targets, HOLDING_ORIENTATION)
        solved = body.solve(q, tasks, arms, iterations=60, posture_weight=1e-4)
        offsets.append(solved - placed)
        slipped = max(slipped, _spacing_error(body, solved, targets))
    return offsets, slipped


def _spacing_error(body, q: np.ndarray, targets: dict) -> float:
    """How far the holding palms' spacing at q is from their targets' (0: one hand)."""
    if len(targets) < 2:
        return 0.0
    at = [body.frame_pose(f"{side}_hand_grasp", q).translation() for side in targets]
    aimed = [p for p, _ in targets.values()]
    return abs(float(np.linalg.norm(at[0] - at[1]) - np.linalg.norm(aimed[0] - aimed[1])))


def _crossing(s: float) -> float:
    """How far across a way over something the hands are at s: in its middle half."""
    return min(max(2.0 * s - 0.5, 0.0), 1.0)


def _plateau(s: float) -> float:
    """How far up to the crossing height the hands are at s: up in the first quarter of the
    way, down in the last."""
    return minimum_jerk(min(4.0 * s, 1.0)) * minimum_jerk(min(4.0 * (1.0 - s), 1.0))


def crossing_height(body, furniture: Furniture, carry: CarryArms, a, b, heading: float):
    """The height the holding palms' midpoint keeps while it carries the object from `a` to
    `b` (the midpoint's world positions at the two ends): the object's bottom and the
    hands' lowest edges CLEARANCE above whatever stands under its way higher than where the
    object's bottom is at the lower end and lower than its top at the higher one (a stack
    beside where a box is put down, the edge of a board it is taken off; not the board
    above). None: nothing does."""
    depth, width, height = carry.size
    ahead, aside, below = object_center_in_holder(Hold(_hands_of(carry), carry.size))
    R = facing(heading, "sides_fingers_forward")
    hand = max(hand_extent(body, R, outward(side, R), side) for side in carry.hands)
    lowest = max(-below + height / 2, *(hand_below(body, R, side) for side in carry.hands))
    up = (0.0, 0.0, 1.0)
    highest = max(below + height / 2, *(hand_extent(body, R, up, side) for side in carry.hands))
    forward = np.array([np.cos(heading), np.sin(heading)])
    left = np.array([-forward[1], forward[0]])
    corners = [
        np.asarray(end[:2]) + (ahead + u * depth / 2) * forward + (aside + v) * left
        for end in (a, b)
        for u in (-1.0, 1.0)
        for v in (-width / 2 - PALM_GAP - hand, width / 2 + PALM_GAP + hand)
    ]
    bottom = min(a[2], b[2]) - lowest
    area = MultiPoint(corners).convex_hull.buffer(WAY_BEND)
    top = furniture.highest_between(area, bottom + CLEARANCE / 2, max(a[2], b[2]) + highest)
    return None if top is None else top + CLEARANCE + lowest


def _over(body, carry: CarryArms, a: np.ndarray, b: np.ndarray, around) -> float | None:
    """The crossing height of the way of the held object from pose a to pose b."""
    furniture, heading = around
    middle = [
        np.mean([body.frame_pose(f"{s}_hand_grasp", q).translation() for s in carry.hands], axis=0)
        for q in (a, b)
    ]
    return crossing_height(body, furniture, carry, *middle, heading)


def _hands_of(carry: CarryArms) -> str:
    return BOTH_HANDS if len(carry.hands) == 2 else ONE_HAND


def _in_chest(body: HumanBody, q: np.ndarray, sides) -> dict:
    """The hands' grasp frames in the chest's frame at q."""
    chest = body.frame_pose(CHEST, q).inverse()
    return {s: chest @ body.frame_pose(f"{s}_hand_grasp", q) for s in sides}


def carried_off(body, clip, placed_pose, hands, carry, on_target, marks, keys: "Keys", around):
    """Offsets of a clip that takes an object and carries it off in the carry posture:
    `keys` up to the grasp, then the way into the carry posture, over what stands on it
    (`around`: the furniture and the person's heading)."""
    approach_time, _, hold_end = marks
    sides = tuple(hands)
    grasped = placed_pose(clip.sample(hold_end)) + on_target
    end_pose = placed_pose(clip.sample(clip.duration))
    carried = carry.over(end_pose)
    start, end = _in_chest(body, grasped, sides), _in_chest(body, carried, sides)
    times = tuple(np.linspace(hold_end, clip.duration, CARRY_SAMPLES))
    zero = np.zeros_like(on_target)
    over = _over(body, carry, grasped, carried, around)
    arms = arm_indices(body, sides)
    way = _way(body, clip, placed_pose, times, start, end, on_target, zero, arms, over)
    way[0], way[-1] = on_target, carried - end_pose
    first = len(keys.times)
    for time, offset in zip(times, way, strict=True):
        keys.add(time, offset)
    keys.paths.append((first, len(keys.times) - 1))
    return keys.motion(sides, (approach_time, clip.duration))


def put_down(
    body, clip, placed_pose, hands, carry, near_offset, on_target, marks, opened, edge, around
):
    """Offsets of a clip that starts in the carry posture and puts the object down over
    what stands on its way (`around`: the furniture and the person's heading): the hands
    open to `opened` and, over a surface, leave it over its `edge`."""
    approach_time, event, hold_end = marks
    sides = tuple(hands)
    start_pose = placed_pose(clip.sample(0.0))
    held = carry.over(start_pose)
    above = placed_pose(clip.sample(approach_time)) + near_offset
    start, end = _in_chest(body, held, sides), _in_chest(body, above, sides)
    times = tuple(np.linspace(0.0, approach_time, CARRY_SAMPLES))
    zero = np.zeros_like(on_target)
    arms = arm_indices(body, sides)
    over = _over(body, carry, held, above, around)
    way = _way(body, clip, placed_pose, times, start, end, zero, near_offset, arms, over)
    way[0], way[-1] = held - start_pose, near_offset
    keys = Keys(body, clip, placed_pose)
    for time, offset in zip(times, way, strict=True):
        keys.add(time, offset)
    keys.paths.append((0, CARRY_SAMPLES - 1))
    keys.add(event, on_target)
    keys.add(hold_end, on_target)
    release_end = hold_end + 0.3 * (clip.duration - hold_end)
    keys.add(
        release_end, offset_to(body, placed_pose, clip, release_end, on_target, opened, on_target)
    )
    if edge is not None:
        rest = clip.duration - release_end
        keys.off_the_edge(edge, release_end + rest * np.array(LEAVE_AT[1:]))
    keys.add(clip.duration, zero)
    return keys.motion(sides, (0.0, release_end))
