"""Clips from key poses: the pose vocabulary, minimum-jerk easing, the turn on the spot and
the step back.

`keyed_clip` joins key poses (degrees / metres, overriding the relaxed stance) by
minimum-jerk segments (the bell-shaped speed profile of human reaching), adds optional
periodic layers (breathing, weight shift), then solves the legs by IK so that the soles stay
planted (or follow keyed foot placements, as when stepping round on the spot). Right-handed
variants and left/right step orders come from `mirror_pose`.

The person builds turns of any angle and steps back of any length with it while it runs
(`turn_clip`, `step_back_clip`), and eases every fade with `minimum_jerk`; the built-in clips
are authored with it offline (hrc_drake.modelgen.clips).
"""

from dataclasses import dataclass, field
from math import pi

import numpy as np
from pydrake.math import RotationMatrix

from hrc_drake.human.body import HumanBody, human_body
from hrc_drake.human.clip import LENGTH_JOINTS, Clip
from hrc_drake.human.legs import Legs
from hrc_drake.human.skeleton import LATERAL_CENTRAL_JOINTS, SIDES

FPS = 30.0
"""Frames a second of a keyed clip."""

RELAXED = {
    "shoulder_abduction": 8,
    "shoulder_flexion": 2,
    "elbow_flexion": 12,
    "wrist_flexion": 4,
    "neck_flexion": 3,
}
"""Standing at ease: arms hang just clear of the thighs, elbows soft."""

HOLD = {
    "shoulder_flexion": 0,
    "shoulder_abduction": 6,
    "shoulder_rotation": 8,
    "elbow_flexion": 85,
    "wrist_flexion": -5,
    "neck_flexion": 10,
}
"""Both hands hold an object in front of the belly (carrying, between pick and place): the
upper arms hanging, the elbows bent (the carry posture, hrc_drake.human.grasp)."""


@dataclass(frozen=True)
class Key:
    """A key pose at `time`: joint overrides, and optional foot placements per side.

    A foot placement is (yaw_deg, lift_m) or (yaw_deg, lift_m, ahead_m): the sole's
    standing place turned about the pelvis by yaw, raised by lift and moved ahead (stepping
    round on the spot, or back).
    """

    time: float
    joints: dict = field(default_factory=dict)
    feet: dict = field(default_factory=dict)


@dataclass(frozen=True)
class Layer:
    """An additive sinusoid (breathing, sway): amplitude in degrees or metres."""

    joint: str
    amplitude: float
    cycles: int
    phase: float = 0.0


@dataclass(frozen=True)
class KeyedSpec:
    name: str
    description: str
    keys: tuple[Key, ...]
    events: dict = field(default_factory=dict)
    loop: bool = False
    layers: tuple[Layer, ...] = ()


def expand(joints: dict) -> dict:
    """Joint overrides with unsided names (e.g. `elbow_flexion`) set on both sides."""
    expanded = {}
    for name, value in joints.items():
        if name.startswith(("left_", "right_")) or name in _central_names():
            expanded[name] = value
        else:
            for side in SIDES:
                expanded[f"{side}_{name}"] = value
    return expanded


def _central_names() -> set[str]:
    return {n for n in human_body().joint_names if not n.startswith(("left_", "right_"))}


def pose_vector(body: HumanBody, *layers: dict) -> np.ndarray:
    """Canonical joint vector of the standing pose overridden by each layer in turn."""
    q = body.standing_pose()
    for layer in layers:
        for name, value in expand(layer).items():
            q[body.index(name)] = value if name in LENGTH_JOINTS else np.radians(value)
    return q


def mirror_pose(body: HumanBody, q: np.ndarray) -> np.ndarray:
    """Left/right mirror image of a pose: swap sides, negate lateral midline joints."""
    mirrored = q.copy()
    for i, name in enumerate(body.joint_names):
        if name.startswith("left_"):
            j = body.index("right_" + name[5:])
            mirrored[i], mirrored[j] = q[j], q[i]
        elif name in LATERAL_CENTRAL_JOINTS:
            mirrored[i] = -q[i]
    return mirrored


def minimum_jerk(s):
    """Ease from 0 to 1 as s goes from 0 to 1 (clamped): zero speed and acceleration at both
    ends. Arrays or floats; a float stays a plain float, which is several times quicker than
    a 0-d array (the person's update eases a few scalars at every update)."""
    s = min(max(s, 0.0), 1.0) if isinstance(s, float) else np.clip(s, 0.0, 1.0)
    return s**3 * (10 - 15 * s + 6 * s**2)


def fade(elapsed: float, duration: float) -> float:
    """1 at the start of a fade, 0 at its end, minimum-jerk in between."""
    return 1.0 - minimum_jerk(elapsed / duration)


def _interpolate_keys(times: np.ndarray, key_times, key_values) -> np.ndarray:
    """Minimum-jerk segments between consecutive keys (values: one row per key)."""
    key_times = np.asarray(key_times)
    segment = np.clip(np.searchsorted(key_times, times, side="right") - 1, 0, len(key_times) - 2)
    t0, t1 = key_times[segment], key_times[segment + 1]
    s = minimum_jerk((times - t0) / np.maximum(t1 - t0, 1e-9))
    v0, v1 = key_values[segment], key_values[segment + 1]
    return v0 + (v1 - v0) * s[:, None]


