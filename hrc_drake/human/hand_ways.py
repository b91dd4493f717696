"""The ways of the hands in and out of an aimed clip: to a point above the target and a
little wider apart before they close on it (`approached`), up beside the body and over the
edge of the surface the target is on (`over_the_edge`), and off a surface when a reach is
cut short (`withdrawal`); with an object in the hands: hrc_drake.human.held_ways. Each
writes its postures as keys of one clip (`Keys`): an offset at a clip time, or the hands
put on waypoints by IK there (hrc_drake.human.aiming); hrc_drake.human.targeting lays them
out round the clip's event.
"""

from functools import lru_cache

import numpy as np
from shapely.geometry import LineString

from hrc_drake.human.aiming import (
    HAND_TOLERANCE,
    WAYPOINT_TOLERANCE,
    AimedMotion,
    Unreachable,
    arms_toward,
    hands_on,
)
from hrc_drake.human.body import HumanBody
from hrc_drake.human.clip import Clip
from hrc_drake.human.furniture import Furniture
from hrc_drake.human.grasp import (
    arm_indices,
    facing,
    outward,
)
from hrc_drake.human.hand_shape import hand_below, hand_extent, hand_half_breadth
from hrc_drake.human.keyed_clips import minimum_jerk
from hrc_drake.human.skeleton import SIDES

APPROACH = (0.06, 0.06)
"""m: where the hands come to before they close on the target: this far outwards (palms
on an object's faces; a reaching hand: back towards the body) and this far above it."""
LEAVE_AT = 0.3
"""Fraction of the time from letting go to the clip's end at which hands leaving a surface
are back above their target; from there they go over the surface's edge, down below its
top outside the edge and back to the body's sides, each stretch taking its share of the
rest of the clip as the hands go in it (`Keys.off_the_edge`)."""
LOWERED = 0.25
"""m: how far hands leaving a surface go straight down outside its edge (as far as the arms
alone take them): below its top, before the clip's own arms take them back to the body's
sides (on the way straight there, a hand over the edge swung forward and down into a box
standing at it: coexistence seed 9, 2 cm)."""
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


def approached(
    hands: dict,
    heading: float,
    reaching: bool,
    opening: bool = True,
    above=None,
    room=None,
    headroom: float = np.inf,
) -> dict:
    """The hands' targets moved to where they come before closing on them: above, and
    (`opening`) outwards from an object's faces (a reaching hand: back towards the body);
    hands that hold what they put down stay on it. `above` (side: height) raises a hand
    further, so far that its grasp frame is at least that high; `room` (side: m) is as far
    as a palm can open outwards (a neighbouring object); `headroom` (m) is as far as what
    the hands hold may rise (CLEARANCE / 2 under the board above)."""
    out, up = APPROACH
    up = min(up, max(headroom - CLEARANCE / 2, 0.0))
    back = -np.array([np.cos(heading), np.sin(heading), 0.0])
    moved = {}
    for side, (position, R) in hands.items():
        away = back if reaching or R is None else outward(side, R)
        wide = min(out, (room or {}).get(side, out))
        point = np.asarray(position) + opening * wide * away + [0.0, 0.0, up]
        point[2] = max(point[2], (above or {}).get(side, -np.inf))
        moved[side] = (point, R)
    return moved


def clearing(body: HumanBody, furniture: Furniture, hands: dict, lowest, base) -> dict:
    """Per side, the height a hand's grasp frame keeps above what it is aimed at and its
    neighbours: its lowest edge CLEARANCE above `lowest` (side: height its lowest point
    passes over, e.g. the top of what it takes; default: its target's height less its
    reach below the frame), and above the surface the target is on and the walls round it
    on the way from the body (`rim`; `base`: the pelvis' floor point)."""
    heights = {}
    for side, (position, R) in hands.items():
        reach = hand_below(body, R, side)
        over = lowest.get(side, position[2] - reach) if lowest else position[2] - reach
        support = furniture.support(position)
        if support is not None:
            over = max(over, rim(body, furniture, support, position, base))
        heights[side] = over + reach + CLEARANCE
    return heights


