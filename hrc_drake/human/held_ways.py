"""The ways of an object held in the hands: from taking it into the carry posture
(`carried_off`) and from the carry posture to putting it down (`put_down`). The palms stay
on its faces all the way, in the chest's frame so that the arms follow the trunk, and the
object rises over whatever stands beside its way before it crosses (`crossing_height`).
Each way is keys of the clip (hrc_drake.human.hand_ways.Keys) that
hrc_drake.human.targeting lays out round the clip's event.

Longer than 400 lines: the way's route (`_Route`, its phases) and the room it has (the
crossing level under and over what stands about it) are both read by the pick's and the
put-down's ways and by nothing else; split off, each would import the other's privates.
"""

from dataclasses import dataclass
from functools import cached_property
from itertools import pairwise, product

import numpy as np
from pydrake.math import RigidTransform, RotationMatrix
from shapely.geometry import MultiPoint

from hrc_drake.human.aiming import Unreachable, offset_to
from hrc_drake.human.body import HumanBody
from hrc_drake.human.furniture import Furniture
from hrc_drake.human.grasp import (
    PALM_GAP,
    CarryArms,
    arm_indices,
    facing,
    grip_style,
    hand_tasks,
    object_center_in_holder,
    outward,
    spread,
)
from hrc_drake.human.hand_shape import hand_below, hand_extent
from hrc_drake.human.hand_ways import CLEARANCE, LEAVE_AT, Keys, below_the_top
from hrc_drake.human.keyed_clips import minimum_jerk
from hrc_drake.human.legs import legs_of

CARRY_SAMPLES = 8
"""Points of the way between the grasp and the carry posture at which the palms are put on
the object's faces by IK, at first; between them the joints run straight."""
MOST_SAMPLES = 29
"""Where the palms' spacing strays by more than HOLDING_SLIP between two points, the way is
solved again at twice as many, up to this many (rising from a squat with a carton, the
palms came 3.2 cm off it between two of 8 points)."""
HOLDING_SLIP = 0.02
"""m: palms whose spacing strays further than this from the held object's are off its faces
by more than about 1 cm each, past their 8 mm gap (the audit allows 2 cm)."""
WAY_STRAY = 0.01
"""m: where the palms' midpoint, halfway between two points of a way, strays further than
this from the way, the way is solved at more points (the audit allows a held object 1 cm
into anything)."""
LOSING_HOLD = 2 * HOLDING_SLIP
"""m: palms whose spacing strays further than this on the straight way are each off the
object by more than the audit allows: the person cannot carry it off from where they stand
(a 95th-percentile man moved 0.7 m along a pallet for room to turn lifted a carton with his
palms 12 cm off it)."""
OUT_SHARE = 0.4
"""Share of the way into the carry posture spent drawing an object out from under a board."""
OUT_STEP, OUT_MOST = 0.02, 0.5
"""m: an object is drawn out from under a board in these steps, this far at most."""
WAY_BEND = 0.05
"""m: how far the held object's way may pass beside the straight one between its ends (it
runs in the chest's frame, which turns and leans with the trunk: coexistence seed 9's
box passed 3 cm outside it, over a stack)."""
CHEST = "chest"
"""The body the hands' way with a held object is laid out in."""
SPINE = ("lumbar_flexion", "lumbar_bending", "thorax_flexion", "thorax_rotation")
"""The joints that also move the holding hands where the arms alone leave them short of the
way (rising from a stoop, the clip draws the shoulders back faster than straight arms can
keep a carton over the crate it was lifted off: 2.7 cm low); the pelvis and legs stay as
the clip has them."""
REACH_TOLERANCE = 0.005
"""m: a holding hand further than this from its target on the way is short of it."""
FIRST_SHARE, MOVE_SHARE = 0.25, 0.1
"""Shares of a way within a crossing level at least given to moving to the level and to
moving from it to the end."""
LIFT, LIFTING = 0.01, 0.15
"""m, share of the way: an object held on its way keeps this far above where it was taken
(or is put) once it is this share of the way from there."""
HOLDING_ORIENTATION = 1.0
"""Weight of the hands' orientation while they hold an object on its way: a palm that
tilts pokes its fingers into the object."""


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
    across = spread(turned)
    return {side: (middle + across[side] * width / 2, R) for side, R in turned.items()}


