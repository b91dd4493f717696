"""Run metrics for report.json, from the robot's logged state, the monitor's final status
and logged signals and, when the scenario has them, the behavior trees' task events and
node statistics.

Every value is rounded (`rounded`) so the report is byte-identical for the same scenario and
seed. Sections whose source is absent are empty, never missing.
"""

import math

import numpy as np

from hrc_drake.messages import TaskEvent
from hrc_drake.motion.messages import IDLE
from hrc_drake.safety.log import signal
from hrc_drake.safety.messages import ContactRecord, SafetyStatus, ViolationEpisode
from hrc_drake.safety.ssm import ZONES

WAITING_SPEED = 0.05
"""m/s of the pelvis below which the person counts as waiting (standing)."""
SECONDS_PER_HOUR = 3600.0
PLACE_SQUARE = 0.25
"""m: the side of the floor squares in which where the person stood is counted."""


def rounded(x: float, digits: int = 9):
    """Stable across platforms' last-bit differences; infinities and NaN become None."""
    x = float(x)
    return round(x, digits) + 0.0 if math.isfinite(x) else None


def robot_metrics(variant: str, initial: tuple[float, ...], states: np.ndarray) -> dict:
    """How far the arm strayed from its initial joint positions (`initial`, rad), and where
    it ended; `states` are its logged states (positions, then velocities; x samples)."""
    q = states[: len(initial)]
    deviation = np.abs(q - np.array(initial)[:, None]).max() if q.size else 0.0
    return {
        "variant": variant,
        "max_deviation_from_initial_rad": rounded(deviation),
        "final_joint_positions_rad": [rounded(x) for x in q[:, -1]],
    }


def safety_metrics(status: SafetyStatus | None, moving_speed: float) -> dict:
    """The monitor's totals; a robot counts as moving above `moving_speed` (m/s)."""
    if status is None:
        return {}
    totals = status.totals
    records = totals.contact_records
    worst = totals.worst_contact
    return {
        "ssm_enabled": status.ssm_enabled,
        "min_separation": {
            "distance": rounded(totals.min_separation),
            "region": totals.min_separation_region,
            "link": totals.min_separation_link,
            "time": rounded(totals.min_separation_time),
        },
        "time_reduced": rounded(totals.reduced_time),
        "time_stopped": rounded(totals.stopped_time),
        "stops": totals.stops,
        "ssm_violations": {
            "count": totals.violations,
            "moving_speed": rounded(moving_speed),
            "duration": rounded(totals.violation_time),
            "worst_deficit": rounded(totals.worst_deficit),
            "episodes": [_episode(e) for e in totals.violation_episodes],
        },
        "contacts": {
            "count": totals.contacts,
            "robot_moving": totals.robot_contacts,
            "robot_at_rest": totals.contacts - totals.robot_contacts,
            "duration": rounded(totals.contact_time),
            "violations": totals.contact_violations,
            "worst_region": worst.worst.region if worst else "",
            "max_force_ratio": rounded(max((r.worst.force_ratio for r in records), default=0)),
            "max_pressure_ratio": rounded(
                max((r.worst.pressure_ratio for r in records), default=0)
            ),
            "max_force": rounded(max((r.worst.force for r in records), default=0)),
            "max_pressure": rounded(max((r.worst.pressure for r in records), default=0)),
            "list": [_contact(r) for r in records],
        },
    }


def _episode(episode: ViolationEpisode) -> dict:
    return {
        "start": rounded(episode.start),
        "end": rounded(episode.end),
        "region": episode.region,
        "part": episode.part,
        "separation": rounded(episode.separation),
        "protective": rounded(episode.protective),
        "deficit": rounded(episode.deficit),
    }


def _contact(record: ContactRecord) -> dict:
    """One contact: when, where, its worst update's figures, and who moved into whom."""
    c = record.worst
    return {
        "start": rounded(record.start),
        "end": rounded(record.end),
        "region": c.region,
        "part": c.part,
        "kind": c.kind,
        "relative_speed": rounded(c.relative_speed),
        "force": rounded(c.force),
        "pressure": rounded(c.pressure),
        "force_limit": rounded(c.force_limit),
        "pressure_limit": rounded(c.pressure_limit),
        "force_ratio": rounded(c.force_ratio),
        "pressure_ratio": rounded(c.pressure_ratio),
        "robot_moving": record.robot_moving,
        "violation": record.violation,
    }


def utilisation_metrics(
    times: np.ndarray, signals: np.ndarray, moving_speed: float, robot_modes: list
) -> dict:
    """Fractions of the run the robot moved, waited (still, and not stopped with a move to
    make) or was stopped by the safety function with a move under way or pending, and where
    the person stood most of the time it was stopped (`stopped_with_person_at`).
    `robot_modes` are RobotMotion's (time, mode) changes."""
    if times.size < 2:
        return {}
    dt = np.diff(times)
    moving = signal(signals, "robot_speed")[:-1] > moving_speed
    held = signal(signals, "zone")[:-1] == ZONES.index("stopped")
    stopped = held & ~moving & _had_a_move(times[:-1], robot_modes)
    total = dt.sum()
    fractions = {
        "moving": rounded(dt[moving].sum() / total),
        "waiting": rounded(dt[~moving & ~stopped].sum() / total),
        "stopped": rounded(dt[stopped].sum() / total),
    }
    place = _most_stood_at(dt, stopped, signals)
    return fractions if place is None else {**fractions, "stopped_with_person_at": place}


