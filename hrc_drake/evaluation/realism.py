"""The realism audit: does the person move like a person in this cell?

Sampled at the person's update rate during the run, it keeps the worst of each of these
(docs/realism.md gives the published figures behind the limits):
- how deep any body segment goes into the cell's static geometry, and into objects that
  the person does not hold (a box on the pallet, the carton the robot holds out);
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

CONTACT_HEIGHT = 0.003
"""m: a sole point this close to the floor stands on it."""
STEADY_SPEED_CHANGE = 0.05
"""A stride is steady walking when its start and end speeds differ by less than this
fraction of its mean (speeding up and slowing down are not strides of a gait)."""
WALKING_SPEED = 0.5
"""m/s: slower strides are not walking at a normal speed."""


LIMITS = {
    "penetration_static": 0.01,
    "penetration_objects": 0.01,
    "hand_object_gap": 0.02,
    "carried_tilt_deg": 15.0,
    "foot_slip": 0.01,
}
"""What a realistic run stays within (m, or degrees for the tilt); docs/realism.md."""
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
    if mean < WALKING_SPEED or abs(speeds[-1] - speeds[0]) > STEADY_SPEED_CHANGE * mean:
        return state
    variation = float(speeds.max() - speeds.min()) / 2 / mean
    return replace(
        state,
        stride_variations=(*state.stride_variations, variation),
        stride_speeds=(*state.stride_speeds, mean),
    )


def realism_metrics(state: AuditState | None) -> dict:
    """The report's `realism` section (empty without a person)."""
    if state is None:
        return {}

    def worst(w: Worst, what: str) -> dict:
        return {"max": rounded(w.value), "time": rounded(w.time), what: w.what}

    variations = np.array(state.stride_variations)
    return {
        "penetration_static": worst(state.static_penetration, "where"),
        "penetration_objects": worst(state.object_penetration, "where"),
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


def realism_rows(metrics: dict) -> list[list]:
    """The report page's realism table: measure, worst value, limit, where and when, ok."""
    rows = []
    for name, limit in LIMITS.items():
        worst = metrics[name]
        where = next(v for k, v in worst.items() if k not in ("max", "time"))
        rows.append(
            [name, worst["max"], limit, f"{where} at {worst['time']:.1f} s", worst["max"] <= limit]
        )
    pelvis = metrics["pelvis_speed"]
    swing = pelvis["variation_max"]
    rows.append(
        [
            "pelvis_speed_swing",
            swing,
            PELVIS_SPEED_SWING,
            f"{pelvis['strides']} strides",
            swing <= PELVIS_SPEED_SWING,
        ]
    )
    return rows