def _slerp(a: RotationMatrix, b: RotationMatrix, s: float) -> RotationMatrix:
    return RotationMatrix(a.ToQuaternion().slerp(s, b.ToQuaternion()))


def _way(body, clip, placed_pose, span, *way, level=None, taken=False):
    """`way` = (start, end, trunk_from, trunk_to, arms). Times evenly spaced over `span` (the
    first and last), CARRY_SAMPLES of them or more (MOST_SAMPLES), and the offsets there on
    the way of the holding hands from `start` to
    `end` (grasp frames in the chest's frame at the first and last time): the way runs in
    the chest's frame, which rises and turns with the trunk, so the arms can follow it; the
    arms are solved to hold the object, the rest of the body eases from the offset
    `trunk_from` to `trunk_to`, the feet kept where the clip has them (a squat eased out
    linearly in the joints sank the feet 3.6 cm into the floor, rising with a carton from a
    shelf's bottom board). With `level` (world heights, low and high: `crossing_level`),
    the palms' midpoint rises or lowers to within them first, crosses there and moves to
    the end last (over what stands on the way, under a board over its end), if the arms
    can hold the object there: else it goes the straight way (lifted too high, a carton in
    both hands was 5.3 cm off a palm: collaboration seed 15). Where the palms
    cannot keep their orientation and their hold, they keep only their normals and turn
    about them (`_held_way`'s `turning`). Unreachable where the arms cannot hold it even on
    the straight way. `taken`: the way starts where the hands took the object (it is not
    let below there while it rises: `_Route._lowest`)."""
    start, end, trunk_from, trunk_to, arms = way
    count = CARRY_SAMPLES
    while True:
        times = tuple(np.linspace(*span, count))
        straight = []
        for crossing, turning in product(dict.fromkeys((level, None)), (False, True)):
            route = _Route(
                body, clip, placed_pose, times, start, end, trunk_from, trunk_to, crossing, taken
            )
            offsets, slipped, missed = _held_way(route, arms, turning)
            if slipped <= HOLDING_SLIP and missed <= WAY_STRAY:
                break
            if crossing is None:
                straight.append((slipped, missed, route, offsets))
        else:
            slipped, _, route, offsets = min(straight, key=lambda held: held[:2])
        if slipped > LOSING_HOLD:
            raise Unreachable(
                f"the hands cannot keep hold of the object on its way from where the person "
                f"stands (their spacing strays {slipped * 100:.0f} cm from its width)"
            )
        if count >= MOST_SAMPLES or not _strays_between(route, offsets):
            return times, offsets
        count = 2 * count - 1


@dataclass(frozen=True)
class _Phases:
    """The parts of a way within a crossing level: the palms move to the level while it
    holds to its start (up to `across`), cross (up to `lowering`) and move to its end."""

    across: float
    lowering: float

    def crossing(self, s: float) -> float:
        """How far across the way the hands are at s."""
        return min(max((s - self.across) / (self.lowering - self.across), 0.0), 1.0)

    def rising(self, s: float) -> float:
        """How much the way holds to its start at s: all until it crosses, none from the
        crossing's middle."""
        return 1.0 - minimum_jerk(2.0 * self.crossing(s))

    def lowering_weight(self, s: float) -> float:
        """How much the way holds to its end at s: none to the crossing's middle, all once
        it has crossed."""
        return 1.0 - minimum_jerk(2.0 - 2.0 * self.crossing(s))

    def plateau(self, s: float) -> float:
        """How far to the level the hands are at s."""
        to = minimum_jerk(min(s / self.across, 1.0))
        return to * minimum_jerk(min((1.0 - s) / (1.0 - self.lowering), 1.0))


