"""The person's work over a run, scored: RULA and REBA of both sides at every posture
sample, and the NIOSH lifting equation for every lift (an object from the moment the
person's hands take it to the moment they let it go).

Works from plain data (`PersonTrack`: the sampled joint positions, what the hands held
and when, when the person walked and started actions), so any recorded run, or a posture
held on purpose, can be assessed.
"""

from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from hrc_drake.ergonomics import niosh
from hrc_drake.ergonomics.config import ErgonomicsOptions
from hrc_drake.ergonomics.posture import Pose, poses_of, posture_angles
from hrc_drake.ergonomics.reba import COUPLINGS, reba_score
from hrc_drake.ergonomics.rula import grand_score
from hrc_drake.ergonomics.scoring import Activity, Load, reba_parts, rula_parts
from hrc_drake.human.body import human_body
from hrc_drake.human.skeleton import SIDES
from hrc_drake.workpieces.messages import BOTH_HANDS, LEFT_HAND, HeldObject

STATIC = 60.0
"""s a posture or a load is held before it counts as static (both methods: over a minute)"""
REPEATED = 4
"""actions in the last minute above which they count as repeated"""
RAPID_WINDOW, RAPID_RANGE = 1.0, 45.0
"""a trunk or upper-arm angle changing by more than RAPID_RANGE degrees within RAPID_WINDOW
seconds is a rapid large change of posture (REBA's activity score)"""
CM_PER_M = 100.0


@dataclass(frozen=True)
class PersonTrack:
    """What a run shows of the person: their size, the plant positions of their joints
    (one column per time in `times`), what their hands held from each time on, when they
    walked, when they started an action, and what they were doing (`activity(t)`)."""

    height: float
    mass: float
    times: np.ndarray
    positions: np.ndarray
    holds: list[tuple[float, tuple[HeldObject, ...]]] = field(default_factory=list)
    walking: list[tuple[float, float]] = field(default_factory=list)
    actions: list[float] = field(default_factory=list)
    activity: Callable[[float], str] = lambda t: ""


@dataclass(frozen=True)
class LiftEnd:
    """One end of a lift in the equation's terms (cm, degrees) and its result."""

    point: niosh.LiftPoint
    multipliers: niosh.Multipliers
    rwl: float
    lifting_index: float


@dataclass(frozen=True)
class Lift:
    time: float
    end_time: float
    object: HeldObject
    coupling: str
    distance: float
    frequency: float
    duration: str
    origin: LiftEnd
    destination: LiftEnd
    notes: tuple[str, ...]

    @property
    def lifting_index(self) -> float:
        return max(self.origin.lifting_index, self.destination.lifting_index)


@dataclass(frozen=True)
class Assessment:
    """Per posture sample (`times`) and side (`SIDES` order) the RULA grand score and the
    REBA score; every lift; what the person was doing at each sample."""

    times: np.ndarray
    rula: np.ndarray
    reba: np.ndarray
    lifts: list[Lift]
    activities: list[str]


def assess(track: PersonTrack, options: ErgonomicsOptions) -> Assessment:
    poses = poses_of(human_body(track.height, track.mass), track.positions)
    every = posture_angles(poses)
    angles = every.samples()
    times = track.times
    walking = _during(times, track.walking)
    held = [_held_at(track.holds, t) for t in times]
    repeated = _repeated(times, track.actions)
    rapid = _rapid(times, every)
    load_static = _held_long(times, held)
    rula_scores = np.zeros((len(SIDES), len(times)), dtype=int)
    reba_scores = np.zeros((len(SIDES), len(times)), dtype=int)
    static_a, static_b = _static_groups(angles, times, walking)
    for i, a in enumerate(angles):
        activity = Activity(
            static_a=static_a[i],
            static_b=static_b[i],
            repeated=repeated[i],
            rapid_change=rapid[i],
            walking=walking[i],
        )
        load = _load(held[i], load_static[i] or repeated[i], options.coupling)
        for s, side in enumerate(SIDES):
            rula_scores[s, i] = grand_score(rula_parts(a, side, load, activity))
            reba_scores[s, i] = reba_score(reba_parts(a, side, load, activity))
    lifts = _lifts(track, poses, options)
    activities = [track.activity(t) for t in times]
    return Assessment(times, rula_scores, reba_scores, lifts, activities)


def _during(times: np.ndarray, spans: list[tuple[float, float]]) -> np.ndarray:
    inside = np.zeros(len(times), dtype=bool)
    for start, end in spans:
        inside |= (times >= start) & (times < end)
    return inside


def _held_at(holds: list, t: float) -> tuple[HeldObject, ...]:
    current: tuple[HeldObject, ...] = ()
    for time, objects in holds:
        if time > t:
            break
        current = objects
    return current


def _repeated(times: np.ndarray, actions: list[float]) -> np.ndarray:
    """More than REPEATED actions started in the minute up to each time."""
    starts = np.sort(np.array(actions, dtype=float))
    counts = np.searchsorted(starts, times, "right") - np.searchsorted(starts, times - STATIC)
    return counts > REPEATED


def _rapid(times: np.ndarray, angles) -> np.ndarray:
    series = np.stack([angles.trunk_flexion, *(angles.arms[s].flexion for s in SIDES)], axis=1)
    rapid = np.zeros(len(times), dtype=bool)
    for i, t in enumerate(times):
        window = series[np.searchsorted(times, t - RAPID_WINDOW) : i + 1]
        rapid[i] = bool((np.ptp(window, axis=0) > RAPID_RANGE).any())
    return rapid


