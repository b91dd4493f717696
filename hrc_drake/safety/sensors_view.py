"""What the monitor makes of its sensors' readings (docs/safety.md): per sensor, how far the
nearest detection of the person is from the robot, and which of its fields are occupied.

Separations are horizontal, as ISO 13855 measures a detection zone's distance from the
hazard: from each point where a scanner's beam met the person (or each light-curtain beam
the person interrupts, all of it) to the robot's parts' bounding capsules (hrc_drake.safety.
geometry, as the proximity meter places them), all projected onto the floor. A projected
distance is never longer than the distance in space, and a capsule holds its part, so the
sensed separation errs on the near side; what the sensor cannot see of the body (an arm
reaching over the scan plane) is ISO 13855's intrusion distance C, which S_p adds.
"""

import math
from dataclasses import dataclass, field

import numpy as np

from hrc_drake.safety.kernels import segment_distances
from hrc_drake.safety.sensors import FieldSet, LaserScanner, Sensor, SensorsConfig
from hrc_drake.safety.sensors_reading import CLEAR, PROTECTIVE, SensorReading, reported


@dataclass(frozen=True, eq=False)
class SensorView:
    """One sensor's reported reading as the monitor reads it."""

    name: str
    separation: float = math.inf
    """m from the nearest detection of the person to the robot, on the floor (inf: not
    seen, or nothing reported yet)"""
    field_set: int = -1
    """index of the active field set (-1: the sensor has none)"""
    field_state: int = CLEAR
    """the active set's state: CLEAR, WARNING or PROTECTIVE occupied (a light curtain:
    PROTECTIVE while interrupted)"""
    speed_limit: float = 1.0
    """the fraction of full speed its fields allow (`field_limit`)"""
    detections: np.ndarray = field(default_factory=lambda: np.zeros((0, 3)))
    """a scanner's points on the person, a light curtain's interrupted beams' mid points"""
    reported: bool = False
    """the sensor has reported a reading"""

    @property
    def seen(self) -> bool:
        return math.isfinite(self.separation)


def active_set(fields: list[FieldSet], speed_fraction: float) -> int:
    """The field set for a robot at `speed_fraction` of full speed: the one with the least
    `speed` at least that (the fastest set beyond the fastest speed); -1 without fields."""
    if not fields:
        return -1
    ranked = sorted(range(len(fields)), key=lambda k: fields[k].speed)
    return next((k for k in ranked if fields[k].speed >= speed_fraction), ranked[-1])


def field_limit(fields: list[FieldSet], states: list[int], active: int, reduced: float) -> float:
    """The speed the fields allow: none with the active set's protective field occupied,
    else the fastest set's whose fields are all clear (so that the robot speeds up only
    where the faster set's fields are clear too), else `reduced` (a warning field occupied
    in every set)."""
    if active < 0:
        return 1.0
    if states[active] == PROTECTIVE:
        return 0.0
    clear = [f.speed for f, state in zip(fields, states, strict=True) if state == CLEAR]
    return max(clear, default=reduced)


def horizontal_separation(starts, spans, capsules) -> float:
    """Least floor distance from the segments (× 3; points have no span) to the capsules."""
    if not len(starts):
        return math.inf
    cap_starts, cap_spans, radii = capsules
    flat = np.array([1.0, 1.0, 0.0])
    distances = segment_distances(starts * flat, spans * flat, cap_starts * flat, cap_spans * flat)
    return float(max((distances - radii[None, :]).min(), 0.0))


def sensor_view(
    name: str,
    sensor: Sensor,
    reading: SensorReading | None,
    capsules,
    speed_fraction: float,
    reduced_speed: float,
) -> SensorView:
    """What `reading` (None: nothing reported yet) tells of the person near the robot's
    `capsules` moving at `speed_fraction` of full speed (`reduced_speed`: what a warning
    field allows)."""
    if reading is None:
        return SensorView(name)
    if isinstance(sensor, LaserScanner):
        chosen = active_set(sensor.fields, speed_fraction)
        state = reading.fields[chosen] if chosen >= 0 else CLEAR
        limit = field_limit(sensor.fields, list(reading.fields), chosen, reduced_speed)
    else:  # a trip device: interrupted, it stops the robot, as if its protective field
        chosen = -1
        state, limit = (PROTECTIVE, 0.0) if reading.sees_person else (CLEAR, 1.0)
    starts, spans = reading.starts, reading.spans
    separation = horizontal_separation(starts, spans, capsules) if len(starts) else math.inf
    points = starts + spans / 2
    return SensorView(name, separation, chosen, state, limit, points, reported=True)


def view(
    config: SensorsConfig, histories: dict, time: float, capsules, speed_fraction: float
) -> tuple[SensorView, ...]:
    """Every sensor's view at `time` of its history of readings (`histories` by name), the
    robot's parts being the bounding `capsules` (starts, spans, radii) and moving at
    `speed_fraction` of full speed."""
    return tuple(
        sensor_view(
            name,
            sensor,
            reported(histories.get(name, ()), time, sensor.latency),
            capsules,
            speed_fraction,
            config.reduced_speed,
        )
        for name, sensor in config.all().items()
    )
