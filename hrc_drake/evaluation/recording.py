"""What replay.html animates, as the ReplayRecorder system samples it (`Recording`), and the
names both sides share: the robot's safety states and where Meshcat draws a frame.

Plain data, so that `hrc_drake.evaluation.replay` writes a replay from a run's record
without knowing the system that recorded it.
"""

from dataclasses import dataclass, field

import numpy as np

from hrc_drake.safety.messages import SafetyStatus

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


@dataclass
class Recording:
    """Samples at `times`: per Meshcat path its poses (rows x, y, z, qw, qx, qy, qz), the
    safety state, and the held workpieces as {object path: holder}."""

    times: list[float] = field(default_factory=list)
    poses: dict[str, list[np.ndarray]] = field(default_factory=dict)
    safety: list[str] = field(default_factory=list)
    held: list[dict[str, str]] = field(default_factory=list)

    def pose_array(self, path: str) -> np.ndarray:
        return np.array(self.poses[path])
