"""Walking on footsteps: the feet stand where they land, on any path, from a standstill to
a standstill.

A gait clip (walk, carry) is authored on a straight line at its own speed. Played along a
path that bends, speeds up and slows down, its stance feet would slide. Instead the legs
are placed: at plan time every step gets its place (`plan_steps`): along the path under
where the pelvis passes during that stance, turned with the path; the first steps leave
the feet's standing places and the last ones close the feet side by side at the goal. At
every pose the clip gives the body, the trunk and the arms, the rhythm (its phase runs with
time at the clip's cadence) and how each foot pitches, lifts and travels through a swing
(`GaitProfile`); hrc_drake.human.legs then solves each leg onto its sole's place.
"""

from dataclasses import dataclass, replace
from functools import lru_cache
from itertools import pairwise
from math import cos, inf, sin, sqrt

import numpy as np

from hrc_drake.human.clip import Clip
from hrc_drake.human.keyed_clips import minimum_jerk
from hrc_drake.human.legs import Legs
from hrc_drake.human.rotations import wrap_angle
from hrc_drake.human.skeleton import SIDES

PROFILE_SAMPLES = 240
"""Samples of one gait cycle in a GaitProfile."""
STANCE = 0.6
"""Fraction of the gait cycle a foot stands (heel strike to toe-off; docs/human-body.md)."""
LIFTING = (STANCE, 0.68)
"""Leg phases over which the foot leaving the floor picks up speed: it rises before it
moves on (the gait clips are authored so too: hrc_drake.modelgen.gait)."""
SETTLING = (0.9, 1.0)
"""Leg phases over which the swinging foot slows to a stop above its landing place: it comes
down on it without sliding on."""
LAG = {"left": 0.0, "right": 0.5}
"""Phase of each foot's heel strike in the gait cycle (the clips' `<side>_heel_strike`)."""
START_PHASE = 0.0
"""A walk starts at the phase of the left heel strike: the left foot stands flat where it
stood while the right heel rises and the right foot leaves its standing place first."""
CLOSING = 0.15
"""m: a step that would land less than this short of the goal (or past it) closes the feet
at the goal instead, if the goal is no further ahead of the pelvis than the gait's own
landing: a foot put down further ahead than that needs a longer leg than the person has,
and the pelvis would drop for it (it lands as far ahead as it reaches, and the next step
closes the feet)."""
SETTLE = 0.1
"""Fraction of a gait cycle after the last heel strike until the foot stands flat."""
LAST_OF_CYCLE = 1.0 - 1e-9
"""A swing's last phase (1.0 would wrap round to the cycle's start)."""
SWING_SLACK = 0.03
"""m: a swinging foot may fall this far short of its place rather than the pelvis dropping
for it (on the floor a foot must be exactly where it stands)."""
UNROLLING = 0.8
"""Leg phase by which a foot that left the floor pitched as far as a full step's has come
to the pitch of its own, shorter, step."""
LANDING = (0.8, 0.9)
"""Leg phases over which a landing foot comes to keep at least LANDING_SLOPE of its way
still to go above the floor."""
LANDING_SLOPE = 0.5
"""A landing foot comes down onto its step rather than gliding in low: a step that lags
behind the clip's (the body still speeding up) would skim the last centimetres along the
floor, which the eye, and the realism audit, read as a sliding foot. The audit counts a
sole within 3 mm of the floor as standing: at 0.3, a heel on a walk round a robot at rest
came down 1.0 cm from its step (the audit's limit), now 0.3-0.4 cm."""
FIRST_RISE = 0.1
"""Fraction of a gait cycle over which the first heel of a walk rises to the clip's pitch."""
LOWEST_LIFT = 0.35

"""A short step lifts the foot this fraction of a full stride's lift at least."""


@dataclass(frozen=True, eq=False)
class GaitProfile:
    """What a gait clip does with each foot, per phase of its own leg (0 = heel strike).

    A foot is followed by its *spot*: where its sole's origin would be if it were set down
    flat (on a standing foot: where it stands). Per leg phase: the foot's pitch (sine); in
    swing how high its spot is, how far it swings out sideways, how far it has come from one
    step to the next (`progress`, 0..1) and how far relative to the pelvis (`following`,
    0..1: from where it left the pelvis behind to where it lands ahead of it); and where a
    foot lands relative to the pelvis (`offset`: ahead of it at heel strike; `track`: to
    the side of the path).
    """

    pitch: np.ndarray
    progress: np.ndarray
    following: np.ndarray
    height: np.ndarray
    sideways: np.ndarray
    offset: dict
    track: dict
    stride: float

    def at(self, values: np.ndarray, leg_phase: float) -> float:
        u = (leg_phase % 1.0) * PROFILE_SAMPLES
        k = int(u)
        s = u - k
        return float(values[k] * (1 - s) + values[min(k + 1, PROFILE_SAMPLES - 1)] * s)


