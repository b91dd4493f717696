"""report.json's `ergonomics` section, the ergonomic rows of timeline.png and the section
of report.html, from what a run recorded of the person (`RunRecord.person`) and what it
shows of them (their states: walking, actions; the person's tree: what they were doing).

The scores themselves are `hrc_drake.ergonomics`; this module turns a record into its
`PersonTrack` and the assessment into figures.
"""

import weakref
from html import escape

import numpy as np

from hrc_drake.ergonomics.assessment import Assessment, Lift, PersonTrack, assess
from hrc_drake.ergonomics.reba import RISK_LEVELS, risk_level
from hrc_drake.ergonomics.rula import ACTION_LEVELS, action_level
from hrc_drake.evaluation.html import html_table
from hrc_drake.evaluation.metrics import rounded
from hrc_drake.evaluation.record import RunRecord
from hrc_drake.evaluation.timeline import activity
from hrc_drake.human.skeleton import SIDES

PERSON, PERSON_TREE = "person", "human tree"
WALKING, ACTING = "MOVEMENT", "ANIMATION"
RULA_ROW, REBA_ROW = "RULA", "REBA"

_assessed: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()


def assessment_of(record: RunRecord) -> Assessment | None:
    """The run's ergonomic assessment (None without a person), computed once per record."""
    if record.person is None:
        return None
    if record.person not in _assessed:
        _assessed[record.person] = assess(person_track(record), record.setup.ergonomics)
    return _assessed[record.person]


def person_track(record: RunRecord) -> PersonTrack:
    person = record.person
    states = record.states.get(PERSON, [])
    end = record.setup.duration
    tree = record.states.get(PERSON_TREE, [])
    return PersonTrack(
        height=person.height,
        mass=person.mass,
        times=person.times,
        positions=person.positions,
        holds=person.holds,
        walking=[(a, b) for a, b, state in _spans(states, end) if state == WALKING],
        actions=[a for a, _, state in _spans(states, end) if state == ACTING],
        activity=lambda t: activity(PERSON_TREE, _state_at(tree, t)),
    )


def _spans(changes: list[tuple[float, str]], end: float) -> list[tuple[float, float, str]]:
    stops = [t for t, _ in changes[1:]] + [end]
    return [(t, stop, state) for (t, state), stop in zip(changes, stops, strict=True)]


def _state_at(changes: list[tuple[float, str]], t: float) -> str:
    current = ""
    for time, state in changes:
        if time > t:
            break
        current = state
    return current


def ergonomics_metrics(record: RunRecord) -> dict:
    """The worst RULA and REBA scores (with time, side, activity), the share of the
    person's time at each RULA action level and REBA risk level, every lift and the
    largest lifting index; empty without a person."""
    assessment = assessment_of(record)
    if assessment is None or len(assessment.times) == 0:
        return {}
    person = record.person
    lifts = [_lift(lift, assessment) for lift in assessment.lifts]
    worst_lift = max(assessment.lifts, key=lambda lift: lift.lifting_index, default=None)
    return {
        "person": {"height": rounded(person.height), "mass": rounded(person.mass)},
        "period": rounded(record.setup.ergonomics.period),
        "rula": {
            "max": _worst(assessment, assessment.rula),
            "share_by_action_level": _shares(
                assessment, assessment.rula, action_level, ACTION_LEVELS
            ),
        },
        "reba": {
            "max": _worst(assessment, assessment.reba),
            "share_by_risk_level": _shares(assessment, assessment.reba, risk_level, RISK_LEVELS),
        },
        "lifts": lifts,
        "lifting_index_max": _worst_lift(worst_lift, assessment),
    }


def _worst(assessment: Assessment, scores: np.ndarray) -> dict:
    side, i = np.unravel_index(int(np.argmax(scores)), scores.shape)
    return {
        "score": int(scores[side, i]),
        "time": rounded(assessment.times[i]),
        "side": SIDES[side],
        "activity": assessment.activities[i],
    }