def rim(body: HumanBody, furniture: Furniture, support, position, base) -> float:
    """The height a hand comes over on its way from the body (`base`, the pelvis' floor
    point) to `position` on `support`: the top of the walls that rise round that surface
    between the two (a bin's near wall round its floor), else the surface's own top. Lifted
    only over the bin's floor, the forearm on its way to a part 0.1 m inside the near wall
    of a bin on a table went 9.9 cm into the wall."""
    way = LineString([tuple(position[:2]), tuple(base)]).buffer(hand_half_breadth(body))
    walls = furniture.walls_round(support).highest_between(way, support.high, np.inf)
    return support.high if walls is None else max(walls, support.high)


def over_the_edge(body, furniture: Furniture, hands: dict, near: dict, base, heading, held=False):
    """Where the hands rise to before they move over the surface their targets are on, and
    leave it by: above it and the walls round it (`rim`) with the hand's whole length,
    whichever way it points, just outside its edge (the hand's half breadth and a margin)
    back towards the body from their approach points; beside the trunk where that is in
    front of it. None when no target is over a surface of the cell. Hands that `held` one
    object leave it together."""
    forward = np.array([np.cos(heading), np.sin(heading), 0.0])
    left = np.array([-forward[1], forward[0], 0.0])
    R = facing(heading, "sides_fingers_down")
    edges = {}
    for side, (position, _) in near.items():
        support = furniture.support(hands[side][0])
        inset = hand_extent(body, R, forward, side) + EDGE_MARGIN
        if support is not None:
            edge = furniture.behind_edge(furniture.pile(support), position, -forward, inset)
            if edge is not None:
                edges[side] = (edge, support)
    if not edges:
        return None
    if held:
        edges = _left_together(edges, near, base, forward)
    clear = dict(near)
    for side, (edge, support) in edges.items():
        ahead, aside = (edge - base) @ forward[:2], (edge - base) @ left[:2]
        if ahead < TRUNK_FRONT:
            sign = 1.0 if side == "left" else -1.0
            aside = sign * max(sign * aside, TRUNK_SIDE)
        top = rim(body, furniture, support, near[side][0], base)
        height = max(near[side][0][2], top + hand_below(body, R, side) + CLEARANCE)
        point = np.array([*(base + ahead * forward[:2] + aside * left[:2]), height])
        clear[side] = (point, None)
    return clear


def _left_together(edges: dict, near: dict, base, forward) -> dict:
    """`edges` (side: edge point, surface) with each hand that has none (its palm on a face
    beyond the surface's side) drawn back as far as the others', where it is across: left
    beside the part it had put down, it went into it (coexistence seed 2 at 106.7 s, 1.3 cm)."""
    ahead = min((edge - base) @ forward[:2] for edge, _ in edges.values())
    support = next(iter(edges.values()))[1]
    together = dict(edges)
    for side, (position, _) in near.items():
        if side not in edges:
            back = max((position[:2] - base) @ forward[:2] - ahead, 0.0)
            together[side] = (position[:2] - back * forward[:2], support)
    return together


def below_the_top(body: HumanBody, furniture: Furniture, hands: dict) -> bool:
    """Whether hands leaving the surfaces under `hands` (side: target) go down outside
    their edge (LOWERED) before they swing back to the body's sides: only where a surface's
    top stands above the fingertips of hands hanging at the sides. Over a lower top they
    swing back above it anyway; lowered there, they bent a person who had put a tote into a
    shelf's middle compartment so low that the face went into the board above, and the
    body rose back in the last tenth of a second."""
    tops = [furniture.support(target[0]) for target in hands.values()]
    highest = max((top.high for top in tops if top is not None), default=-np.inf)
    return highest > min(_hanging_fingertips(body, side) for side in hands)