def _pivot(pitch: float, half_foot: float) -> float:
    """Where along the foot it rolls: over the heel when the toe is up, else over the toe."""
    return -half_foot if pitch > 0 else half_foot


@lru_cache(maxsize=16)
def gait_profile(legs: Legs, clip: Clip) -> GaitProfile:
    """The profile of a gait clip whose left heel strikes at phase 0 (see GaitProfile); the
    right foot does the same half a cycle later."""
    ix = clip.joint_names.index("base_x")
    phases = np.arange(PROFILE_SAMPLES) / PROFILE_SAMPLES
    poses = [clip.sample(p * clip.duration) for p in phases]
    stride = clip.animation_distance
    root = poses[0][ix] + phases * stride  # where the pelvis would be at an even pace
    offset, track = {}, {}
    for side in SIDES:
        spots = np.array([_spot_of(legs.sole(q, side), legs.half_foot) for q in poses])
        flat = spots[int(round((LAG[side] + 0.25) * PROFILE_SAMPLES)) % PROFILE_SAMPLES]
        step = flat[0] - (LAG[side] + 0.25 >= 1.0) * stride
        offset[side] = float(step - _root_at(root, stride, LAG[side]))
        track[side] = float(flat[1])
        if side == "left":
            left, pitch = spots, np.array([legs.sole(q, side).forward[2] for q in poses])
            swinging = phases >= STANCE
            ahead = left[:, 0] - root
            left_behind = ahead[int(STANCE * PROFILE_SAMPLES)]
            following = (ahead - left_behind) / (offset[side] - left_behind)
            progress = np.where(swinging, (left[:, 0] - step) / stride, 0.0)
            height = np.where(swinging, left[:, 2], 0.0)
            sideways = np.where(swinging, left[:, 1] - flat[1], 0.0)
    return GaitProfile(
        pitch,
        np.clip(progress, 0.0, 1.0),
        np.where(phases >= STANCE, np.clip(following, 0.0, 1.0), 0.0),
        height,
        sideways,
        offset,
        track,
        stride,
    )


def _spot_of(sole, half_foot: float) -> np.ndarray:
    """The spot of a sole (see GaitProfile): its origin as if set down flat round its pivot."""
    heading = sole.forward.copy()
    heading[2] = 0.0
    heading /= np.linalg.norm(heading)
    pivot = _pivot(float(sole.forward[2]), half_foot)
    return sole.position - pivot * heading + pivot * sole.forward


def _root_at(root: np.ndarray, stride: float, phase: float) -> float:
    """The clip's pelvis travel at `phase` (cycles past the first add a stride each)."""
    cycles, rest = divmod(phase, 1.0)
    return float(
        np.interp(rest * PROFILE_SAMPLES, np.arange(PROFILE_SAMPLES), root) + cycles * stride
    )


@dataclass(frozen=True)
class Spot:
    """Where a foot stands: `along` the path and `lateral` to its left, and in the world its
    flat sole's origin on the floor and its heading."""

    along: float
    lateral: float
    x: float
    y: float
    yaw: float

    def distance(self, other: "Spot") -> float:
        return sqrt((self.x - other.x) ** 2 + (self.y - other.y) ** 2)


@dataclass(frozen=True)
class Stance:
    """One foot standing on `spot` from `strike` to `toe_off` (seconds; inf: it stays), the
    pelvis `pelvis_in` along the path at strike and `pelvis_out` at toe-off. `first`: it
    stood there before the walk (flat, its heel rising from the start of the walk only as
    far as its first step needs); `last`: it closes the feet at the goal (it stays flat). `arriving`
    and `leaving` scale how far the foot rolls landing here and how high it lifts leaving
    (a step's length over a full step's, at least LOWEST_LIFT: a short step lands flatter
    and lifts the foot less)."""

    spot: Spot
    strike: float
    toe_off: float
    pelvis_in: float
    pelvis_out: float
    entered: float = 0.0
    """The foot's own gait phase at `strike` (0, a heel strike, except for the first)."""
    first: bool = False
    last: bool = False
    arriving: float = 1.0
    leaving: float = 1.0
    heel: float = 1.0
    """How far its heel rises before toe-off, as a fraction of the gait's: as far as the
    pelvis has gone past the foot by then over how far it goes in the gait (a first
    stance: `leaving`). A foot still under or ahead of the pelvis leaves flat: a walk's
    closing step of 4 cm, the pelvis already stopped behind the foot, rose on its toes as
    in a full stride and threw the knee 31 cm ahead of the pelvis, the thigh 3.1 cm into
    a KLT in front (a 95th-percentile man at a rack, a user's assembly cell)."""