@dataclass(frozen=True, eq=False)
class _Route:
    """The way of the holding hands at `times` of `clip`: the body under the arms at each
    point and the hands' world targets there (`_way`)."""

    body: HumanBody
    clip: object
    placed_pose: object
    times: tuple
    start: dict
    end: dict
    trunk_from: np.ndarray
    trunk_to: np.ndarray
    level: tuple[float, float] | None
    taken: bool = False
    """The way starts where the hands took the object, off what it lay on."""

    def body_at(self, t: float, s: float) -> np.ndarray:
        """The pose under the arms a fraction s of the way, at clip time t."""
        placed = self.placed_pose(self.clip.sample(t))
        eased = placed + self.trunk_from + s * (self.trunk_to - self.trunk_from)
        return legs_of(self.body).planted(eased, placed)

    def targets(self, q: np.ndarray, s: float) -> dict:
        """The hands' world targets a fraction s of the way, the body under them at q: laid
        out in the chest's frame, within `level` in the middle, never lower than the way's
        lower end and, near an end it rises from or lowers onto, held over that end's place
        in the world (the chest swings as the trunk rises: a crate lifted off a pallet from
        between two others swung 8 cm into one, collaboration seed 0; a carton lifted off a
        crate dipped 3.2 cm into it, seed 15). The palms keep their orientation in the
        chest (held in the world too, the arms left the carton 1 cm lower between points)."""
        targets = self._in_world(q, _between(self.start, self.end, self._progress(s)))
        middle = _midpoint(targets)
        shift = np.zeros(3)
        if self.level is not None:
            low, high = self.level
            shift[2] = self.phases.plateau(s) * (min(max(middle[2], low), high) - middle[2])
        for end, weight in self._held_to(s):
            shift[:2] += weight * (_midpoint(end)[:2] - middle[:2])
        shift[:2] += self._back_beside_the_straight(middle[:2] + shift[:2])
        shift[2] = max(shift[2], self._lowest(s) - middle[2])
        return {side: (p + shift, R) for side, (p, R) in targets.items()}

    def _held_to(self, s: float) -> list:
        """The ends the way keeps to at s, each with how much: over something, its start
        while it rises and its end while it lowers; else its lower end until LIFTING of the
        way from it."""
        start, end = self.ends
        if self.level is not None:
            return [(start, self.phases.rising(s)), (end, self.phases.lowering_weight(s))]
        low, off = (start, s) if self._low_first else (end, 1.0 - s)
        return [(low, 1.0 - minimum_jerk(off / LIFTING))]

    def _back_beside_the_straight(self, point: np.ndarray) -> np.ndarray:
        """How far (on the floor) the palms' midpoint at `point` must move to pass no
        further than WAY_BEND beside the straight way between the ends, which is all that
        `crossing_height` looks at (in the chest's frame, rising from a squat with a carton
        drawn out from under a shelf's 0.6 m board, the way swung 28 cm ahead of where it
        was drawn out to, back into the shelf, and the carton went 5 cm into the board)."""
        a, b = (_midpoint(end)[:2] for end in self.ends)
        along = b - a
        u = np.clip(np.dot(point - a, along) / max(np.dot(along, along), 1e-12), 0.0, 1.0)
        aside = point - (a + u * along)
        distance = float(np.linalg.norm(aside))
        return aside * (WAY_BEND / distance - 1.0) if distance > WAY_BEND else np.zeros(2)

    def _lowest(self, s: float) -> float:
        """How low the palms' midpoint may be a fraction s of the way: LIFT above its lower
        end once it is off it, and, on the way of an object `taken` off something, not below
        where the hands took it while the way holds to that place (a carton taken off a
        shelf's board above the carry posture sank 2.1 cm into the board as the trunk rose,
        before the way rose over its edge: a packing cell of our own, #26)."""
        a, b = (_midpoint(end)[2] for end in self.ends)
        off = s if self._low_first else 1.0 - s
        lowest = min(a, b) + LIFT * minimum_jerk(off / LIFTING)
        if not self.taken or self.level is None:
            return lowest
        return lowest + self.phases.rising(s) * max(a - lowest, 0.0)

    @cached_property
    def _low_first(self) -> bool:
        a, b = (_midpoint(end)[2] for end in self.ends)
        return a <= b

    def _progress(self, s: float) -> float:
        return minimum_jerk(s if self.level is None else self.phases.crossing(s))

    def _in_world(self, q: np.ndarray, local: dict) -> dict:
        chest = self.body.frame_pose(CHEST, q)
        return {side: (chest @ p, chest.rotation() @ R) for side, (p, R) in local.items()}

    @cached_property
    def ends(self) -> tuple[dict, dict]:
        """The hands' world targets at the way's two ends, as laid out in the chest."""
        return tuple(
            self._in_world(self.body_at(t, s), _between(self.start, self.end, s))
            for t, s in ((self.times[0], 0.0), (self.times[-1], 1.0))
        )

    @cached_property
    def phases(self) -> _Phases:
        """The parts of the way within its level: moving to it takes its share of how far
        the palms go, or a quarter of the way if that is more (a tenth: material lifted off
        a shelf's board reached its level too soon and went 3.4 cm into the board,
        coexistence seeds 4, 8 and 9); crossing and moving to the end share the rest as the
        palms go in them, the last at least MOVE_SHARE (in fixed quarters a tote carried
        0.47 m into a shelf crossed at up to 3 m/s and a forearm went 2.9 cm into the board
        above)."""
        start, end = (_midpoint(e) for e in self.ends)
        low, high = self.level
        into, out_of = (np.array([*p[:2], min(max(p[2], low), high)]) for p in (start, end))
        lengths = np.array(
            [abs(into[2] - start[2]), np.linalg.norm(out_of - into), abs(end[2] - out_of[2])]
        )
        shares = lengths / max(lengths.sum(), 1e-9)
        across = max(float(shares[0]), FIRST_SHARE)
        crossing = (1.0 - across) * float(shares[1] / max(shares[1] + shares[2], 1e-9))
        return _Phases(across, min(across + crossing, 1.0 - MOVE_SHARE))

    def fractions(self) -> np.ndarray:
        return np.linspace(0.0, 1.0, len(self.times))


