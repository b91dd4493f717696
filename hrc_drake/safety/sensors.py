"""The scenario's `safety.sensors:` section: the cell's safety sensors, which the monitor
sees the person through instead of knowing every point of their body (docs/safety.md).

- A laser scanner sweeps beams in a horizontal plane `height` above the floor from its
  `pose` ([x, y, yaw in degrees]): `angles_deg` relative to its yaw, one beam every
  `resolution_deg`, out to `range`. It scans every `scan_time` and reports a scan
  `response_time` after the person entered it at worst (a whole scan later, plus the rest:
  its multiple sampling and processing). Each beam's range is off by up to
  `measurement_error` (Z_d). Its `detection_capability` d is the smallest object it is
  rated to detect; its protective and warning `fields` are polygons on its scan plane.
- A light curtain is beams between two posts (`ends`, [x, y] each), one every
  `resolution` from `heights[0]` to `heights[1]` above the floor; it reports a beam
  interrupted at most `response_time` after the interruption, and nothing of where along
  the beam. Interrupted, it stops the robot (ISO 13855 places it so that the stop comes in
  time); clear again, it lets the robot go on (automatic restart: what is behind it, it
  does not see).

Field sets (`FieldSet`) switch with the robot's speed: the active set is the one with the
smallest `speed` (fraction of full speed) at least the robot's present one. Its protective
field occupied stops the robot; otherwise the robot may move as fast as the fastest set
whose fields are all clear allows (a warning field occupied slows it to the next slower
set's speed), and at `reduced_speed` where no set is clear.
"""

import math
from dataclasses import dataclass, field

import numpy as np

from hrc_drake.safety.iso13855 import horizontal_intrusion, orthogonal_intrusion
from hrc_drake.yaml_check import REQUIRED

Polygon = list[list[float]]


@dataclass
class FieldSet:
    """Protective and warning fields ([x, y] corners in the world, on the scan plane) for
    the robot moving at up to `speed` of full speed; an empty field watches nothing."""

    speed: float = 1.0
    protective: Polygon = field(default_factory=list)
    warning: Polygon = field(default_factory=list)


@dataclass
class LaserScanner:
    pose: list[float] = field(default_factory=list, metadata=REQUIRED)
    """[x, y, yaw_deg]: where the scanner stands, and where its angle 0 points"""
    height: float = 0.3
    angles_deg: list[float] = field(default_factory=lambda: [-135.0, 135.0])
    resolution_deg: float = 0.5
    range: float = 5.5
    scan_time: float = 0.04
    response_time: float = 0.08
    detection_capability: float = 0.07
    measurement_error: float = 0.05
    fields: list[FieldSet] = field(default_factory=list)

    @property
    def intrusion(self) -> float:
        """ISO 13855's C for its horizontal detection zone."""
        return horizontal_intrusion(self.height)

    @property
    def latency(self) -> float:
        """How long after a scan ends it is reported: the response time less the one scan
        the person may have entered just after."""
        return self.response_time - self.scan_time

    def origin(self) -> np.ndarray:
        x, y, _ = self.pose
        return np.array([x, y, self.height])

    def beam_angles(self) -> np.ndarray:
        """World yaw of every beam (rad), first to last."""
        low, high = self.angles_deg
        count = int(math.floor((high - low) / self.resolution_deg + 1e-9)) + 1
        return np.radians(self.pose[2] + low + self.resolution_deg * np.arange(count))

    def beam_directions(self) -> np.ndarray:
        """Unit vectors (beams × 3) of the beams, in the scan plane."""
        angles = self.beam_angles()
        return np.column_stack([np.cos(angles), np.sin(angles), np.zeros_like(angles)])


@dataclass
class LightCurtain:
    ends: list[list[float]] = field(default_factory=list, metadata=REQUIRED)
    """[[x, y], [x, y]]: the emitter's and the receiver's post"""
    heights: list[float] = field(default_factory=lambda: [0.3, 1.5])
    """m above the floor of the lowest and the highest beam"""
    resolution: float = 0.03
    response_time: float = 0.02

    @property
    def intrusion(self) -> float:
        """ISO 13855's C for an orthogonal approach."""
        return orthogonal_intrusion(self.resolution)

    @property
    def scan_time(self) -> float:
        """It reads its beams every response time and reports them at once."""
        return self.response_time

    @property
    def latency(self) -> float:
        return 0.0

    @property
    def measurement_error(self) -> float:
        """It measures no position: the beam itself is where the person is."""
        return 0.0

    def beam_heights(self) -> np.ndarray:
        low, high = self.heights
        count = int(math.floor((high - low) / self.resolution + 1e-9)) + 1
        return low + self.resolution * np.arange(count)

    def beam_starts(self) -> np.ndarray:
        """The beams' emitter ends (beams × 3)."""
        heights = self.beam_heights()
        x, y = self.ends[0]
        return np.column_stack([np.full_like(heights, x), np.full_like(heights, y), heights])

    def span(self) -> np.ndarray:
        """From the emitter to the receiver, on the floor (3)."""
        (x0, y0), (x1, y1) = self.ends
        return np.array([x1 - x0, y1 - y0, 0.0])


Sensor = LaserScanner | LightCurtain


@dataclass
class SensorsConfig:
    """The cell's safety sensors by name; none: the monitor knows the person's body."""

    scanners: dict[str, LaserScanner] = field(default_factory=dict)
    light_curtains: dict[str, LightCurtain] = field(default_factory=dict)
    reduced_speed: float = 0.3
    """fraction of full speed while a warning field is occupied in every field set"""
    speed_and_separation: bool = True
    """the robot also slows down for the nearest detection's distance (S_p with the
    sensor's response time, C and Z_d); false: only the fields act"""

    def all(self) -> dict[str, Sensor]:
        """Every sensor by name, scanners first (names are unique across both kinds)."""
        return {**self.scanners, **self.light_curtains}

    @property
    def present(self) -> bool:
        return bool(self.scanners or self.light_curtains)

    @property
    def response_time(self) -> float:
        """The slowest sensor's response time: how late the person may be reported."""
        return max(sensor.response_time for sensor in self.all().values())
