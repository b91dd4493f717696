"""The realism audit: does the person move like a person in this cell, and do the objects
stay out of the cell and of each other? In a cell without a person only the objects' part
(what the robot holds) is measured, and the report says the person's measures were not.

Sampled at the person's update rate during the run, it keeps the worst of each of these
(docs/realism.md gives the published figures behind the limits):
- how deep any body segment goes into the cell's static geometry, and into objects that
  the person does not hold (a box on the pallet, the carton the robot holds out);
- how deep an object the person or the robot holds goes into the cell's static geometry
  or another object (a carton carried through the top of a stack, a part the robot puts
  down into a table);
- how far a held object is from its holding hand(s): the grasp point's distance to the
  object's surface, inside or out;
- how far a carried object leans from upright;
- how far a sole point slides while it stands on the floor (foot skating);
- how much the pelvis speed swings within a stride of steady walking, as a fraction of the
  stride's mean speed (published gait data: about ±10-15 % at normal speed).

`AuditState` is immutable and holds no Drake objects, so a System keeps it as abstract
state; `audited(state, sample)` is one step.
"""

import math
from dataclasses import dataclass, field, replace

import numpy as np

from hrc_drake.evaluation.metrics import rounded
from hrc_drake.scene_geometry import OBJECT_DEPTH_LIMIT

CONTACT_HEIGHT = 0.003
"""m: a sole point this close to the floor stands on it."""
STEADY_SPEED_CHANGE = 0.05
"""A stride is steady walking when it starts, turns to its second step and ends at walking
speed, the three differing by less than this fraction of its mean: the speed repeats with
each step of a steady gait (speeding up, slowing down, and a short walk from standing to
standing are not strides of a gait: a 1.8 m walk, collaboration seed 8 at 91.2 s, had a
stride from its speeding up into its slowing down, 1.02 and 1.08 m/s at its ends, 1.31 at
its middle)."""
WALKING_SPEED = 0.5
"""m/s: a stride that starts or ends slower is not walking at a normal speed."""


LIMITS = {
    "penetration_static": 0.01,
    "penetration_objects": 0.01,
    "penetration_carried": OBJECT_DEPTH_LIMIT,
    "hand_object_gap": 0.02,
    "carried_tilt_deg": 15.0,
    "foot_slip": 0.01,
}
"""What a realistic run stays within (m, or degrees for the tilt); docs/realism.md."""
NO_PERSON = "no person in this cell"
"""The report's `realism.person` in a cell without one: the person's measures are absent,
not zero and within their limits."""
PELVIS_SPEED_SWING = 0.15
"""Largest believable swing of the pelvis speed within a stride (fraction of its mean)."""


@dataclass(frozen=True)
class Worst:
    """The largest value seen, when, and of what."""

    value: float = 0.0
    time: float = 0.0
    what: str = ""

    def of(self, value: float, time: float, what: str) -> "Worst":
        return Worst(float(value), time, what) if value > self.value else self


@dataclass(frozen=True)
class Sample:
    """What the audit looks at in one instant."""

    time: float
    static_depths: tuple[tuple[float, str], ...]
    """Penetration depth (m) of each body segment into the cell's static geometry."""
    object_depths: tuple[tuple[float, str], ...]
    """Penetration depth (m) of each body segment into objects the person does not hold."""
    carried_depths: tuple[tuple[float, str], ...]
    """Penetration depth (m) of each held object into the static geometry or another object."""
    hand_gaps: tuple[tuple[float, str], ...]
    """|distance| from each holding hand's grasp point to its object's surface."""
    tilts: tuple[tuple[float, str], ...]
    """Angle (rad) between each held object's up axis and the world's."""
    sole_points: dict[str, np.ndarray]
    """World position of each sole point (heel and toe of each foot)."""
    pelvis: tuple[float, float, float] | None
    """(time of the person's pose, x, y) of the pelvis, or None before the first pose."""
    walking: bool


@dataclass(frozen=True)
class AuditState:
    static_penetration: Worst = Worst()
    object_penetration: Worst = Worst()
    carried_penetration: Worst = Worst()
    hand_gap: Worst = Worst()
    carried_tilt: Worst = Worst()
    foot_slip: Worst = Worst()
    stride_variations: tuple[float, ...] = ()
    """Per steady stride: (max - min pelvis speed) / 2 / mean speed."""
    stride_speeds: tuple[float, ...] = ()
    anchors: dict[str, tuple[float, float]] = field(default_factory=dict)
    """Where each sole point standing on the floor touched down."""
    pelvis: tuple[float, float, float] | None = None
    stride: tuple[tuple[float, float], ...] = ()
    """(time, pelvis speed) since the current stride began."""
    person: bool = True
    """False in a cell without a person: only the objects' measures mean anything."""

    def __deepcopy__(self, memo):
        """Immutable: Drake's state copies can share it."""
        return self