def _strays_between(route: _Route, offsets) -> bool:
    """Whether the holding palms stray between two points of the way, the joints halfway
    (as they run straight): their spacing from its mean at the two by more than
    HOLDING_SLIP, or their midpoint from the way's there by more than WAY_STRAY (the keys
    on a way rising from a pallet were on it, the carton between them 2.9 cm below it)."""
    body, sides = route.body, tuple(route.start)
    for (a, b), (p, q), (u, v) in zip(
        pairwise(route.times), pairwise(offsets), pairwise(route.fractions()), strict=True
    ):
        t, s = (a + b) / 2, (u + v) / 2
        played = route.placed_pose(route.clip.sample(t)) + (p + q) / 2
        hands = _hands_at(body, sides, played)
        aimed = _midpoint(route.targets(route.body_at(t, s), s))
        if np.linalg.norm(np.mean(hands, axis=0) - aimed) > WAY_STRAY:
            return True
        spacings = [
            _spacing(_hands_at(body, sides, route.placed_pose(route.clip.sample(x)) + o))
            for x, o in ((a, p), (b, q))
        ]
        if abs(_spacing(hands) - np.mean(spacings)) > HOLDING_SLIP:
            return True
    return False


def _midpoint(targets: dict) -> np.ndarray:
    return np.mean([p for p, _ in targets.values()], axis=0)


def _hands_at(body, sides, q: np.ndarray) -> list[np.ndarray]:
    return [body.frame_pose(f"{side}_hand_grasp", q).translation() for side in sides]


def _spacing(hands: list[np.ndarray]) -> float:
    return float(np.linalg.norm(hands[0] - hands[1])) if len(hands) == 2 else 0.0


