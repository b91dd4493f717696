"""Motion clips: joint trajectories sampled at a fixed frame rate, with events and a loop flag.

Frames hold every joint of the skeleton in canonical order and SI units. Between frames a
clip is interpolated with a Catmull-Rom spline (continuous joint speeds), clamped between
the two frames so that it never overshoots a joint limit. A looping clip's
last frame equals its first plus a constant root displacement (`root_shift`, the distance a
walk cycle covers), so it can be played forever without jumps.

Files (models/human/animations/<name>.json) store revolute joints in degrees and the base
translations in metres, one frame per line.
"""

import json
from dataclasses import dataclass, field, replace
from functools import cached_property, lru_cache
from math import floor
from pathlib import Path

import numpy as np

from hrc_drake.human.anthropometry import DEFAULT_HEIGHT
from hrc_drake.paths import resource_dir

LENGTH_JOINTS = ("base_x", "base_y", "pelvis_height")
"""Joints in metres; every other joint is an angle."""

ROOT_MOTION = ("base_x", "base_y", "base_yaw")
"""Joints a looping clip may advance per cycle (walking forwards, turning on the spot)."""


@dataclass(frozen=True, eq=False)
class Clip:
    """One animation. `events` maps a name to the clip time (s) at which it fires."""

    name: str
    joint_names: tuple[str, ...]
    frames: np.ndarray
    fps: float
    loop: bool = False
    events: dict[str, float] = field(default_factory=dict)
    animation_distance: float = 0.0
    description: str = ""

    @cached_property
    def duration(self) -> float:
        return (len(self.frames) - 1) / self.fps

    @cached_property
    def root_shift(self) -> np.ndarray:
        """Displacement of the root over one loop (zero for clips that stay in place)."""
        shift = np.zeros(self.frames.shape[1])
        if self.loop:
            for joint in ROOT_MOTION:
                i = self.joint_names.index(joint)
                shift[i] = self.frames[-1, i] - self.frames[0, i]
        return shift

    @cached_property
    def _spline(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Per frame interval k: Catmull-Rom coefficients (interval, power of s, joint) and the
        clamp bounds min/max(frame k, frame k + 1); one cycle, later cycles add root_shift.

        Computed once per clip, so that sampling (60 times a simulated second per person) is
        one small matrix product and a clamp rather than four frame look-ups and a spline.
        """
        k = np.arange(len(self.frames) - 1)
        p0, p1, p2, p3 = (self._frames_at(k + j) for j in (-1, 0, 1, 2))
        coefficients = 0.5 * np.stack(
            (2 * p1, p2 - p0, 2 * p0 - 5 * p1 + 4 * p2 - p3, 3 * p1 - p0 - 3 * p2 + p3), axis=1
        )
        return coefficients, np.minimum(p1, p2), np.maximum(p1, p2)

    def sample(self, t: float) -> np.ndarray:
        """Joint positions at clip time t; loops wrap (adding root_shift), others clamp."""
        coefficients, lower, upper = self._spline
        n = len(lower)
        cycles = 0
        if self.loop:
            cycles = floor(t / self.duration)
            u = (t - cycles * self.duration) * self.fps
        else:
            u = min(max(t, 0.0), self.duration) * self.fps
        k = min(floor(u), n - 1)
        s = u - k
        if k < 0:  # rounding put t a hair before its cycle: the previous cycle's last interval
            k, cycles = k + n, cycles - 1
        between = np.minimum(
            np.maximum((1.0, s, s * s, s * s * s) @ coefficients[k], lower[k]), upper[k]
        )
        return between + cycles * self.root_shift if cycles else between

    def _frames_at(self, k: np.ndarray) -> np.ndarray:
        """Frames k, extended past the ends: by wrapping for loops, by clamping otherwise."""
        n = len(self.frames) - 1
        if not self.loop:
            return self.frames[np.clip(k, 0, n)]
        cycles, index = np.divmod(k, n)
        return self.frames[index] + cycles[:, None] * self.root_shift


def animations_dir() -> Path:
    return resource_dir("models") / "human" / "animations"


def _angle_columns(joint_names) -> np.ndarray:
    return np.array([name not in LENGTH_JOINTS for name in joint_names])


def clip_to_json(clip: Clip) -> str:
    """File text: metadata, then one frame per line (degrees / metres, 5 decimals)."""
    stored = clip.frames.copy()
    angles = _angle_columns(clip.joint_names)
    stored[:, angles] = np.degrees(stored[:, angles])
    header = {
        "name": clip.name,
        "description": clip.description,
        "fps": clip.fps,
        "loop": clip.loop,
        "animation_distance": round(clip.animation_distance, 5),
        "events": {k: round(v, 5) for k, v in clip.events.items()},
        "units": "degrees; metres for base_x, base_y, pelvis_height",
        "joints": list(clip.joint_names),
    }
    body = json.dumps(header, indent=1)[:-2]
    rows = ",\n  ".join(json.dumps([round(float(v), 5) + 0.0 for v in row]) for row in stored)
    return f'{body},\n "frames": [\n  {rows}\n ]\n}}\n'


def clip_from_json(text: str) -> Clip:
    data = json.loads(text)
    joints = tuple(data["joints"])
    frames = np.array(data["frames"], dtype=float)
    angles = _angle_columns(joints)
    frames[:, angles] = np.radians(frames[:, angles])
    return Clip(
        name=data["name"],
        joint_names=joints,
        frames=frames,
        fps=float(data["fps"]),
        loop=bool(data["loop"]),
        events={k: float(v) for k, v in data["events"].items()},
        animation_distance=float(data["animation_distance"]),
        description=data.get("description", ""),
    )


def save_clip(clip: Clip, directory: Path | None = None) -> Path:
    path = (directory or animations_dir()) / f"{clip.name}.json"
    path.write_text(clip_to_json(clip))
    return path


def load_clip(path: Path) -> Clip:
    return clip_from_json(Path(path).read_text())


@lru_cache(maxsize=4)
def load_clips(directory: Path | None = None) -> dict[str, Clip]:
    """Every clip in the animations folder, by name (read once per process)."""
    folder = directory or animations_dir()
    return {path.stem: load_clip(path) for path in sorted(folder.glob("*.json"))}


def scaled_clips(clips: dict[str, Clip], height: float) -> dict[str, Clip]:
    """The clips for a person of another height: every length scales with body height."""
    factor = height / DEFAULT_HEIGHT
    if factor == 1.0:
        return clips
    scaled = {}
    for name, clip in clips.items():
        frames = clip.frames.copy()
        for joint in LENGTH_JOINTS:
            frames[:, clip.joint_names.index(joint)] *= factor
        scaled[name] = replace(
            clip, frames=frames, animation_distance=clip.animation_distance * factor
        )
    return scaled