@lru_cache(maxsize=16)
def _hanging_fingertips(body: HumanBody, side: str) -> float:
    """How high the `side` hand's lowest point is when the person stands, arms hanging."""
    X = body.frame_pose(f"{side}_hand_grasp", body.standing_pose())
    return float(X.translation()[2]) - hand_below(body, X.rotation(), side)


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
    base = q[[body.index("base_x"), body.index("base_y")]]
    above = clearing(body, furniture, hands, None, base)
    up = approached(hands, heading, False, opening=False, above=above)
    edge = over_the_edge(body, furniture, hands, up, base, heading)
    keys.reach(LEAVE_AT * WITHDRAWAL, up)
    if edge is not None:
        lowered = below_the_top(body, furniture, hands)
        keys.off_the_edge(edge, WITHDRAWAL, lowered)
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
        for t, s in self._eased_to(time):
            key = start + s * (offset - start)
            key[arms] = a + s * (b - a) - self._pose(t, 0.0)[arms]
            self.add(t, key)
        self.paths.append((first, len(self.times) - 1))

    def straight(self, time: float, start: dict, end: dict, fallback: np.ndarray, landed=None):
        """Keys from the last one to `time` that take the hands straight from `start` to
        `end` (side: position, orientation), eased, as one movement; where they cannot get
        to the end, `fallback` there; `landed`: the offset at the end, its hands already put
        on it. Letting go of a box, the clip's own arms and trunk swung a palm back into it
        on its way out (coexistence seed 9 at 66.2 s, 1.2 cm)."""
        first = len(self.times) - 1
        for t, s in self._eased_to(time):
            targets = {side: (p + s * (end[side][0] - p), R) for side, (p, R) in start.items()}
            offset = landed if t == time else None
            if offset is None:
                offset = self._solved(t, targets, self.offsets[-1], HAND_TOLERANCE)
            if offset is not None:
                self.add(t, offset)
            elif t == time:
                self.add(t, fallback)
        self.paths.append((first, len(self.times) - 1))

    def straight_to_the_end(self, end: float, sides) -> None:
        """Keys to `end` that take the `sides` hands straight to where the clip's end pose
        has them, by the arms, the trunk eased to the clip's: eased by the clip's arms, hands
        leaving a put-down swung forward into the part (coexistence seed 2, 2.2 cm); by the
        whole body, the trunk bent and the head went at 1.7 m/s."""
        last, final = self._pose(self.times[-1], self.offsets[-1]), self._pose(end, 0.0)
        start, goal = (
            {s: self.body.frame_pose(f"{s}_hand_grasp", q).translation() for s in sides}
            for q in (last, final)
        )
        first, offset = len(self.times) - 1, self.offsets[-1]
        for t, share in self._eased_to(end):
            targets = {s: (p + share * (goal[s] - p), None) for s, p in start.items()}
            key = (1.0 - share) * offset
            if t < end:
                key = self._arms_toward(t, targets, key)
            self.add(t, key)
        self.paths.append((first, len(self.times) - 1))

    def _eased_to(self, time: float):
        """PASSAGE_KEYS (time, fraction of the way) from the last key to `time`, the fractions
        easing in and out (minimum jerk) over evenly spaced times."""
        times = np.linspace(self.times[-1], time, PASSAGE_KEYS + 1)[1:]
        return [(float(t), minimum_jerk(k / PASSAGE_KEYS)) for k, t in enumerate(times, start=1)]

    def off_the_edge(self, edge: dict, end: float, lowered: bool) -> None:
        """Keys that take the hands from the last key over a surface's `edge` (its
        waypoints) and then, if `lowered` (`below_the_top`), straight down outside it as far
        as the arms alone take them, leaving the rest up to `end` for the way back to the
        clip's end pose: each stretch takes its share of the time as the hands and the head
        go in it (laid out once at even times to measure that). At fixed fractions (0.6 and
        0.8 of the rest), the hands went down 0.25 m and back to the sides in 0.17 s each,
        the trunk bent to lower them, and the head moved at 2.6-4.4 m/s."""
        down = None
        if lowered:
            down = {side: (p - [0.0, 0.0, LOWERED], None) for side, (p, _) in edge.items()}
        start = self.times[-1]
        stretches = 3 if lowered else 2
        even = [start + k * (end - start) / stretches for k in range(1, stretches)]
        trial = Keys(self.body, self.clip, self.placed_pose)
        trial.times, trial.offsets = list(self.times), list(self.offsets)
        trial._leave(edge, down, even)
        poses = [trial._keyed_pose(t) for t in [start, *even]] + [self._pose(end, 0.0)]
        self._leave(edge, down, self._shared(start, end, poses, tuple(edge)))

    def _leave(self, edge: dict, down: dict | None, times) -> None:
        """The keys over the edge and down at `times`, the hands turned down as they are
        over the edge (let turn, the fingers of a hand lowered outside a shelf board's edge
        pointed into it, and the arm went 4.2 cm into the shelf: tests/corpus machine_cell)."""
        self.passage(times[0], edge)
        if down is not None:
            over = self._pose(self.times[-1], self.offsets[-1])
            turned = {
                side: (p, self.body.frame_pose(f"{side}_hand_grasp", over).rotation())
                for side, (p, _) in down.items()
            }
            self.add(times[1], self._arms_toward(times[1], turned))

    def _keyed_pose(self, time: float) -> np.ndarray:
        """The pose at `time` with the offset of the last key at or before it."""
        k = int(np.searchsorted(self.times, time, side="right")) - 1
        return self._pose(time, self.offsets[k])

    def _shared(self, start: float, end: float, poses, sides) -> list[float]:
        """The times between `start` and `end` at which the body is in `poses` (but the first
        and the last), shared as far as the hands or the head go from one to the next."""
        frames = [f"{side}_hand_grasp" for side in sides] + ["head"]
        points = [[self.body.frame_pose(f, q).translation() for f in frames] for q in poses]
        lengths = np.linalg.norm(np.diff(points, axis=0), axis=2).max(axis=1)
        shares = np.cumsum(lengths)[:-1] / max(float(lengths.sum()), 1e-9)
        return [float(start + share * (end - start)) for share in shares]

    def _arms_toward(self, time: float, targets: dict, offset=None) -> np.ndarray:
        """The offset at `time` with the arms moved towards `targets` from where the last key
        has them, the trunk as the last key bends it (or as `offset` does)."""
        placed = self._pose(time, 0.0)
        kept = self._arms_kept(time, self.offsets[-1] if offset is None else offset)
        return arms_toward(self.body, kept, targets) - placed

    def _arms_kept(self, time: float, offset: np.ndarray) -> np.ndarray:
        """The pose at `time` with `offset`, the arms where the last key has them."""
        kept = self._pose(time, offset)
        kept[self.arms] = self._pose(self.times[-1], self.offsets[-1])[self.arms]
        return kept

    def _pose(self, time: float, offset) -> np.ndarray:
        return self.placed_pose(self.clip.sample(time)) + offset

    def _solved(self, time: float, targets: dict, start: np.ndarray, tolerance=WAYPOINT_TOLERANCE):
        """The offset at `time` with the hands on `targets` (within `tolerance`): the arms
        start from where the last key has them, or else the whole body from the clip's pose
        (IK finds some postures only from one of them); None when neither reaches."""
        placed = self._pose(time, 0.0)
        for q in (self._arms_kept(time, start), placed):
            try:
                return hands_on(self.body, q, targets, True, tolerance) - placed
            except Unreachable:
                continue
        return None

    def motion(self, hands: tuple[str, ...], held: tuple[float, float]) -> AimedMotion:
        return AimedMotion(tuple(self.times), tuple(self.offsets), tuple(self.paths), hands, held)