def _held_way(route: _Route, arms: np.ndarray, turning: bool):
    """The offsets at the route's times, how far the palms' spacing strays from the
    object's on it and how far their midpoint misses the way's (the arms cannot hold the
    palms' orientation up there: over a stack in a shelf the keys were 13 cm under the way,
    then one jumped 25 cm onto it). With `turning` the palms keep only their normals, free
    to turn about them (the fingers down a box's sides at head height; one palm's object,
    held level at the palm, does not tilt: a 95th-percentile man's hand raising a blank to
    a flow rack's 1.4 m board, held as it took it, missed the way over the board's edge by
    4.8 cm, and the straight way cut the edge, the blank 3.0 cm in)."""
    offsets, solved, slipped, missed = [], None, 0.0, 0.0
    for t, s in zip(route.times, route.fractions(), strict=True):
        q = route.body_at(t, s)
        if solved is not None:  # each point starts from the last: the arms follow the way
            q[arms] = solved[arms]
        targets = route.targets(q, s)
        tasks = hand_tasks(targets, HOLDING_ORIENTATION, turn_in_palm=turning)
        solved = route.body.solve(q, tasks, arms, iterations=60, posture_weight=1e-4)
        if route.body.task_error(solved, tasks) > REACH_TOLERANCE:
            spine = np.concatenate([arms, _spine(route.body)])
            solved = route.body.solve(q, tasks, spine, iterations=60, posture_weight=1e-4)
        offsets.append(solved - route.placed_pose(route.clip.sample(t)))
        hands = _hands_at(route.body, tuple(targets), solved)
        aimed = [p for p, _ in targets.values()]
        slipped = max(slipped, abs(_spacing(hands) - _spacing(aimed)))
        missed = max(missed, float(np.linalg.norm(np.mean(hands, axis=0) - _midpoint(targets))))
    return offsets, slipped, missed


def _spine(body) -> np.ndarray:
    return np.array([body.index(name) for name in SPINE])


def crossing_height(body, furniture: Furniture, carry: CarryArms, a, b, heading: float):
    """The height the holding palms' midpoint keeps while it carries the object from `a` to
    `b` (the midpoint's world positions at the two ends): the object's bottom and the
    hands' lowest edges CLEARANCE above whatever stands under its way higher than where the
    object's bottom is at the lower end and lower than its top at the higher one (a stack
    beside where a box is put down, the edge of a board it is taken off), but not what
    stands over the lower end (the board above a shelf's compartment a box is put into:
    carried in at chest height, a tote's top was above that board's underside, the way rose
    over the board and came down through it, the arms 10.8 cm in), nor what is over either
    end above the object's centre there (a tray taken off a rack's board and carried off
    0.35 m from the rack: its far edge under the board above, 1.5 cm inside the rack, the
    way rose over that board and came down through it, 1.6 cm in). None: nothing does."""
    around, lowest, highest = _held_outline(body, carry, heading)
    corners = [np.asarray(end[:2]) + c for end in (a, b) for c in around]
    bottom = min(a[2], b[2]) - lowest
    area = MultiPoint(corners).convex_hull.buffer(WAY_BEND)
    low_end = a if a[2] <= b[2] else b
    beside = furniture.not_over(_outline_at(low_end, around), low_end[2] + highest)
    centre_below = object_center_in_holder(carry.hold)[2]
    for end in (a, b):
        beside = beside.not_above(_outline_at(end, around), end[2] + centre_below)
    top = beside.highest_between(area, bottom + CLEARANCE / 2, max(a[2], b[2]) + highest)
    return None if top is None else top + CLEARANCE + lowest


def _outline_at(middle, around):
    """The held object's outline with the hands, the palms' midpoint at `middle`."""
    return MultiPoint([np.asarray(middle[:2]) + c for c in around]).convex_hull


def crossing_level(body, furniture: Furniture, carry: CarryArms, a, b, heading: float):
    """The heights (low, high) between which the holding palms' midpoint crosses from `a`
    to `b`: over what stands beside its way (`crossing_height`) and CLEARANCE / 2 under
    what stands over its lower end (`_under`: a tote carried at the height of the board
    above the shelf compartment it is put into went through the board's edge; it comes down
    first, then in). None: neither is in the way."""
    over = crossing_height(body, furniture, carry, a, b, heading)
    under = _under(body, furniture, carry, a, b, heading)
    if over is None and under is None:
        return None
    return (-np.inf if over is None else over, np.inf if under is None else under)