def _worst(current: Worst, values, time: float) -> Worst:
    for value, what in values:
        current = current.of(value, time, what)
    return current


def audited(state: AuditState, sample: Sample, stride_time: float) -> AuditState:
    """The audit after one more sample; strides last `stride_time` (one gait cycle)."""
    t = sample.time
    anchors, slip = _slid(state.anchors, sample.sole_points, state.foot_slip, t)
    state = replace(
        state,
        static_penetration=_worst(state.static_penetration, sample.static_depths, t),
        object_penetration=_worst(state.object_penetration, sample.object_depths, t),
        carried_penetration=_worst(state.carried_penetration, sample.carried_depths, t),
        hand_gap=_worst(state.hand_gap, sample.hand_gaps, t),
        carried_tilt=_worst(state.carried_tilt, [(math.degrees(a), w) for a, w in sample.tilts], t),
        foot_slip=slip,
        anchors=anchors,
    )
    return _walked(state, sample, stride_time)


def _slid(anchors, points, worst: Worst, t: float):
    """Anchor each sole point when it touches the floor; a point that stays there and moves
    away from its anchor slides."""
    kept = {}
    for name, p in points.items():
        if p[2] > CONTACT_HEIGHT:
            continue
        anchor = anchors.get(name, (float(p[0]), float(p[1])))
        kept[name] = anchor
        worst = worst.of(math.hypot(p[0] - anchor[0], p[1] - anchor[1]), t, name)
    return kept, worst


def _walked(state: AuditState, sample: Sample, stride_time: float) -> AuditState:
    """Pelvis speed from the person's successive poses, gathered into strides."""
    pelvis = sample.pelvis
    if pelvis is None or (state.pelvis is not None and pelvis[0] <= state.pelvis[0]):
        return state
    if state.pelvis is None or not sample.walking:
        return replace(state, pelvis=pelvis, stride=())
    t0, x0, y0 = state.pelvis
    speed = math.hypot(pelvis[1] - x0, pelvis[2] - y0) / (pelvis[0] - t0)
    stride = (*state.stride, (pelvis[0], speed))
    if stride[-1][0] - stride[0][0] < stride_time:
        return replace(state, pelvis=pelvis, stride=stride)
    speeds = np.array([v for _, v in stride])
    mean = float(speeds.mean())
    state = replace(state, pelvis=pelvis, stride=(stride[-1],))
    times = np.array([t for t, _ in stride])
    steps = (speeds[0], np.interp((times[0] + times[-1]) / 2, times, speeds), speeds[-1])
    if min(steps) < WALKING_SPEED or max(steps) - min(steps) > STEADY_SPEED_CHANGE * mean:
        return state
    variation = float(speeds.max() - speeds.min()) / 2 / mean
    return replace(
        state,
        stride_variations=(*state.stride_variations, variation),
        stride_speeds=(*state.stride_speeds, mean),
    )


def realism_metrics(state: AuditState | None) -> dict:
    """The report's `realism` section (empty without a person or objects; the objects'
    measures and `person` saying there is none, without a person)."""
    if state is None:
        return {}

    def worst(w: Worst, what: str) -> dict:
        return {"max": rounded(w.value), "time": rounded(w.time), what: w.what}

    if not state.person:
        carried = worst(state.carried_penetration, "where")
        return {"penetration_carried": carried, "person": NO_PERSON}
    variations = np.array(state.stride_variations)
    return {
        "penetration_static": worst(state.static_penetration, "where"),
        "penetration_objects": worst(state.object_penetration, "where"),
        "penetration_carried": worst(state.carried_penetration, "where"),
        "hand_object_gap": worst(state.hand_gap, "object"),
        "carried_tilt_deg": worst(state.carried_tilt, "object"),
        "foot_slip": worst(state.foot_slip, "point"),
        "pelvis_speed": {
            "strides": len(variations),
            "mean_speed": rounded(np.mean(state.stride_speeds)) if len(variations) else 0.0,
            "variation_median": rounded(np.median(variations)) if len(variations) else 0.0,
            "variation_max": rounded(variations.max()) if len(variations) else 0.0,
        },
    }


def audits_a_person(metrics: dict) -> bool:
    """Whether the report's `realism` section measured a person (not only objects)."""
    return metrics.get("person") != NO_PERSON


