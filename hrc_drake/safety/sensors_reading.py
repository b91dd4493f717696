"""One reading of a safety sensor: what each of its beams met, as the SafetySensors system
takes it from the scene, and when the monitor may know it.

A laser scanner's reading holds each beam's measured range (off by up to its measurement
error, drawn from the run's seed) and whether the beam ended on the person; a light
curtain's the same for its beams, of which the monitor only learns which were interrupted.
The beams that end on the person are the sensor's detections: the cell's furniture is the
contour a scanner is taught, the robot (and what it holds) is masked by its known pose, and
objects only block the beams. A scanner evaluates its fields itself: the reading says which
of its field sets' fields the detections occupy.
"""

import functools
from dataclasses import dataclass

import numpy as np
import shapely

from hrc_drake.safety.sensors import FieldSet, LaserScanner, Sensor
from hrc_drake.safety.sensors_raycast import MISS, Solids, cast
from hrc_drake.seeding import substream

CLEAR, WARNING, PROTECTIVE = 0, 1, 2
FIELD_STATES = ("clear", "warning", "protective")
"""What a scanner's field set says, from nothing in it to its protective field occupied
(the index is the `field` safety signal)."""
SCAN_TOLERANCE = 1e-9
"""s: a reading due at the monitor's update time is reported then"""


@dataclass(frozen=True, eq=False)
class SensorReading:
    """One scan: `time` when taken, per beam its `ranges` (m along the beam, MISS where it
    met nothing in range) and whether it ended on the person (`person`); the detections as
    segments (`starts`, `spans`, × 3, world: a scanner's points on the person, spans 0; a
    light curtain's interrupted beams, whole: it does not know where along them); a
    scanner's field sets' states as it evaluates them (`fields`, CLEAR, WARNING or
    PROTECTIVE occupied, per set)."""

    time: float
    ranges: np.ndarray
    person: np.ndarray
    starts: np.ndarray
    spans: np.ndarray
    fields: tuple[int, ...] = ()

    @property
    def sees_person(self) -> bool:
        return bool(self.person.any())

    def __deepcopy__(self, memo):
        return self  # immutable: Drake's state copies may share it


def beams(sensor: Sensor) -> tuple[np.ndarray, np.ndarray, float]:
    """The sensor's beams: origins and unit directions (beams × 3) and their length."""
    if isinstance(sensor, LaserScanner):
        directions = sensor.beam_directions()
        return np.tile(sensor.origin(), (len(directions), 1)), directions, sensor.range
    starts = sensor.beam_starts()
    span = sensor.span()
    length = float(np.linalg.norm(span))
    return starts, np.tile(span / length, (len(starts), 1)), length


def contour(sensor: Sensor, shapes: Solids, poses: np.ndarray) -> np.ndarray:
    """Where the sensor's beams end on shapes that never move (the cell's furniture: the
    contour a scanner is taught), MISS where on none: per beam, m along it."""
    origins, directions, length = beams(sensor)
    return cast(origins, directions, length, shapes, poses, _fan(sensor))[0]


def _fan(sensor: Sensor) -> np.ndarray | None:
    """A scanner's beams' yaws, which `cast` finds the shapes they pass by."""
    return sensor.beam_angles() if isinstance(sensor, LaserScanner) else None


def take_reading(
    sensor: Sensor,
    time: float,
    shapes: Solids,
    poses: np.ndarray,
    person: np.ndarray,
    noise: np.random.SeedSequence,
    scan: int,
    still: np.ndarray | None = None,
) -> SensorReading:
    """The reading of scan number `scan` at `time` of the `shapes` at `poses` (shapes × 3
    × 4) before the `still` contour (`contour`, of the shapes that never move; None: all
    shapes are among `shapes`): `person` flags the shapes of the person's body; `noise` is
    the sensor's stream (scan `scan` draws from its substream)."""
    origins, directions, length = beams(sensor)
    ranges, which = cast(origins, directions, length, shapes, poses, _fan(sensor))
    on_person = (which >= 0) & person[np.maximum(which, 0)]
    if still is not None:
        on_person &= ranges < still
        ranges = np.minimum(ranges, still)
    met = np.isfinite(ranges)
    if sensor.measurement_error > 0.0:
        rng = np.random.default_rng(substream(noise, scan))
        error = rng.uniform(-1.0, 1.0, len(ranges)) * sensor.measurement_error
        ranges = np.where(met, np.maximum(ranges + error, 0.0), MISS)
    ranges.flags.writeable = False
    on_person.flags.writeable = False
    if isinstance(sensor, LaserScanner):
        starts = origins[on_person] + ranges[on_person, None] * directions[on_person]
        spans = np.zeros_like(starts)
        fields = tuple(occupied_field(field_set, starts) for field_set in sensor.fields)
        return SensorReading(time, ranges, on_person, starts, spans, fields)
    starts, spans = origins[on_person], length * directions[on_person]
    return SensorReading(time, ranges, on_person, starts, spans)


def occupied_field(field_set: FieldSet, points: np.ndarray) -> int:
    """Whether any of `points` (× 3) lies in the set's protective or warning field."""
    if not len(points):
        return CLEAR
    for state, corners in ((PROTECTIVE, field_set.protective), (WARNING, field_set.warning)):
        if len(corners) < 3:
            continue
        polygon = _prepared(tuple(map(tuple, corners)))
        if shapely.contains_xy(polygon, points[:, 0], points[:, 1]).any():
            return state
    return CLEAR


@functools.lru_cache(maxsize=256)
def _prepared(corners: tuple) -> shapely.Polygon:
    """A field's polygon, prepared for many point tests (made once per field)."""
    polygon = shapely.Polygon(corners)
    shapely.prepare(polygon)
    return polygon


def reported(history: tuple[SensorReading, ...], time: float, latency: float):
    """The newest reading of `history` (oldest first) the sensor has reported by `time`,
    `latency` after it was taken; None before its first."""
    due = time - latency + SCAN_TOLERANCE
    return next((r for r in reversed(history) if r.time <= due), None)


def kept(history: tuple[SensorReading, ...], reading: SensorReading, latency: float) -> tuple:
    """The history with `reading` added, less the readings nobody will be told of again (all
    before the newest one already due at the new reading's time)."""
    history = (*history, reading)
    due = reading.time - latency + SCAN_TOLERANCE
    first = max((k for k, r in enumerate(history) if r.time <= due), default=0)
    return history[first:]