def _under(body, furniture: Furniture, carry: CarryArms, a, b, heading: float):
    """The highest the palms' midpoint may cross at under what stands over the way's lower
    end (None: nothing does), even where both ends are below that: the way in the chest's
    frame bulges up as the trunk leans in (4 cm putting a tote into a shelf from the carry
    posture: checked against a straight line, a tote put on a shelf's middle board still
    went 3.3 cm into the edge of the board above; a KLT carried 6.5 cm under a rack's
    1.2 m board and put on its 0.4 m board went 1.4 cm into that board's edge, #26)."""
    low_end = min((a, b), key=lambda end: end[2])
    ceiling = _over_the_end(body, furniture, carry, low_end, heading)
    if not ceiling.pieces:
        return None
    _, _, highest = _held_outline(body, carry, heading)
    return ceiling.lowest() - highest - CLEARANCE / 2


def headroom(body, furniture: Furniture, carry: CarryArms, middle, heading: float) -> float:
    """How far the held object, the palms' midpoint at `middle`, can rise before it or the
    hands meet what stands over it (the board above a shelf's compartment; inf: nothing)."""
    lowest = _over_the_end(body, furniture, carry, middle, heading).lowest()
    _, _, highest = _held_outline(body, carry, heading)
    return np.inf if lowest is None else lowest - (middle[2] + highest)


def _over_the_end(body, furniture: Furniture, carry: CarryArms, middle, heading: float):
    """What stands over the held object, the palms' midpoint at `middle`."""
    around, _, highest = _held_outline(body, carry, heading)
    return furniture.above(_outline_at(middle, around), middle[2] + highest)


def _held_outline(body, carry: CarryArms, heading: float):
    """The held object with the hands at its sides, round the palms' midpoint: the corners
    of its outline on the floor (offsets), and how far it reaches below and above."""
    depth, width, height = carry.size
    ahead, aside, below = object_center_in_holder(carry.hold)
    style = grip_style(carry.hold.hands, height)
    R = {side: facing(heading, style, side) for side in carry.hands}
    hand = max(hand_extent(body, R[s], outward(s, R[s]), s) for s in carry.hands)
    lowest = max(-below + height / 2, *(hand_below(body, R[s], s) for s in carry.hands))
    up = (0.0, 0.0, 1.0)
    highest = max(below + height / 2, *(hand_extent(body, R[s], up, s) for s in carry.hands))
    forward = np.array([np.cos(heading), np.sin(heading)])
    left = np.array([-forward[1], forward[0]])
    corners = [
        (ahead + u * depth / 2) * forward + (aside + v) * left
        for u in (-1.0, 1.0)
        for v in (-width / 2 - PALM_GAP - hand, width / 2 + PALM_GAP + hand)
    ]
    return corners, lowest, highest


def _out_from_under(body, carry: CarryArms, grasped, carried, around) -> np.ndarray | None:
    """How far (a world vector) the object taken at `grasped` must be drawn out towards the
    person, level, before it can rise into the carry posture at `carried`: out from under
    what stands over it lower than it rises (the board above it in a shelf; lifted straight
    up there, a forearm went 11 cm into it), and by WAY_BEND further, which the way up may
    pass beside the straight one (a hand rising from a shelf's bottom board went 2.3 cm into
    the board above). None: nothing stands over it."""
    furniture, heading = around
    a, b = (_palms_midpoint(body, carry, q) for q in (grasped, carried))
    around_it, _, highest = _held_outline(body, carry, heading)
    low, high = a[2] + highest + CLEARANCE / 2, b[2] + highest
    back = -np.array([np.cos(heading), np.sin(heading)])
    for distance in np.arange(0.0, OUT_MOST, OUT_STEP):
        corners = [a[:2] + c + distance * back for c in around_it]
        if furniture.highest_between(MultiPoint(corners).convex_hull, low, high) is None:
            drawn = distance + CLEARANCE + WAY_BEND
            return None if distance == 0.0 else np.array([*(drawn * back), 0.0])
    return None


def _palms_midpoint(body, carry: CarryArms, q: np.ndarray) -> np.ndarray:
    return np.mean(_hands_at(body, carry.hands, q), axis=0)