def standing_spots(legs: Legs, place, along: float) -> dict[str, Spot]:
    """Where the feet stand when the pelvis stands `along` the path (`place` as in
    plan_steps)."""
    return {side: place(along + legs.sole_offset[0], legs.hip[side][1]) for side in SIDES}


def plan_steps(profile, cycle, start, arrive, travel, pace, place, begin, end, kept=None):
    """Every stance of both feet of a walk that sets off at `start`: `travel(t)` is the
    pelvis's distance along the path at t (it arrives at `arrive`), `pace(t)` its speed as a
    fraction of the clip's, `place(along, lateral)` the Spot that far along the path and to
    its left; the feet stand on `begin` at the start and close on `end` at the goal. With
    `kept` (stances per side), the feet have already taken those steps.

    A foot lands as far ahead of the pelvis as in the clip, in proportion to the pace: the
    slower the body moves, the closer under it the foot lands (as a balancing walker puts
    it, near where the body's momentum carries it). Returns the stances per side and when
    the last foot stands flat at the goal."""
    total = travel(arrive)
    stances = {}
    for side in SIDES:
        plan = list(kept[side]) if kept else [_first_stance(side, start, cycle, travel, begin)]
        if not plan[-1].last:
            plan[-1] = replace(plan[-1], pelvis_out=travel(plan[-1].toe_off))
        strike = plan[-1].strike + (1.0 - plan[-1].entered) * cycle
        while not plan[-1].last:
            pelvis = travel(strike)
            along = pelvis + profile.offset[side] * pace(strike)
            toe_off = strike + STANCE * cycle
            closing = along >= total - CLOSING or strike >= arrive
            if closing and end[side].along - pelvis <= profile.offset[side]:
                plan.append(Stance(end[side], strike, inf, pelvis, total, last=True))
            else:
                if closing:  # the goal is out of the leg's reach: as far as it reaches
                    along = pelvis + profile.offset[side]
                spot = place(along, profile.track[side])
                plan.append(Stance(spot, strike, toe_off, pelvis, travel(toe_off)))
            strike += cycle
        stances[side] = _scaled(plan, profile.stride, profile.offset[side])
    over = max(stances[side][-1].strike for side in SIDES) + SETTLE * cycle
    return stances, over


def _first_stance(side: str, start: float, cycle: float, travel, begin) -> Stance:
    """Where a foot stands when the walk sets off, and until its first toe-off."""
    toe_off = start + ((LAG[side] + STANCE - START_PHASE) % 1.0) * cycle
    entered = (START_PHASE - LAG[side]) % 1.0
    return Stance(begin[side], start, toe_off, 0.0, travel(toe_off), entered, first=True)


def _scaled(plan: list[Stance], stride: float, ahead: float) -> tuple[Stance, ...]:
    """The stances with the scale of the steps between them (`leaving`), of their
    landings (`arriving`: how far ahead of the pelvis the foot lands over the gait's own
    `ahead`; a walk's first step is short, yet it lands as far ahead as any) and of their
    heels' rise (`heel`: how far the pelvis has passed the foot at toe-off over the
    gait's own, its pelvis's travel over a stance less `ahead`)."""
    scales = [_scale(a.spot.distance(b.spot) / stride) for a, b in pairwise(plan)]
    arriving = [_scale((s.spot.along - s.pelvis_in) / ahead) for s in plan]
    leaving = [*scales, scales[-1]]
    passed = STANCE * stride - ahead
    return tuple(
        replace(stance, arriving=a, leaving=b, heel=b if stance.first else _heel(stance, passed))
        for stance, a, b in zip(plan, arriving, leaving, strict=True)
    )


def _heel(stance: Stance, passed: float) -> float:
    """`Stance.heel` of a stance whose foot the gait's pelvis has `passed` at toe-off."""
    return min(max((stance.pelvis_out - stance.spot.along) / passed, 0.0), 1.0)