def _since_change(times: np.ndarray, keys: list) -> np.ndarray:
    """Seconds each sample's key has stayed the same."""
    start = np.zeros(len(times))
    for i in range(1, len(times)):
        start[i] = start[i - 1] if keys[i] == keys[i - 1] else times[i]
    return times - start


def _static_groups(angles: list, times: np.ndarray, walking: np.ndarray):
    """Whether the arms (group A) and the neck, trunk and legs (group B) have kept their
    RULA part scores, without walking, for over a minute."""
    plain, still = Load(), Activity()
    parts = [[rula_parts(a, side, plain, still) for side in SIDES] for a in angles]
    arms = [tuple((p.upper_arm, p.lower_arm, p.wrist) for p in sides) for sides in parts]
    rest = [
        (sides[0].neck, sides[0].trunk, sides[0].legs, w)
        for sides, w in zip(parts, walking, strict=True)
    ]
    return (
        (_since_change(times, arms) > STATIC) & ~walking,
        (_since_change(times, rest) > STATIC) & ~walking,
    )


def _held_long(times: np.ndarray, held: list) -> np.ndarray:
    """The same load held for over a minute (static)."""
    keys = [tuple(o.id for o in objects) for objects in held]
    return (_since_change(times, keys) > STATIC) & np.array([bool(k) for k in keys])


def _load(objects: tuple[HeldObject, ...], static_or_repeated: bool, default: str) -> Load:
    left = sum(o.mass for o in objects if o.holder in (LEFT_HAND, BOTH_HANDS))
    right = sum(o.mass for o in objects if o.holder != LEFT_HAND)
    couplings = [o.coupling or default for o in objects] or ["good"]
    coupling = max(couplings, key=COUPLINGS.index)
    return Load(left, right, coupling, static_or_repeated)


def _lifts(track: PersonTrack, poses: Pose, options: ErgonomicsOptions) -> list[Lift]:
    """Every object the hands took and let go of during the run, as NIOSH lifts; the
    frequency is the run's own lifts per minute."""
    spans = _holding_spans(track.holds)
    if not spans or len(track.times) == 0:
        return []
    minutes = max(track.times[-1] - track.times[0], 1e-9) / 60.0
    frequency = len(spans) / minutes
    duration = niosh.duration_category(options.work_hours)
    lifts = []
    for start, end, held in spans:
        ends = [_lift_point(poses.at(_nearest(track.times, t)), held.holder) for t in (start, end)]
        distance = abs(ends[1].v - ends[0].v)
        coupling = held.coupling or options.coupling
        results = [
            _lift_end(point, distance, frequency, duration, coupling, held.mass) for point in ends
        ]
        notes = [n for point in ends for n in niosh.out_of_range(point, distance, frequency)]
        if held.holder != BOTH_HANDS:
            notes.insert(0, "one-handed: outside the lifting equation's scope")
        lifts.append(
            Lift(start, end, held, coupling, distance, frequency, duration, *results, tuple(notes))
        )
    return lifts


def _holding_spans(holds: list) -> list[tuple[float, float, HeldObject]]:
    """(taken, let go, object) of every object held and released during the run."""
    taken: dict[int, tuple[float, HeldObject]] = {}
    spans = []
    for time, objects in holds:
        now = {o.id: o for o in objects}
        for object_id, (start, held) in list(taken.items()):
            if object_id not in now:
                spans.append((start, time, held))
                del taken[object_id]
        for object_id, held in now.items():
            taken.setdefault(object_id, (time, held))
    return sorted(spans, key=lambda span: span[0])


def _nearest(times: np.ndarray, t: float) -> int:
    i = int(np.searchsorted(times, t))
    if i == len(times) or (i > 0 and t - times[i - 1] <= times[i] - t):
        return max(i - 1, 0)
    return i


def _lift_point(pose: Pose, holder: str) -> niosh.LiftPoint:
    """H, V (cm) and A (degrees) of the hands as the manual measures them: from the
    midpoint between the ankles, along the floor, and against the sagittal line of the
    feet."""
    p, R = pose.positions, pose.rotations
    hands = [f"{side}_hand_grasp" for side in SIDES]
    if holder != BOTH_HANDS:
        hands = ["left_hand_grasp" if holder == LEFT_HAND else "right_hand_grasp"]
    grasp = np.mean([p[h] for h in hands], axis=0)
    ankles = np.mean([p[f"{side}_foot"] for side in SIDES], axis=0)
    sagittal = sum(R[f"{side}_foot"][:2, 0] for side in SIDES)
    reach = grasp[:2] - ankles[:2]
    cross = sagittal[0] * reach[1] - sagittal[1] * reach[0]
    asymmetry = np.degrees(np.arctan2(abs(cross), sagittal @ reach))
    return niosh.LiftPoint(
        h=float(np.linalg.norm(reach)) * CM_PER_M,
        v=float(grasp[2]) * CM_PER_M,
        a=float(asymmetry),
    )


def _lift_end(point, distance, frequency, duration, coupling, mass) -> LiftEnd:
    factors = niosh.multipliers(point, distance, frequency, duration, coupling)
    rwl = niosh.recommended_weight_limit(factors)
    return LiftEnd(point, factors, rwl, niosh.lifting_index(mass, rwl))
