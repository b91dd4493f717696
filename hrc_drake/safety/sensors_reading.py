"""One reading of a safety sensor: what each of its beams met, as the SafetySensors system
takes it from the scene, and when the monitor may know it.

A laser scanner's reading holds each beam's measured range (off by up to its measurement
error, drawn from the run's seed) and whether the beam ended on the person; a light
curtain's the same for its beams, of which the monitor only learns which were interrupted.
The beams that end on the person are the sensor's detections: the cell's furniture is the
contour a scanner is taught, the robot (and what it holds) is masked by its known pose, and
objects only block the beams.
"""

from dataclasses import dataclass

import numpy as np

from hrc_drake.safety.sensors import LaserScanner, LightCurtain, Sensor
from hrc_drake.safety.sensors_raycast import MISS, Solids, cast
from hrc_drake.seeding import substream

SCAN_TOLERANCE = 1e-9
"""s: a reading due at the monitor's update time is reported then"""


@dataclass(frozen=True, eq=False)
class SensorReading:
    """One scan: `time` when taken, per beam its `ranges` (m along the beam, MISS where it
    met nothing in range) and whether it ended on the person (`person`)."""

    time: float
    ranges: np.ndarray
    person: np.ndarray

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


def take_reading(
    sensor: Sensor,
    time: float,
    shapes: Solids,
    poses: np.ndarray,
    person: np.ndarray,
    noise: np.random.SeedSequence,
    scan: int,
) -> SensorReading:
    """The reading of scan number `scan` at `time` of the `shapes` at `poses` (shapes × 3
    × 4): `person` flags the shapes of the person's body; `noise` is the sensor's stream
    (scan `scan` draws from its substream)."""
    origins, directions, length = beams(sensor)
    fan = sensor.beam_angles() if isinstance(sensor, LaserScanner) else None
    ranges, which = cast(origins, directions, length, shapes, poses, fan)
    met = which >= 0
    on_person = met & person[np.maximum(which, 0)]
    if sensor.measurement_error > 0.0:
        rng = np.random.default_rng(substream(noise, scan))
        error = rng.uniform(-1.0, 1.0, len(ranges)) * sensor.measurement_error
        ranges = np.where(met, np.maximum(ranges + error, 0.0), MISS)
    ranges.flags.writeable = False
    on_person.flags.writeable = False
    return SensorReading(time, ranges, on_person)


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


def person_points(scanner: LaserScanner, reading: SensorReading) -> np.ndarray:
    """Where the scanner's beams met the person (points × 3, world), as measured."""
    origins, directions, _ = beams(scanner)
    hits = reading.person
    return origins[hits] + reading.ranges[hits, None] * directions[hits]


def interrupted_beams(curtain: LightCurtain, reading: SensorReading) -> np.ndarray:
    """The beams the person interrupts, whole (beams × 3 × 2: start and end): the curtain
    does not know where along a beam."""
    origins, directions, length = beams(curtain)
    hits = reading.person
    return np.stack([origins[hits], origins[hits] + length * directions[hits]], axis=2)
