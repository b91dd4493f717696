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

Longer than 400 lines: the ways in and out (from above, over a surface's edge, taking,
putting down, withdrawing) write the same key times of one clip (`_Keys`); splitting them
from it is the next step when this grows.
"""

from dataclasses import dataclass

import numpy as np
from pydrake.math import RigidTransform, RotationMatrix

from hrc_drake.human.body import FrameTask, HumanBody
from hrc_drake.human.clip import Clip
from hrc_drake.human.furniture import Furniture
from hrc_drake.human.grasp import (
    CarryArms,
    arm_indices,
    facing,
    hand_below,
    hand_extent,
    hand_half_breadth,
    hand_tasks,
    outward,
)
from hrc_drake.human.keyed_clips import minimum_jerk
from hrc_drake.human.skeleton import SIDES

TARGETED = {
    "pick_floor": "grasp",
    "pick_table": "grasp",
    "place_floor": "release",
    "place_table": "release",
    "reach": "reached",
    "hand_over": "extended",
}
"""Clips that accept a target, and the event at which the hands arrive."""

HAND_TOLERANCE = 0.02
WAYPOINT_TOLERANCE = 0.06
"""m: hands on their way (rising beside the body, over a surface's edge) need only come
near their waypoints; the arms are then kept clear of the furniture all the way
(hrc_drake.human.clearance)."""
FOOT_TOLERANCE = 0.01
FEET_WEIGHT = (4.0, 4.0, 4.0)
"""Feet outrank hands in the IK: the person bends rather than sliding a foot."""
HOLD_AFTER_EVENT = 0.3
MAX_HORIZONTAL_REACH = 1.2
TRUNK = (
    "pelvis_height",
    "pelvis_tilt",
    "lumbar_flexion",
    "lumbar_bending",
    "thorax_flexion",
    "thorax_rotation",
)
APPROACH = (0.06, 0.06)
"""m: where the hands come to before they close on the target: this far outwards (palms
on an object's faces; a reaching hand: back towards the body) and this far above it."""
APPROACH_AT = 0.7
"""Fraction of the time to the event at which the hands are at the approach point."""
RISE_AT = 0.4
"""Fraction of the time to the event at which hands on their way to a surface have risen
above it, outside its edge."""
LEAVE_AT = (0.3, 0.6)
"""Fractions of the time from letting go to the clip's end at which hands leaving a surface
are back above their target, and over the surface's edge again."""
NO_FURNITURE = Furniture()
CLEARANCE = 0.02
"""m: the hands' lowest edge passes this far above what they pass over."""
EDGE_MARGIN = 0.015
"""m: hands rising to a surface stay this far outside its edge."""
TRUNK_FRONT = 0.15
"""m: from the pelvis axis to in front of the belly with a hand's half breadth (the belly
is 0.105 m in front for the default adult)."""
TRUNK_SIDE = 0.22
"""m: from the body's midline to beside the trunk, outside the shoulders (0.186 m)."""
REST_GAP = 0.003
"""m: a hand resting on a surface keeps its lowest point this far above it."""
RESTING_PASSES = 4
"""Times a hand resting on a surface is moved by how far its lowest point is off."""
WITHDRAWAL = 1.0
"""s: hands cut short on a surface take this long to leave it."""
PASSAGE_KEYS = 4
"""Keys (IK solutions) along a passage of the hands from one place to another."""
CARRY_SAMPLES = 8
"""Points of the way between the grasp and the carry posture at which the palms are put on
the object's faces by IK."""
CHEST = "chest"
"""The body the hands' way with a held object is laid out in."""


PALM_ORIENTATION = 1.0
"""Weight of a palm's orientation reaching for a target."""
HOLDING_ORIENTATION = 1.0
"""Weight of the hands' orientation while they hold an object on its way: a palm that
tilts pokes its fingers into the object."""


class Unreachable(ValueError):
    """The person cannot put a hand on the target without stepping."""


@dataclass(frozen=True, eq=False)
class AimedMotion:
    """Joint offsets that aim a clip: at each key time an offset added to the clip's pose;
    in between they ease from key to key (minimum jerk), or run straight through the evenly
    spaced keys of a carried object's way (`paths`; the way itself eases the object)."""

    times: tuple[float, ...]
    offsets: tuple[np.ndarray, ...]
    paths: tuple[tuple[int, int], ...] = ()
    """(first key, last key) of each stretch that is one smooth movement."""
    hands: tuple[str, ...] = ()
    """The sides whose hands are aimed."""
    held: tuple[float, float] = (0.0, 0.0)
    """The clip times between which the aimed hands are on their targets or hold what they
    took (on their way there and back they are free)."""

    def holds(self, clip_time: float) -> bool:
        return self.held[0] <= clip_time <= self.held[1]

    def offset(self, clip_time: float) -> np.ndarray:
        times = self.times
        if clip_time <= times[0]:
            return self.offsets[0]
        if clip_time >= times[-1]:
            return self.offsets[-1]
        for first, last in self.paths:
            if times[first] <= clip_time <= times[last]:
                return self._along(first, last, clip_time)
        k = int(np.searchsorted(times, clip_time, side="right")) - 1
        s = minimum_jerk((clip_time - times[k]) / (times[k + 1] - times[k]))
        return self.offsets[k] + s * (self.offsets[k + 1] - self.offsets[k])

    def _along(self, first: int, last: int, clip_time: float) -> np.ndarray:
        span = self.times[last] - self.times[first]
        u = (clip_time - self.times[first]) / span * (last - first)
        k = min(int(u), last - first - 1)
        a, b = self.offsets[first + k], self.offsets[first + k + 1]
        return a + (u - k) * (b - a)

    def pose(self, placed: np.ndarray, clip_time: float) -> np.ndarray:
        return placed + self.offset(clip_time)


def _hold_end(clip: Clip, event: str) -> float:
    later = sorted(t for t in clip.events.values() if t > clip.events[event])
    return later[0] if later else min(clip.events[event] + HOLD_AFTER_EVENT, clip.duration)


def _free_joints(body: HumanBody, sides, squat: bool) -> np.ndarray:
    """Arms of the aiming hands and the trunk; with `squat` also pelvis height and legs."""
    names = [n for n in body.joint_names if n in TRUNK and (squat or n != "pelvis_height")]
    parts = [(side, ("shoulder", "elbow", "wrist")) for side in sides]
    if squat:
        parts += [(side, ("hip", "knee", "ankle")) for side in SIDES]
    for side, joints in parts:
        names += [n for n in body.joint_names if n.startswith(side) and any(j in n for j in joints)]
    return np.array([body.index(n) for n in names])


def _feet_tasks(body: HumanBody, q: np.ndarray) -> list[FrameTask]:
    tasks = []
    for side in SIDES:
        X: RigidTransform = body.frame_pose(f"{side}_sole", q)
        tasks.append(
            FrameTask(
                f"{side}_sole",
                X.translation(),
                X.rotation(),
                FEET_WEIGHT,
                rotation_weights=(1.0, 1.0, 1.0),
            )
        )
    return tasks


def _reach(
    body: HumanBody,
    q: np.ndarray,
    hands: dict,
    turning: bool | None = None,
    tolerance: float = HAND_TOLERANCE,
) -> np.ndarray:
    """q with the aiming hands' grasp frames on their targets, within `tolerance`, the feet
    where they stand (a squat if the hands cannot reach otherwise). With `turning` the palms
    may turn about their normals (the fingers pointing where the arms put them best); by
    default two palms on an object's faces do. Raises Unreachable."""
    feet = _feet_tasks(body, q)
    both = len(hands) == 2 if turning is None else turning
    for squat, oriented in ((False, True), (True, True), (True, False)):
        aimed = hands if oriented else {s: (p, None) for s, (p, _) in hands.items()}
        tasks = hand_tasks(aimed, PALM_ORIENTATION, turn_in_palm=both)
        solved = body.solve(
            q,
            tasks + feet,
            _free_joints(body, tuple(hands), squat),
            iterations=150,
            posture_weight=1e-3,
        )
        hand_error = body.task_error(solved, tasks)
        feet_error = body.task_error(solved, feet) / FEET_WEIGHT[0]
        if hand_error <= tolerance and feet_error <= FOOT_TOLERANCE:
            return solved
    if hand_error <= tolerance:
        raise Unreachable("only reachable by stepping")
    raise Unreachable(f"hand stays {hand_error:.2f} m from the target")


def _floors(body: HumanBody, furniture: Furniture, hands: dict, reaching: bool) -> dict:
    """Per side, the height the hand's lowest point keeps above at its target, and whether
    it rests there: a reaching hand's edge on the point it reaches to, palms on an object's
    faces anywhere above the surface it stands on."""
    floors = {}
    for side, (position, _) in hands.items():
        support = furniture.support(position)
        if reaching:
            floors[side] = (position[2] - hand_half_breadth(body), True)
        elif support is not None:
            floors[side] = (support.high, False)
    return floors


def _resting(body: HumanBody, q: np.ndarray, hands: dict, floors: dict) -> np.ndarray:
    """`_reach`, each hand with a floor moved up until its lowest point is REST_GAP above
    it, or, resting there, up or down (IK leaves a hand tilted a little: on a surface a
    corner would dip into it, or the hand would hover)."""
    solved = _reach(body, q, hands)
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
        solved = _reach(body, solved, hands)
    return solved


def _lowest(body: HumanBody, q: np.ndarray, side: str) -> float:
    """The height of the `side` hand's lowest point at q."""
    X = body.frame_pose(f"{side}_hand_grasp", q)
    return X.translation()[2] - hand_below(body, X.rotation())


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


def _room(body: HumanBody, furniture: Furniture, hands: dict) -> dict:
    """Per side, how far a palm on an object's face can open outwards before the back of the
    hand meets something (its thickness and a margin less than the free way)."""
    room = {}
    for side, (position, R) in hands.items():
        if R is None:
            continue
        reach = hand_below(body, R)
        free = furniture.room(position, outward(side, R), position[2] - reach, position[2] + reach)
        room[side] = max(free - hand_extent(body, R, outward(side, R)) - EDGE_MARGIN, 0.0)
    return room


def clearing(body: HumanBody, furniture: Furniture, hands: dict, lowest) -> dict:
    """Per side, the height a hand's grasp frame keeps above what it is aimed at and its
    neighbours: its lowest edge CLEARANCE above `lowest` (side: height its lowest point
    passes over, e.g. the top of what it takes; default: its target's height less its
    reach below the frame), and above the surface the target is on."""
    heights = {}
    for side, (position, R) in hands.items():
        reach = hand_below(body, R)
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
        inset = hand_extent(body, R, forward) + EDGE_MARGIN
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
        height = max(position[2], support.high + hand_below(body, R) + CLEARANCE)
        point = np.array([*(base + ahead * forward[:2] + aside * left[:2]), height])
        clear[side], moved = (point, None), True
    return clear if moved else None


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
) -> AimedMotion:
    """The joint offsets that make `clip` (placed in the world by `placed_pose`) put each
    hand's grasp frame at its target: `hands` maps a side to (position, orientation or
    None). `carry`: the carry posture of what the hands take (`takes`) or put down.
    `furniture`: the cell's surfaces, approached from above and over their edge; `lowest`
    (side: height): what a hand's lowest edge passes over on its way (the top of what it
    takes).

    `placed_pose(q)` maps a clip pose to the world. Raises Unreachable with a reason.
    """
    event_name = TARGETED[clip.name]
    event = clip.events[event_name]
    hold_end = _hold_end(clip, event_name)
    at_event = placed_pose(clip.sample(event))
    middle = np.mean([position for position, _ in hands.values()], axis=0)
    base = at_event[[body.index("base_x"), body.index("base_y")]]
    distance = float(np.linalg.norm(middle[:2] - base))
    if distance > MAX_HORIZONTAL_REACH:
        raise Unreachable(f"target {distance:.2f} m away, out of reach without walking")
    reaching = clip.name == "reach"
    on_target = _resting(body, at_event, hands, _floors(body, furniture, hands, reaching))
    on_target = on_target - at_event
    approach_time = APPROACH_AT * event
    putting_down = carry is not None and not takes
    above = clearing(body, furniture, hands, lowest)
    room = _room(body, furniture, hands)
    near = approached(
        hands, heading, reaching, not putting_down, None if putting_down else above, room
    )
    near_offset = _offset(body, placed_pose, clip, approach_time, on_target, near, on_target)
    marks = (approach_time, event, hold_end)
    if putting_down:
        opened = approached(hands, heading, False, above=above, room=room)
        return _putting_down(
            body,
            clip,
            placed_pose,
            hands,
            carry,
            near_offset,
            on_target,
            marks,
            opened,
            over_the_edge(body, furniture, hands, opened, base, heading),
        )
    edge = over_the_edge(body, furniture, hands, near, base, heading)
    keys = _Keys(body, clip, placed_pose)
    keys.add(0.0, np.zeros_like(on_target))
    if edge is not None:
        keys.reach(RISE_AT * event, edge)
        keys.passage(approach_time, offset=near_offset)
    else:
        keys.add(approach_time, near_offset)
    keys.add(event, on_target)
    if takes:
        return _taking(body, clip, placed_pose, hands, carry, on_target, marks, keys)
    keys.add(hold_end, on_target)
    if edge is not None:
        rest = clip.duration - hold_end
        keys.reach(hold_end + LEAVE_AT[0] * rest, near)
        keys.passage(hold_end + LEAVE_AT[1] * rest, edge)
    keys.add(clip.duration, np.zeros_like(on_target))
    return keys.motion(tuple(hands), (approach_time, hold_end))


def withdrawal(body, furniture, clip, placed_pose, q, sides, heading) -> AimedMotion | None:
    """Offsets that take hands cut short on a surface (a cancelled reach) off it the way
    they came, over WITHDRAWAL seconds of `clip` (idle) from the pose `q`: up, over the
    edge beside the body, down. None when no hand is over a surface of the cell."""
    hands = {side: (body.frame_pose(f"{side}_hand_grasp", q).translation(), None) for side in sides}
    hands = {side: target for side, target in hands.items() if furniture.support(target[0])}
    if not hands:
        return None
    keys = _Keys(body, clip, placed_pose)
    keys.add(0.0, q - placed_pose(clip.sample(0.0)))
    up = approached(
        hands, heading, False, opening=False, above=clearing(body, furniture, hands, None)
    )
    base = q[[body.index("base_x"), body.index("base_y")]]
    edge = over_the_edge(body, furniture, hands, up, base, heading)
    keys.reach(LEAVE_AT[0] * WITHDRAWAL, up)
    if edge is not None:
        keys.passage(LEAVE_AT[1] * WITHDRAWAL, edge)
    keys.add(WITHDRAWAL, np.zeros_like(q))
    return keys.motion(tuple(hands), (0.0, 0.0))


class _Keys:
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
                return _reach(self.body, q, targets, True, WAYPOINT_TOLERANCE) - placed
            except Unreachable:
                continue
        return None

    def motion(self, hands: tuple[str, ...], held: tuple[float, float]) -> AimedMotion:
        return AimedMotion(tuple(self.times), tuple(self.offsets), tuple(self.paths), hands, held)


def _offset(body, placed_pose, clip, time, start, targets, fallback):
    """The offset at clip `time` that puts the hands on `targets` (IK from the clip's pose
    there plus `start`), or `fallback` where they cannot get there without stepping."""
    placed = placed_pose(clip.sample(time))
    try:
        return _reach(body, placed + start, targets) - placed
    except Unreachable:
        return fallback


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


def _way(body, clip, placed_pose, times, start, end, trunk_from, trunk_to, arms):
    """Offsets at `times` (evenly spaced) on the way of the holding hands from `start` to
    `end` (grasp frames in the chest's frame at the first and last time): the way runs in
    the chest's frame, which rises and turns with the trunk, so the arms can follow it; the
    arms are solved to hold the object, the rest of the body eases from the offset
    `trunk_from` to `trunk_to`."""
    offsets, solved = [], None
    for k, t in enumerate(times):
        s = k / (len(times) - 1)
        placed = placed_pose(clip.sample(t))
        q = placed + trunk_from + s * (trunk_to - trunk_from)
        if solved is not None:  # each point starts from the last: the arms follow the way
            q[arms] = solved[arms]
        chest = body.frame_pose(CHEST, q)
        local = _between(start, end, minimum_jerk(s))
        targets = {side: (chest @ p, chest.rotation() @ R) for side, (p, R) in local.items()}
        tasks = hand_tasks(targets, HOLDING_ORIENTATION)
        solved = body.solve(q, tasks, arms, iterations=60, posture_weight=1e-4)
        offsets.append(solved - placed)
    return offsets


def _in_chest(body: HumanBody, q: np.ndarray, sides) -> dict:
    """The hands' grasp frames in the chest's frame at q."""
    chest = body.frame_pose(CHEST, q).inverse()
    return {s: chest @ body.frame_pose(f"{s}_hand_grasp", q) for s in sides}


def _taking(body, clip, placed_pose, hands, carry, on_target, marks, keys: "_Keys"):
    """Offsets of a clip that takes an object and carries it off in the carry posture:
    `keys` up to the grasp, then the way into the carry posture."""
    approach_time, _, hold_end = marks
    sides = tuple(hands)
    grasped = placed_pose(clip.sample(hold_end)) + on_target
    end_pose = placed_pose(clip.sample(clip.duration))
    carried = carry.over(end_pose)
    start, end = _in_chest(body, grasped, sides), _in_chest(body, carried, sides)
    times = tuple(np.linspace(hold_end, clip.duration, CARRY_SAMPLES))
    zero = np.zeros_like(on_target)
    way = _way(
        body, clip, placed_pose, times, start, end, on_target, zero, arm_indices(body, sides)
    )
    way[0], way[-1] = on_target, carried - end_pose
    first = len(keys.times)
    for time, offset in zip(times, way, strict=True):
        keys.add(time, offset)
    keys.paths.append((first, len(keys.times) - 1))
    return keys.motion(sides, (approach_time, clip.duration))


def _putting_down(
    body, clip, placed_pose, hands, carry, near_offset, on_target, marks, opened, edge
):
    """Offsets of a clip that starts in the carry posture and puts the object down: the
    hands open to `opened` and, over a surface, leave it over its `edge`."""
    approach_time, event, hold_end = marks
    sides = tuple(hands)
    start_pose = placed_pose(clip.sample(0.0))
    held = carry.over(start_pose)
    above = placed_pose(clip.sample(approach_time)) + near_offset
    start, end = _in_chest(body, held, sides), _in_chest(body, above, sides)
    times = tuple(np.linspace(0.0, approach_time, CARRY_SAMPLES))
    zero = np.zeros_like(on_target)
    arms = arm_indices(body, sides)
    way = _way(body, clip, placed_pose, times, start, end, zero, near_offset, arms)
    way[0], way[-1] = held - start_pose, near_offset
    keys = _Keys(body, clip, placed_pose)
    for time, offset in zip(times, way, strict=True):
        keys.add(time, offset)
    keys.paths.append((0, CARRY_SAMPLES - 1))
    keys.add(event, on_target)
    keys.add(hold_end, on_target)
    release_end = hold_end + 0.3 * (clip.duration - hold_end)
    keys.add(
        release_end, _offset(body, placed_pose, clip, release_end, on_target, opened, on_target)
    )
    if edge is not None:
        keys.passage(release_end + LEAVE_AT[1] * (clip.duration - release_end), edge)
    keys.add(clip.duration, zero)
    return keys.motion(sides, (0.0, release_end))