MEASURES = {
    "penetration_static": ("body in the cell's geometry", "m"),
    "penetration_objects": ("body in an object", "m"),
    "penetration_carried": ("held object in the cell or another object", "m"),
    "hand_object_gap": ("holding hand off its object", "m"),
    "carried_tilt_deg": ("carried object tilted", "deg"),
    "foot_slip": ("standing foot slid", "m"),
    "pelvis_speed_swing": ("pelvis speed swing within a stride", "fraction"),
}
"""What each measure of the audit means to a reader, and its unit (report.json's)."""


@dataclass(frozen=True)
class Check:
    """One measure of a run's audit against its limit: the worst value, what and where it
    was (with when), or how many strides it was measured over."""

    measure: str
    worst: float
    limit: float
    where: str
    measured: bool = True
    """False when the run had nothing to measure it on (no stride of steady walking): it is
    then neither within nor over its limit, and the verdict says so instead of counting it."""

    @property
    def within(self) -> bool:
        return self.worst <= self.limit

    @property
    def excess(self) -> float:
        """How many times its limit the worst value is: measures of different units
        compare by it."""
        return self.worst / self.limit

    def __str__(self) -> str:
        """`body in the cell's geometry 34.0 cm (limit 1 cm): pelvis in work_table at 36.2 s`"""
        description, unit = MEASURES[self.measure]
        return (
            f"{description} {_amount(self.worst, unit, self._decimals(unit))} "
            f"(limit {_amount(self.limit, unit, 0)}): {self.where}"
        )

    def _decimals(self, unit: str) -> int:
        """One decimal, or as many more as show a worst value beyond its limit as beyond it
        (a hand 1.04 cm into a rack was printed "1.0 cm (limit 1 cm)", a user's cell)."""
        scale = SHOWN_AS[unit][0]
        decimals = 1
        while (
            not self.within
            and decimals < 3
            and round(scale * self.worst, decimals) <= (scale * self.limit)
        ):
            decimals += 1
        return decimals


SHOWN_AS = {"m": (100, " cm"), "deg": (1, "°"), "fraction": (100, " %")}
"""Each unit as a reader pictures it at this scale: centimetres, degrees or per cent (the
factor from report.json's unit, the suffix)."""


def _amount(value: float, unit: str, decimals: int) -> str:
    scale, suffix = SHOWN_AS[unit]
    return f"{scale * value:.{decimals}f}{suffix}"


def realism_checks(metrics: dict) -> list[Check]:
    """Every measure of the report's `realism` section against its limit (none without a
    person or objects; the objects' alone without a person)."""
    checks = []
    for name, limit in LIMITS.items():
        if name not in metrics:
            continue
        worst = metrics[name]
        what = next(v for k, v in worst.items() if k not in ("max", "time"))
        checks.append(Check(name, worst["max"], limit, f"{what} at {worst['time']:.1f} s"))
    pelvis = metrics.get("pelvis_speed")
    if pelvis is None:
        return checks
    strides = f"worst of {pelvis['strides']} strides of steady walking"
    if not pelvis["strides"]:
        strides = "no stride of steady walking to measure it on"
    swing = pelvis["variation_max"]
    checks.append(
        Check("pelvis_speed_swing", swing, PELVIS_SPEED_SWING, strides, bool(pelvis["strides"]))
    )
    return checks


def over_limits(metrics: dict) -> list[Check]:
    """The measures beyond their limits, the farthest beyond first."""
    return sorted((c for c in realism_checks(metrics) if not c.within), key=lambda c: -c.excess)


def realism_verdict(metrics: dict) -> list[str]:
    """The audit's verdict in a line (and one more line per further measure over its
    limit); none without a person or objects. A measure the run had nothing to measure on
    is named as such, not counted within the limits (a packing cell of our own walked 25 m
    in short walks round corners, no stride of steady walking, and was "within its limits
    (7 measures)"), and so are the person's in a cell without one."""
    checks = realism_checks(metrics)
    if not checks:
        return []
    measured = [c for c in checks if c.measured]
    unmeasured = "".join(
        f"; not measured: {MEASURES[c.measure][0]} ({c.where})" for c in checks if not c.measured
    )
    if not audits_a_person(metrics):
        unmeasured += f"; not measured: the person's measures ({NO_PERSON})"
    over = over_limits(metrics)
    if not over:
        counted = f"{len(measured)} measure{'s' if len(measured) != 1 else ''}"
        return [f"within its limits ({counted}){unmeasured}"]
    first = f"{len(over)} of {len(measured)} measures over their limits; worst: {over[0]}"
    return [first + unmeasured, *(f"also: {check}" for check in over[1:])]


def realism_rows(metrics: dict) -> list[list]:
    """The report page's realism table: measure, worst value, limit, where and when, ok
    (or "not measured")."""
    return [
        [c.measure, c.worst, c.limit, c.where, c.within if c.measured else "not measured"]
        for c in realism_checks(metrics)
    ]