def _weights(times: np.ndarray) -> np.ndarray:
    """Each sample's share of the person's time (it stands for the time up to the next)."""
    if len(times) < 2:
        return np.ones(len(times))
    steps = np.diff(times)
    weights = np.append(steps, steps[-1])
    return weights / weights.sum()


def _shares(assessment: Assessment, scores: np.ndarray, level, levels) -> dict:
    """The fraction of the person's time at each level, by their worse side."""
    worse = scores.max(axis=0)
    weights = _weights(assessment.times)
    at = [level(int(score)) for score in worse]
    return {
        str(name): rounded(sum(w for w, a in zip(weights, at, strict=True) if a == name))
        for name in levels
    }


def _end(end) -> dict:
    return {
        "h": rounded(end.point.h, 3),
        "v": rounded(end.point.v, 3),
        "a": rounded(end.point.a, 3),
        "rwl": rounded(end.rwl, 4),
        "lifting_index": rounded(end.lifting_index, 4),
    }


def _lift(lift: Lift, assessment: Assessment) -> dict:
    """One lift, lengths in cm, angles in degrees, masses in kg."""
    origin, destination = _end(lift.origin), _end(lift.destination)
    return {
        "time": rounded(lift.time),
        "end_time": rounded(lift.end_time),
        "object": f"{lift.object.type} {lift.object.id}",
        "mass": rounded(lift.object.mass),
        "hands": lift.object.holder,
        "h": origin["h"],
        "v": origin["v"],
        "a": origin["a"],
        "d": rounded(lift.distance, 3),
        "frequency": rounded(lift.frequency, 4),
        "duration": lift.duration,
        "coupling": lift.coupling,
        "rwl": min(origin["rwl"], destination["rwl"]),
        "lifting_index": rounded(lift.lifting_index, 4),
        "origin": origin,
        "destination": destination,
        "notes": list(lift.notes),
        "activity": assessment.activities[_sample(assessment, lift.time)],
    }


def _sample(assessment: Assessment, t: float) -> int:
    return min(int(np.searchsorted(assessment.times, t)), len(assessment.times) - 1)


def _worst_lift(lift: Lift | None, assessment: Assessment) -> dict:
    if lift is None:
        return {}
    at_origin = lift.origin.lifting_index >= lift.destination.lifting_index
    return {
        "value": rounded(lift.lifting_index, 4),
        "time": rounded(lift.time if at_origin else lift.end_time),
        "end": "origin" if at_origin else "destination",
        "object": f"{lift.object.type} {lift.object.id}",
        "side": lift.object.holder,
        "activity": assessment.activities[_sample(assessment, lift.time)],
    }


def ergonomic_rows(record: RunRecord) -> dict[str, list[tuple[float, str]]]:
    """timeline.png rows: the RULA action level and REBA risk level of the worse side, as
    state changes."""
    assessment = assessment_of(record)
    if assessment is None:
        return {}
    rows = {}
    for name, scores, level in (
        (RULA_ROW, assessment.rula, lambda s: f"RULA AL{action_level(s)}"),
        (REBA_ROW, assessment.reba, lambda s: f"REBA {risk_level(s)}"),
    ):
        worse = scores.max(axis=0)
        rows[name] = _changes(assessment.times, [level(int(s)) for s in worse])
    return rows


def _changes(times: np.ndarray, labels: list[str]) -> list[tuple[float, str]]:
    return [
        (float(t), label)
        for i, (t, label) in enumerate(zip(times, labels, strict=True))
        if i == 0 or labels[i - 1] != label
    ]


LEVEL_COLOURS = ("#2e7d32", "#9ccc65", "#fbc02d", "#ef6c00", "#c62828")
"""From acceptable to act now: RULA's action levels 1-4, REBA's five risk levels."""