def _level(body, carry: CarryArms, a: np.ndarray, b: np.ndarray, around):
    """The crossing level of the way of the held object from pose a to pose b."""
    furniture, heading = around
    middle = [_palms_midpoint(body, carry, q) for q in (a, b)]
    return crossing_level(body, furniture, carry, *middle, heading)


def _in_chest(body: HumanBody, q: np.ndarray, sides) -> dict:
    """The hands' grasp frames in the chest's frame at q."""
    chest = body.frame_pose(CHEST, q).inverse()
    return {s: chest @ body.frame_pose(f"{s}_hand_grasp", q) for s in sides}


def carried_off(body, clip, placed_pose, hands, carry, on_target, marks, keys: "Keys", around):
    """Offsets of a clip that takes an object and carries it off in the carry posture:
    `keys` up to the grasp, then the way into the carry posture, over what stands on it
    (`around`: the furniture and the person's heading). From under a board (a shelf's) the
    object is first drawn out, level, the body still bent as it took it; off a surface above
    the shoulders, out over the surface's edge (`_off_the_edge`), and then straight down:
    carried at the height of a shelf's 1.6 m top board back to above the chest, a box left
    the arms unable to hold it (the palms' spacing 5-7 cm off its width)."""
    sides = tuple(hands)
    grasped = placed_pose(clip.sample(marks[2])) + on_target
    carried = carry.over(placed_pose(clip.sample(clip.duration)))
    out = _out_from_under(body, carry, grasped, carried, around)
    over = out is None and _above_the_shoulders(body, grasped, sides)
    if over:
        out = _off_the_edge(body, carry, grasped, around)
    taken = (body, clip, placed_pose, carry, on_target, marks, sides, grasped, carried)
    ways = _ways_off(*taken, None if over else around, out)
    for k, (times, way) in enumerate(ways):
        _add_way(keys, times, way, joined=k > 0)
    return keys.motion(sides, (marks[0], clip.duration))


def _ways_off(
    body, clip, placed_pose, carry, on_target, marks, sides, grasped, carried, around, out
):
    """The (times, offsets) of the ways of `carried_off`: drawn out by `out` (None: not)
    and into the carry posture, over what stands on that way (`around`; None: straight,
    drawn out over the edge of what it lay on), each on from the last one's last key."""
    hold_end = marks[2]
    end_pose = placed_pose(clip.sample(clip.duration))
    arms = arm_indices(body, sides)
    start, offset, ways = hold_end, on_target, []
    if out is not None:
        start = hold_end + OUT_SHARE * (clip.duration - hold_end)
        times, way = _drawn_out(body, clip, placed_pose, (hold_end, start), grasped, out, sides)
        way[0] = on_target
        ways.append((times, way))
        offset = way[-1]
    held = placed_pose(clip.sample(start)) + offset
    way_from, way_to = _in_chest(body, held, sides), _in_chest(body, carried, sides)
    zero = np.zeros_like(on_target)
    span = (start, clip.duration)
    level = None if around is None else _level(body, carry, held, carried, around)
    way = (way_from, way_to, offset, zero, arms)
    times, way = _way(body, clip, placed_pose, span, *way, level=level, taken=True)
    way[0], way[-1] = offset, carried - end_pose
    joined = int(out is not None)  # the drawn-out way's last key is this way's first
    ways.append((times[joined:], way[joined:]))
    return ways


def _above_the_shoulders(body, q: np.ndarray, sides) -> bool:
    """Whether the hands are above their shoulders at q."""
    return all(
        body.frame_pose(f"{side}_hand_grasp", q).translation()[2]
        > body.frame_pose(f"{side}_upper_arm", q).translation()[2]
        for side in sides
    )