def _scale(fraction: float) -> float:
    return min(max(fraction, LOWEST_LIFT), 1.0)


def sole_target(
    profile: GaitProfile,
    stances,
    k: int,
    side: str,
    t: float,
    cycle: float,
    half_foot: float,
    pelvis: float,
    pace: float,
    place,
):
    """Where the `side` sole goes at t (origin, forward axis), and how far short of it the
    leg may fall for the pelvis's sake (a foot in the air until it settles): it last struck
    stances[k];
    the feet keep the rhythm of a gait cycle of `cycle` seconds; the pelvis is `pelvis`
    along the path at `pace` (its speed over the clip's; `place` as in plan_steps).

    A swinging foot moves with the pelvis as the clip's does (from where it left the pelvis
    behind to where it lands ahead of it), so that a pelvis still speeding up does not fall
    behind its feet; it leaves its step and, slower than the clip, is brought to rest on
    the next one (at the clip's pace it comes to rest there as the clip's does)."""
    stance = stances[k]
    if t < stance.toe_off:
        u = stance.entered + (t - stance.strike) / cycle
        pitch = profile.at(profile.pitch, u)
        pitch *= stance.arriving if pitch > 0 else stance.heel
        if stance.first:
            rising = (t - stance.strike) / (FIRST_RISE * cycle)
            pitch = min(pitch, 0.0) * min(rising, 1.0)
        if stance.last:
            pitch = max(pitch, 0.0) if u < STANCE / 2 else 0.0
        return (
            *_sole_on(stance.spot.x, stance.spot.y, 0.0, stance.spot.yaw, pitch, half_foot),
            0.0,
        )
    landing = stances[k + 1]
    lift, land = stance.spot, landing.spot
    u = min(STANCE + (t - stance.toe_off) / cycle, LAST_OF_CYCLE)
    behind, ahead = lift.along - stance.pelvis_out, land.along - landing.pelvis_in
    along = pelvis + behind + profile.at(profile.following, u) * (ahead - behind)
    lifted = minimum_jerk((u - LIFTING[0]) / (LIFTING[1] - LIFTING[0]))
    settled = minimum_jerk((u - SETTLING[0]) / (SETTLING[1] - SETTLING[0])) * (1.0 - pace)
    along = lift.along + lifted * (along - lift.along)
    along += settled * (land.along - along)
    p = profile.at(profile.progress, u)
    scale = stance.leaving
    lateral = lift.lateral + p * (land.lateral - lift.lateral)
    lateral += scale * profile.at(profile.sideways, u) * (1 if side == "left" else -1)
    spot = place(along, lateral)
    off = place(land.along, land.lateral)  # a step placed off the path (facing the goal)
    x = spot.x + p * (land.x - off.x)
    y = spot.y + p * (land.y - off.y)
    yaw = lift.yaw + p * wrap_angle(land.yaw - lift.yaw)
    rolled = stance.heel  # how far it rolled leaving the floor
    unrolling = minimum_jerk((u - STANCE) / (UNROLLING - STANCE))
    landing_in = minimum_jerk((u - LANDING[0]) / (LANDING[1] - LANDING[0]))
    rolling = scale + (landing.arriving - scale) * landing_in  # to the pitch it lands with
    pitch = (rolling + (rolled - rolling) * (1.0 - unrolling)) * profile.at(profile.pitch, u)
    height = scale * profile.at(profile.height, u)
    remaining = sqrt((land.x - x) ** 2 + (land.y - y) ** 2)
    height = max(height, LANDING_SLOPE * remaining * landing_in)
    slack = SWING_SLACK * (1.0 - minimum_jerk((u - SETTLING[0]) / (SETTLING[1] - SETTLING[0])))
    return (*_sole_on(x, y, height, yaw, pitch, half_foot), slack)


def _sole_on(x: float, y: float, z: float, yaw: float, pitch: float, half_foot: float):
    """The sole (origin, forward axis) of a foot whose spot is (x, y, z), heading yaw and
    pitched round its heel (pitch > 0) or toe (pitch < 0); as tuples of floats (the legs
    take them apart again, twice a walking pose)."""
    c, s = cos(yaw), sin(yaw)
    level = sqrt(1.0 - pitch * pitch)
    forward = (level * c, level * s, pitch)
    pivot = _pivot(pitch, half_foot)
    rolled_from = (x + pivot * c, y + pivot * s, z)
    origin = tuple(a - pivot * f for a, f in zip(rolled_from, forward, strict=True))
    return origin, forward