def _foot_placements(body: HumanBody, keys: tuple[Key, ...], times: np.ndarray) -> dict:
    """Per side, per frame: (yaw, lift, ahead) of the sole, keyed like the joints (default
    planted)."""
    placements = {}
    for side in SIDES:
        values, last = [], (0.0, 0.0, 0.0)
        for key in keys:
            last = (*key.feet.get(side, last), 0.0)[:3]
            values.append((np.radians(last[0]), last[1], last[2]))
        placements[side] = _interpolate_keys(times, [k.time for k in keys], np.array(values))
    return placements


def _sole_target(body: HumanBody, side: str, yaw: float, lift: float, ahead: float):
    sign = 1 if side == "left" else -1
    standing = np.array(
        [body.sizes["foot"] / 2 - body.sizes["heel_back"], sign * body.sizes["hip_half_width"], 0.0]
    )
    rotation = RotationMatrix.MakeZRotation(yaw)
    return rotation @ standing + np.array([ahead, 0.0, lift]), rotation


SOFT_KNEES = 0.006
"""Stand 6 mm lower than with locked knees: a straight knee is singular, and a person at ease
does not lock their knees."""


def plant_feet(body: HumanBody, frames: np.ndarray, placements: dict) -> np.ndarray:
    """Solve both legs in every frame (in closed form) so each sole sits flat at its
    placement."""
    legs = Legs(body)
    planted = frames.copy()
    for k in range(len(frames)):
        for side in SIDES:
            position, rotation = _sole_target(body, side, *placements[side][k])
            planted[k] = legs.solve(planted[k], side, position, rotation.matrix()[:, 0])
    return planted


def keyed_clip(body: HumanBody, spec: KeyedSpec) -> Clip:
    """Build a clip from key poses (see module docstring)."""
    duration = spec.keys[-1].time
    times = np.arange(round(duration * FPS) + 1) / FPS
    key_poses = np.array([pose_vector(body, RELAXED, key.joints) for key in spec.keys])
    frames = _interpolate_keys(times, [k.time for k in spec.keys], key_poses)
    frames[:, body.index("pelvis_height")] -= SOFT_KNEES
    for layer in spec.layers:
        i = body.index(layer.joint)
        scale = 1.0 if layer.joint in LENGTH_JOINTS else np.radians(1.0)
        wave = np.sin(2 * pi * (layer.cycles * times / duration + layer.phase))
        frames[:, i] += scale * layer.amplitude * wave
    frames = plant_feet(body, frames, _foot_placements(body, spec.keys, times))
    return Clip(
        spec.name,
        body.joint_names,
        frames,
        FPS,
        spec.loop,
        dict(spec.events),
        description=spec.description,
    )


def mirrored_clip(body: HumanBody, clip: Clip, name: str, description: str) -> Clip:
    frames = np.array([mirror_pose(body, q) for q in clip.frames])
    return Clip(
        name,
        clip.joint_names,
        frames,
        clip.fps,
        clip.loop,
        dict(clip.events),
        clip.animation_distance,
        description,
    )


def _step_keys(step: float, degrees: float, ahead: float, lift: float) -> tuple[Key, ...]:
    """Two steps on the spot, turning left by `degrees` and moving `ahead` (m): left foot,
    then right foot, body between. Each foot rises before it moves and moves before it comes
    down, so that it never twists or slides on the floor."""
    keys = [Key(0.0, {"base_yaw": 0, "base_x": 0}, {"left": (0, 0), "right": (0, 0)})]
    for k, side in enumerate(("left", "right")):
        start = k * step
        for fraction, (moved, raised) in zip(
            (0.2, 0.85, 1.0), ((0.0, lift), (1.0, lift), (1.0, 0.0)), strict=True
        ):
            body = {"base_yaw": (k + fraction) * degrees / 2, "base_x": (k + fraction) * ahead / 2}
            feet = {side: (moved * degrees, raised, moved * ahead)}
            keys.append(Key(start + fraction * step, body, feet))
    return tuple(keys)


TURN_STEP_TIME = 0.5
TURN_LIFT = 0.04


def turn_spec(name: str, degrees: float) -> KeyedSpec:
    """Two steps turning `degrees` left on the spot, looping (the built-in `turn_left` is
    one; `turn_clip` makes the others)."""
    return KeyedSpec(
        name,
        f"Two steps turning {degrees:g} degrees left on the spot (loops; one cycle turns "
        f"{degrees:g} degrees).",
        _step_keys(TURN_STEP_TIME, degrees, 0.0, TURN_LIFT),
        events={"left_step": 0.0, "right_step": TURN_STEP_TIME},
        loop=True,
    )


def turn_clip(body: HumanBody, degrees: float) -> Clip:
    """Two steps turning on the spot by `degrees` (negative: to the right, right foot
    first), the feet planted by IK like every keyed clip: a turn of any angle that does not
    skate."""
    clip = keyed_clip(body, turn_spec(f"turn_{abs(degrees):g}", abs(degrees)))
    if degrees >= 0:
        return clip
    return mirrored_clip(body, clip, f"turn_{degrees:g}", clip.description.replace("left", "right"))


def step_back_clip(body: HumanBody, distance: float) -> Clip:
    """Two steps straight back by `distance` (m), left foot first, the feet planted by IK:
    away from a shelf before turning with what the hands hold (its corners sweep round
    further ahead than they are held)."""
    spec = KeyedSpec(
        f"step_back_{distance:g}",
        f"Two steps straight back by {distance:g} m.",
        _step_keys(TURN_STEP_TIME, 0.0, -distance, TURN_LIFT),
    )
    return keyed_clip(body, spec)