def _off_the_edge(body, carry: CarryArms, grasped, around) -> np.ndarray | None:
    """How far (a world vector) the object taken at `grasped` is drawn out towards the
    person, lifted CLEARANCE off what it lay on, until it and the hands are WAY_BEND clear
    of that surface's edge, as far as the way down may bend (2 cm clear, a box brought down
    from a shelf's 1.6 m top board went 1.4 cm into its edge), None: it lay on nothing of
    the cell, or cannot be."""
    furniture, heading = around
    a = _palms_midpoint(body, carry, grasped)
    around_it, lowest, _ = _held_outline(body, carry, heading)
    support = furniture.support(a - [0.0, 0.0, lowest - CLEARANCE / 2])
    if support is None:
        return None
    back = -np.array([np.cos(heading), np.sin(heading)])
    for distance in np.arange(OUT_STEP, OUT_MOST, OUT_STEP):
        outline = MultiPoint([a[:2] + c + distance * back for c in around_it]).convex_hull
        if not outline.buffer(WAY_BEND).intersects(furniture.pile(support).outline):
            return np.array([*(distance * back), CLEARANCE])
    return None


def _add_way(keys: "Keys", times, way, joined: bool = False) -> None:
    """The way's offsets as keys played straight through (`joined`: on from the last key,
    which is its first point)."""
    first = len(keys.times) - 1 if joined else len(keys.times)
    for time, offset in zip(times, way, strict=True):
        keys.add(time, offset)
    keys.paths.append((first, len(keys.times) - 1))


def _drawn_out(body, clip, placed_pose, span, grasped, out, sides):
    """Times over `span` and the offsets there that draw the held object out by the world
    vector `out`, level, the rest of the body held as it was at the grasp (`grasped`)."""
    arms = arm_indices(body, sides)
    chest = body.frame_pose(CHEST, grasped)
    start = _in_chest(body, grasped, sides)
    shift = chest.rotation().inverse() @ np.asarray(out)
    end = {s: RigidTransform(X.rotation(), X.translation() + shift) for s, X in start.items()}
    zero = np.zeros_like(grasped)
    times, way = _way(body, _Still(grasped), lambda q: q, span, start, end, zero, zero, arms)
    return times, [
        offset + grasped - placed_pose(clip.sample(t)) for t, offset in zip(times, way, strict=True)
    ]


class _Still:
    """A clip that holds one pose (the body as it took the object)."""

    def __init__(self, pose: np.ndarray):
        self.pose = pose

    def sample(self, _time: float) -> np.ndarray:
        return self.pose


def put_down(body, clip, placed_pose, hands, carry, near, on_target, marks, opened, edge, around):
    """Offsets of a clip that starts in the carry posture and puts the object down over
    what stands on its way (`around`: the furniture and the person's heading), lowered
    straight from `near` onto its place: the hands open to `opened` and, over a surface,
    leave it over its `edge`. Lowered by the clip's own motion under offsets eased from
    `near` to the place, a part put into a bin went 4.6 cm below its place and came back
    up to it (cooperation seed 0 at 133.2 s: 4.9 cm into the part it was put on)."""
    approach_time, event, hold_end = marks
    near_offset = offset_to(body, placed_pose, clip, approach_time, on_target, near, on_target)
    sides = tuple(hands)
    start_pose = placed_pose(clip.sample(0.0))
    held = carry.over(start_pose)
    above = placed_pose(clip.sample(approach_time)) + near_offset
    start, end = _in_chest(body, held, sides), _in_chest(body, above, sides)
    zero = np.zeros_like(on_target)
    arms = arm_indices(body, sides)
    level = _level(body, carry, held, above, around)
    span = (0.0, approach_time)
    times, way = _way(
        body, clip, placed_pose, span, start, end, zero, near_offset, arms, level=level
    )
    way[0], way[-1] = held - start_pose, near_offset
    keys = Keys(body, clip, placed_pose)
    _add_way(keys, times, way)
    keys.straight(event, near, hands, on_target, landed=on_target)
    keys.add(hold_end, on_target)
    release_end = hold_end + LEAVE_AT * (clip.duration - hold_end)
    keys.straight(release_end, hands, opened, on_target)
    if edge is None:
        keys.add(clip.duration, zero)
    else:
        keys.off_the_edge(edge, clip.duration, below_the_top(body, around[0], hands))
        keys.straight_to_the_end(clip.duration, sides)
    return keys.motion(sides, (0.0, release_end))