def _had_a_move(times: np.ndarray, robot_modes: list) -> np.ndarray:
    """At each of `times`, whether the robot had a move under way or pending (its mode was
    not idle): a stop costs production only then. A robot whose tree waited the whole run
    was "stopped 100 % of the run" with the person beside it, as if they held it up (#26)."""
    changes = np.array([t for t, _ in robot_modes])
    # busy[k]: from the k-th change on (busy[0]: before the first, when nothing was known)
    busy = np.array([False] + [mode != IDLE for _, mode in robot_modes])
    return busy[np.searchsorted(changes, times, side="right")]


def _most_stood_at(dt: np.ndarray, when: np.ndarray, signals: np.ndarray) -> list | None:
    """Where the person's pelvis was for the longest part of the samples `when` (the mean
    over the PLACE_SQUARE square they spent longest in; None: not known then). A user's
    robot stood stopped 95 % of a run because the person waited for it within its reach,
    and the summary gave no hint of where."""
    xy = np.stack([signal(signals, "person_x"), signal(signals, "person_y")])[:, :-1]
    kept = when & np.all(np.isfinite(xy), axis=0)
    if not kept.any():
        return None
    xy, dt = xy[:, kept], dt[kept]
    _, square = np.unique(np.floor(xy / PLACE_SQUARE), axis=1, return_inverse=True)
    square = square.ravel()
    longest = square == np.argmax(np.bincount(square, weights=dt))
    return [rounded(v, 3) for v in xy[:, longest] @ dt[longest] / dt[longest].sum()]


def person_metrics(times: np.ndarray, signals: np.ndarray) -> dict:
    """The person's walking distance (the pelvis's path along the floor) and time standing
    still (the pelvis slower than WAITING_SPEED)."""
    xy = np.stack([signal(signals, "person_x"), signal(signals, "person_y")])
    known = np.all(np.isfinite(xy), axis=0)
    if times.size < 2 or not known.any():
        return {}
    steps = np.linalg.norm(np.diff(xy[:, known], axis=1), axis=0)
    dt = np.diff(times)
    still = (signal(signals, "walking_speed")[1:] < WAITING_SPEED) & known[1:]
    return {"walking_distance": rounded(steps.sum()), "waiting_time": rounded(dt[still].sum())}


GROUND_TRUTH = "ground truth"
SENSORS = "safety sensors"


def sensing_metrics(
    times: np.ndarray, signals: np.ndarray, status: SafetyStatus, sensors: tuple[str, ...]
) -> dict:
    """What the monitor saw the person through: `ground truth` (every point of their body)
    or `safety sensors` (by name), and then how long the sensors saw them."""
    if status.sensing is None:
        return {"by": GROUND_TRUTH}
    seen = signal(signals, "seen")[:-1] > 0.0
    dt = np.diff(times)
    return {
        "by": SENSORS,
        "sensors": list(sensors),
        "time_seen": rounded(dt[seen].sum()),
        "time_not_seen": rounded(dt[~seen].sum()),
    }


def task_metrics(events: list[TaskEvent], duration: float, names=()) -> dict:
    """Counts of each task event and their rate per hour of simulated time; those `names`
    that never happened count 0."""
    counts: dict[str, int] = dict.fromkeys(names, 0)
    for event in events:
        counts[event.name] = counts.get(event.name, 0) + 1
    hours = duration / SECONDS_PER_HOUR
    return {
        "events": dict(sorted(counts.items())),
        "throughput_per_hour": {name: rounded(n / hours) for name, n in sorted(counts.items())},
    }


def bt_metrics(node_statistics: dict | None) -> dict:
    """Per agent, per node statistics as the BehaviorTreeSystem reports them."""
    return _rounded_tree(node_statistics or {})


WHY_NODES_FAIL = (
    "(an actor refused or could not carry out a command, "
    "or a NextObject found only objects with others lying on them)"
)
"""The reasons a node gives for failing (`node_failures`), as the run's summary says them."""


def node_failures(bt: dict) -> list[str]:
    """One line per tree node that failed with a reason (WHY_NODES_FAIL): which node, how
    often, the first reason; most frequent first."""
    failed = [
        (counts["failures"], agent, path, counts["first_failure"])
        for agent, nodes in bt.items()
        for path, counts in nodes.items()
        if counts.get("first_failure")
    ]
    return [
        f"{agent} {path}: failed {n} time{'s' if n != 1 else ''}, first: {reason}"
        for n, agent, path, reason in sorted(failed, key=lambda f: (-f[0], f[1], f[2]))
    ]


def flatten(metrics: dict, prefix: str = "") -> dict:
    """Nested metrics → `{"a.b.c": value}`; lists stay whole."""
    flat = {}
    for name, value in metrics.items():
        path = f"{prefix}{name}"
        if isinstance(value, dict):
            flat.update(flatten(value, f"{path}."))
        else:
            flat[path] = value
    return flat


def _rounded_tree(value):
    if isinstance(value, dict):
        return {str(k): _rounded_tree(v) for k, v in sorted(value.items())}
    if isinstance(value, float):
        return rounded(value)
    return value