def ergonomics_html(record: RunRecord, metrics: dict) -> str:
    """report.html's section: the scores over time as strips coloured by level, the
    worst values and the lifts table."""
    assessment = assessment_of(record)
    section = metrics.get("ergonomics") or {}
    if assessment is None or not section:
        return ""
    end = float(record.setup.duration)
    rula_colours = [LEVEL_COLOURS[0], LEVEL_COLOURS[1], LEVEL_COLOURS[2], LEVEL_COLOURS[4]]
    strips = [
        _strip(
            "RULA", assessment, assessment.rula, lambda s: rula_colours[action_level(s) - 1], end
        ),
        _strip(
            "REBA",
            assessment,
            assessment.reba,
            lambda s: LEVEL_COLOURS[RISK_LEVELS.index(risk_level(s))],
            end,
        ),
    ]
    legends = [
        _legend([f"AL{level}" for level in ACTION_LEVELS], rula_colours),
        _legend(list(RISK_LEVELS), list(LEVEL_COLOURS)),
    ]
    worst = [
        [
            method,
            values["max"]["score"],
            values["max"]["time"],
            values["max"]["side"],
            values["max"]["activity"],
        ]
        for method, values in (("RULA", section["rula"]), ("REBA", section["reba"]))
    ]
    parts = [
        "<h2>Ergonomics</h2>",
        f"<p>Person: {section['person']['height']} m, {section['person']['mass']} kg. "
        "Scores of the worse side over time, coloured by level "
        "(RULA action levels 1-4, REBA risk levels negligible to very high).</p>",
        strips[0],
        legends[0],
        strips[1],
        legends[1],
        html_table(["method", "worst score", "time (s)", "side", "activity"], worst),
        _lifts_table(section["lifts"]),
    ]
    return "\n".join(parts)


def _strip(name: str, assessment: Assessment, scores: np.ndarray, colour, end: float) -> str:
    """An inline SVG bar: one rectangle per stretch of equal score, titled with it."""
    worse = scores.max(axis=0)
    times = assessment.times
    width, height = 1000.0, 18.0
    scale = width / max(end, 1e-9)
    rects = []
    for (start, label), stop in zip(
        _changes(times, [str(int(s)) for s in worse]),
        [t for t, _ in _changes(times, [str(int(s)) for s in worse])[1:]] + [end],
        strict=True,
    ):
        rects.append(
            f'<rect x="{start * scale:.1f}" y="0" width="{max((stop - start) * scale, 0.5):.1f}" '
            f'height="{height}" fill="{colour(int(label))}"><title>{name} {label} '
            f"at {start:.1f}-{stop:.1f} s</title></rect>"
        )
    return (
        f'<div class="ergonomics-strip"><b>{name}</b> '
        f'<svg viewBox="0 0 {width:.0f} {height:.0f}" width="100%" height="{height:.0f}" '
        f'preserveAspectRatio="none" role="img" aria-label="{name} over time">'
        + "".join(rects)
        + "</svg></div>"
    )


def _legend(names: list[str], colours: list[str]) -> str:
    swatches = [
        f'<span style="display:inline-block;width:12px;height:12px;background:{colour}">'
        f"</span> {escape(name)}"
        for name, colour in zip(names, colours, strict=True)
    ]
    return f'<div style="font-size:12px;margin:2px 0 8px">{" &nbsp; ".join(swatches)}</div>'


LIFT_COLUMNS = ("time", "object", "mass", "hands", "h", "v", "d", "a", "rwl", "lifting_index")


def _lifts_table(lifts: list[dict]) -> str:
    if not lifts:
        return "<p>No lifts: the person's hands took and put down nothing.</p>"
    header = [
        "time (s)",
        "object",
        "mass (kg)",
        "hands",
        "H (cm)",
        "V (cm)",
        "D (cm)",
        "A (deg)",
        "RWL (kg)",
        "lifting index",
        "notes",
    ]
    rows = [[lift[c] for c in LIFT_COLUMNS] + ["; ".join(lift["notes"])] for lift in lifts]
    return "<h3>Lifts (NIOSH)</h3>" + html_table(header, rows)
