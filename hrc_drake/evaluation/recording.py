"""What replay.html animates, as the ReplayRecorder system samples it (`Recording`), and the
names both sides share: the robot's safety states, the safety sensors' states, and where
Meshcat draws a frame.

Plain data, so that `hrc_drake.evaluation.replay` writes a replay from a run's record
without knowing the system that recorded it.
"""

from dataclasses import dataclass, field

import numpy as np

from hrc_drake.safety.messages import SafetyStatus
from hrc_drake.safety.sensors_view import SensorView

MESHCAT_ROOT = "/drake"

FULL_SPEED, REDUCED, STOPPED = "full speed", "reduced speed", "stopped"


def safety_state(status: SafetyStatus) -> str:
    """The robot's state as the monitor commands it: full speed, reduced or stopped."""
    if status.scale >= 1.0:
        return FULL_SPEED
    return STOPPED if status.scale <= 0.0 else REDUCED


def meshcat_path(prefix: str, frame_name: str) -> str:
    """Where MeshcatVisualizer draws a SceneGraph frame (MultibodyPlant's `::` -> `/`)."""
    return f"{MESHCAT_ROOT}/{prefix}/{frame_name.replace('::', '/')}"


@dataclass(frozen=True)
class SensorSample:
    """One safety sensor at one sample: its active field set and that set's state (a
    scanner's; -1 and CLEAR for a light curtain), and whether it sees the person."""

    name: str
    field_set: int
    field_state: int
    seen: bool


def sensor_samples(views: tuple[SensorView, ...]) -> tuple[SensorSample, ...]:
    return tuple(SensorSample(v.name, v.field_set, v.field_state, v.seen) for v in views)


def detections(views: tuple[SensorView, ...]) -> np.ndarray:
    """Where the sensors see the person (points × 3): a scanner's points on them, a light
    curtain's interrupted beams' middles."""
    return np.concatenate([np.zeros((0, 3)), *(v.detections for v in views)])


@dataclass
class Recording:
    """Samples at `times`: per Meshcat path its poses (rows x, y, z, qw, qx, qy, qz), the
    safety state, the held workpieces as {object path: holder}, and with safety sensors
    each sensor's state and where they saw the person."""

    times: list[float] = field(default_factory=list)
    poses: dict[str, list[np.ndarray]] = field(default_factory=dict)
    safety: list[str] = field(default_factory=list)
    held: list[dict[str, str]] = field(default_factory=list)
    sensors: list[tuple[SensorSample, ...]] = field(default_factory=list)
    detections: list[np.ndarray] = field(default_factory=list)

    def pose_array(self, path: str) -> np.ndarray:
        return np.array(self.poses[path])
