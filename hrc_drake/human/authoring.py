"""Author the built-in clips from key poses and published gait figures.

`python -m hrc_drake.human.authoring` rewrites models/human/animations/*.json.

Two builders make every clip:
- `keyed_clip`: key poses (degrees / metres, overriding the relaxed stance) joined by
  minimum-jerk segments (the bell-shaped speed profile of human reaching), plus optional
  periodic layers (breathing, weight shift); then the legs are solved by IK so that the soles
  stay planted (or follow keyed foot placements, as when stepping round on the spot).
- `gait_clip`: hip, knee and ankle angle curves through the published key points of one gait
  cycle, the right leg half a cycle behind the left; the pelvis height and forward travel are
  then derived from the kinematics so that whichever sole point touches the floor stays put.
Right-handed variants and left/right step orders come from `mirror_pose`.
"""

import sys
from dataclasses import dataclass, field
from math import pi

import numpy as np
from pydrake.math import RotationMatrix

from hrc_drake.human.body import FrameTask, HumanBody, human_body
from hrc_drake.human.clip import LENGTH_JOINTS, Clip, save_clip
from hrc_drake.human.skeleton import LATERAL_CENTRAL_JOINTS, SIDES

FPS = 30.0

RELAXED = {
    "shoulder_abduction": 8,
    "shoulder_flexion": 2,
    "elbow_flexion": 12,
    "wrist_flexion": 4,
    "neck_flexion": 3,
}
"""Standing at ease: arms hang just clear of the thighs, elbows soft."""

HOLD = {
    "shoulder_flexion": 20,
    "shoulder_abduction": 14,
    "shoulder_rotation": 22,
    "elbow_flexion": 72,
    "wrist_flexion": -5,
    "neck_flexion": 10,
}
"""Both hands hold an object in front of the belly (carrying, between pick and place)."""


@dataclass(frozen=True)
class Key:
    """A key pose at `time`: joint overrides, and optional foot placements per side.

    A foot placement is (yaw_deg, lift_m): the sole's standing place turned about the
    pelvis by yaw and raised by lift (stepping round on the spot).
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


def _interpolate_keys(times: np.ndarray, key_times, key_values) -> np.ndarray:
    """Minimum-jerk segments between consecutive keys (values: one row per key)."""
    key_times = np.asarray(key_times)
    segment = np.clip(np.searchsorted(key_times, times, side="right") - 1, 0, len(key_times) - 2)
    t0, t1 = key_times[segment], key_times[segment + 1]
    s = minimum_jerk((times - t0) / np.maximum(t1 - t0, 1e-9))
    v0, v1 = key_values[segment], key_values[segment + 1]
    return v0 + (v1 - v0) * s[:, None]


def _foot_placements(body: HumanBody, keys: tuple[Key, ...], times: np.ndarray) -> dict:
    """Per side, per frame: (yaw, lift) of the sole, keyed like the joints (default planted)."""
    placements = {}
    for side in SIDES:
        values, last = [], (0.0, 0.0)
        for key in keys:
            last = key.feet.get(side, last)
            values.append((np.radians(last[0]), last[1]))
        placements[side] = _interpolate_keys(times, [k.time for k in keys], np.array(values))
    return placements


def _sole_target(body: HumanBody, side: str, yaw: float, lift: float):
    sign = 1 if side == "left" else -1
    standing = np.array(
        [body.sizes["foot"] / 2 - body.sizes["heel_back"], sign * body.sizes["hip_half_width"], 0.0]
    )
    rotation = RotationMatrix.MakeZRotation(yaw)
    return rotation @ standing + np.array([0.0, 0.0, lift]), rotation


def leg_indices(body: HumanBody, side: str) -> np.ndarray:
    return np.array(
        [
            i
            for i, n in enumerate(body.joint_names)
            if n.startswith(f"{side}_") and any(j in n for j in ("hip", "knee", "ankle"))
        ]
    )


SOFT_KNEES = 0.006
"""Stand 6 mm lower than with locked knees: a straight knee is singular, so leg IK on locked
knees would snap them between straight and bent as the weight shifts."""

KNEE_SEED = np.radians(25.0)
"""A straight knee is a singular start for leg IK: begin the first frame slightly bent."""


def plant_feet(body: HumanBody, frames: np.ndarray, placements: dict) -> np.ndarray:
    """Solve both legs in every frame so each sole sits flat at its placement."""
    planted = frames.copy()
    free = np.concatenate([leg_indices(body, side) for side in SIDES])
    previous = None
    for k, q in enumerate(frames):
        tasks = []
        for side in SIDES:
            position, rotation = _sole_target(body, side, *placements[side][k])
            tasks.append(
                FrameTask(f"{side}_sole", position, rotation, rotation_weights=(0.3, 0.3, 0.3))
            )
        start = q.copy()
        if previous is None:
            knees = [body.index(f"{side}_knee_flexion") for side in SIDES]
            start[knees] = np.maximum(start[knees], KNEE_SEED)
        else:
            start[free] = previous[free]
        planted[k] = body.solve(start, tasks, free, iterations=40, posture_weight=1e-5)
        previous = planted[k]
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


# --- walking -------------------------------------------------------------------------------

GAIT_CYCLE = 32 / 30
"""Seconds per gait cycle: 110 steps/min."""

GAIT_KEYS = {
    "hip_flexion": ((0, 26), (12, 23), (30, 9), (50, -10), (60, 0), (75, 24), (87, 31)),
    "knee_flexion": ((0, 3), (14, 18), (35, 6), (47, 12), (60, 40), (72, 65), (86, 33), (96, 4)),
    "ankle_flexion": (
        (0, 0),
        (8, -5),
        (30, 5),
        (45, 10),
        (52, 4),
        (62, -18),
        (72, 4),
        (84, 7),
        (94, 1),
    ),
}
"""Sagittal angles (degrees) at % of the gait cycle from heel strike (docs/human-body.md)."""


def periodic_curve(keys, phase: np.ndarray) -> np.ndarray:
    """Smooth periodic cubic through (percent, value) keys, evaluated at phase in [0, 1)."""
    x = np.array([k[0] for k in keys]) / 100.0
    y = np.array([k[1] for k in keys], dtype=float)
    xs = np.concatenate([x[-2:] - 1, x, x[:2] + 1])
    ys = np.concatenate([y[-2:], y, y[:2]])
    slopes = np.gradient(ys, xs)
    p = np.mod(phase, 1.0)
    i = np.searchsorted(xs, p, side="right") - 1
    h = xs[i + 1] - xs[i]
    s = (p - xs[i]) / h
    h00, h10 = 2 * s**3 - 3 * s**2 + 1, s**3 - 2 * s**2 + s
    h01, h11 = -2 * s**3 + 3 * s**2, s**3 - s**2
    return h00 * ys[i] + h10 * h * slopes[i] + h01 * ys[i + 1] + h11 * h * slopes[i + 1]


@dataclass(frozen=True)
class GaitSpec:
    name: str
    description: str
    arms: dict | None = None
    """Fixed arm/trunk pose (e.g. HOLD for carrying); None swings the arms."""


def _gait_joint_curves(body: HumanBody, phase: np.ndarray, spec: GaitSpec) -> np.ndarray:
    """Joint trajectories of one cycle before the root is fitted to the floor."""
    frames = np.tile(pose_vector(body, RELAXED, spec.arms or {}), (len(phase), 1))
    wave = 2 * pi * phase

    def put(name, degrees):
        frames[:, body.index(name)] = np.radians(degrees)

    for side, lag in (("left", 0.0), ("right", 0.5)):
        for joint, keys in GAIT_KEYS.items():
            put(f"{side}_{joint}", periodic_curve(keys, phase - lag))
        put(f"{side}_hip_rotation", 3 * np.cos(wave - 2 * pi * lag))
        if spec.arms is None:
            put(f"{side}_shoulder_flexion", 3 - 13 * np.cos(wave - 2 * pi * lag))
            put(f"{side}_elbow_flexion", 20 - 9 * np.cos(wave - 2 * pi * lag))
    put("pelvis_tilt", 5 + 1.5 * np.cos(2 * wave))
    put("pelvis_list", 4 * np.sin(wave))
    put("base_yaw", -4 * np.cos(wave))
    put("thorax_rotation", 5 * np.cos(wave))
    put("lumbar_flexion", 2 + 1.0 * np.cos(2 * wave))
    frames[:, body.index("base_y")] = 0.018 * np.sin(wave)
    return frames


def _keep_feet_on_track(body: HumanBody, frames: np.ndarray) -> np.ndarray:
    """Hip abduction per frame so each sole stays on its straight track line (no side slip)."""
    fixed = frames.copy()
    for side in SIDES:
        sign = 1 if side == "left" else -1
        free = np.array([body.index(f"{side}_hip_abduction")])
        target = np.array([0.0, sign * body.sizes["hip_half_width"], 0.0])
        for k, q in enumerate(fixed):
            position = body.frame_pose(f"{side}_sole", q).translation()
            target[0], target[2] = position[0], position[2]
            task = FrameTask(f"{side}_sole", target.copy(), position_weights=(0, 1, 0))
            fixed[k] = body.solve(q, [task], free, iterations=10, posture_weight=1e-9)
    return fixed


STANCE = 0.6
"""Fraction of the gait cycle a foot spends on the floor (heel strike to toe-off)."""

PUSH_OFF = (0.5, STANCE, 0.7)
"""Trailing-leg phases: its toe is pinned from 0.5 to toe-off, the correction fades by 0.7."""


def _leg_phase(side: str, phase):
    return (phase - (0.0 if side == "left" else 0.5)) % 1.0


def _fit_root_to_floor(body: HumanBody, frames: np.ndarray, phase: np.ndarray):
    """The leading stance foot carries the body: its lowest sole point stays on the floor.

    The pelvis height puts that point at z = 0 and the forward travel keeps it still; the
    leading leg is the one between its heel strike and the other leg's heel strike. The
    frames cover one cycle without its end; returns them and the stride (travel per cycle).
    """
    fitted = frames.copy()
    ix, iz = body.index("base_x"), body.index("pelvis_height")
    fitted[:, ix] = 0.0
    fitted[:, iz] = 0.0
    points = [body.sole_points(q) for q in fitted]
    travel = 0.0
    for k, p in enumerate(points):
        lead = "left" if _leg_phase("left", phase[k]) < 0.5 else "right"
        support = min((f"{lead}_heel", f"{lead}_toe"), key=lambda n: p[n][2])
        fitted[k, iz] = -p[support][2]
        fitted[k, ix] = travel
        following = points[(k + 1) % len(points)]
        travel -= following[support][0] - p[support][0]
    return fitted, travel


def _pin_trailing_toe(body: HumanBody, frames: np.ndarray, phase: np.ndarray) -> np.ndarray:
    """Close the double-support loop: knee and ankle keep the trailing toe on its spot.

    From the other heel strike to toe-off the trailing toe stays where it was; the knee and
    ankle correction then fades out in early swing so the curves stay smooth.
    """
    pinned = frames.copy()
    toe = (body.sizes["foot"] / 2, 0.0, 0.0)
    start, toe_off, faded = PUSH_OFF
    for side in SIDES:
        free = np.array([body.index(f"{side}_knee_flexion"), body.index(f"{side}_ankle_flexion")])
        leg = _leg_phase(side, phase)
        correction, spot = np.zeros(2), None
        for k in np.argsort(np.where(leg >= start, leg, leg + 1.0)):
            if leg[k] < start or leg[k] >= faded:
                continue
            if spot is None:
                spot = body.frame_pose(f"{side}_sole", frames[k]) @ np.array(toe)
                spot[2] = 0.0
            if leg[k] < toe_off:
                task = FrameTask(f"{side}_sole", spot, position_weights=(1, 0, 1), point=toe)
                pinned[k] = body.solve(frames[k], [task], free, iterations=15, posture_weight=1e-6)
                correction = pinned[k, free] - frames[k, free]
            else:
                fade = 1.0 - minimum_jerk((leg[k] - toe_off) / (faded - toe_off))
                pinned[k, free] = frames[k, free] + fade * correction
    return pinned


def gait_clip(body: HumanBody, spec: GaitSpec, oversample: int = 8) -> Clip:
    """One loopable gait cycle whose stance sole does not slide (see module docstring)."""
    frames_per_cycle = round(GAIT_CYCLE * FPS)
    fine = np.arange(frames_per_cycle * oversample) / (frames_per_cycle * oversample)
    curves = _keep_feet_on_track(body, _gait_joint_curves(body, fine, spec))
    fitted, stride = _fit_root_to_floor(body, curves, fine)
    cycle = _pin_trailing_toe(body, fitted, fine)[::oversample]
    last = cycle[0].copy()
    last[body.index("base_x")] += stride
    frames = np.vstack([cycle, last])
    events = {"left_heel_strike": 0.0, "right_heel_strike": GAIT_CYCLE / 2}
    return Clip(spec.name, body.joint_names, frames, FPS, True, events, stride, spec.description)


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


# --- the built-in clips ----------------------------------------------------------------------

STOOP_SQUAT = {
    "base_x": -0.2,
    "pelvis_height": 0.72,
    "pelvis_tilt": 45,
    "lumbar_flexion": 40,
    "thorax_flexion": 20,
    "neck_flexion": -20,
    "shoulder_flexion": 100,
    "shoulder_abduction": 0,
    "shoulder_rotation": 30,
    "elbow_flexion": 12,
    "wrist_flexion": -10,
}
"""Hands at the floor in front of the feet: knees, hips and trunk all bend (a real lift)."""

TABLE_LEAN = {
    "base_x": -0.02,
    "pelvis_tilt": 10,
    "lumbar_flexion": 14,
    "thorax_flexion": 8,
    "neck_flexion": 28,
    "shoulder_flexion": 45,
    "shoulder_abduction": 12,
    "shoulder_rotation": 32,
    "elbow_flexion": 35,
    "wrist_flexion": -10,
}
"""Both hands at table height (about 0.8 m) in front of the body."""

INSPECT = {
    "shoulder_flexion": 36,
    "shoulder_abduction": 14,
    "shoulder_rotation": 30,
    "elbow_flexion": 98,
    "wrist_flexion": 5,
    "thorax_flexion": 4,
    "neck_flexion": 32,
}

REACH = {
    "right_shoulder_flexion": 55,
    "right_shoulder_abduction": 4,
    "right_elbow_flexion": 22,
    "right_wrist_flexion": -5,
    "pelvis_tilt": 6,
    "lumbar_flexion": 10,
    "thorax_rotation": -8,
    "neck_flexion": 22,
}
"""Right hand to a point in front at table height."""

HAND_OVER = {
    "shoulder_flexion": 58,
    "shoulder_abduction": 12,
    "shoulder_rotation": 12,
    "elbow_flexion": 32,
    "wrist_flexion": -10,
    "thorax_flexion": 4,
    "neck_flexion": 12,
}
"""Both hands offered in front of the chest (to take or give a box between the palms)."""

WAVE = {
    "right_shoulder_abduction": 115,
    "right_shoulder_rotation": -75,
    "right_elbow_flexion": 40,
    "right_wrist_deviation": 5,
    "thorax_rotation": -6,
    "neck_rotation": -12,
}

LOOK = {"neck_rotation": 65, "thorax_rotation": 22, "neck_flexion": 0}


def _waving(start: float, swings: int, period: float) -> tuple[Key, ...]:
    """Forearm swinging side to side above the shoulder."""
    return tuple(
        Key(start + i * period / 2, {**WAVE, "right_elbow_flexion": 40 if i % 2 == 0 else 85})
        for i in range(swings * 2 + 1)
    )


def _turn_keys(step: float, degrees: float, lift: float) -> tuple[Key, ...]:
    """Two steps turning left on the spot: left foot, then right foot, body between."""
    half = degrees / 2
    return (
        Key(0.0, {"base_yaw": 0}, {"left": (0, 0), "right": (0, 0)}),
        Key(step / 2, {"base_yaw": half / 2}, {"left": (half, lift)}),
        Key(step, {"base_yaw": half}, {"left": (degrees, 0)}),
        Key(1.5 * step, {"base_yaw": 1.5 * half}, {"right": (half, lift)}),
        Key(2 * step, {"base_yaw": degrees}, {"right": (degrees, 0)}),
    )


TURN_STEP_TIME = 0.45
TURN_LIFT = 0.05


def _turn_spec(name: str, degrees: float) -> KeyedSpec:
    return KeyedSpec(
        name,
        f"Two steps turning {degrees:g} degrees left on the spot (loops; one cycle turns "
        f"{degrees:g} degrees).",
        _turn_keys(TURN_STEP_TIME, degrees, TURN_LIFT),
        events={"left_step": 0.0, "right_step": TURN_STEP_TIME},
        loop=True,
    )


def turn_clip(body: HumanBody, degrees: float) -> Clip:
    """Two steps turning on the spot by `degrees` (negative: to the right, right foot
    first), the feet planted by IK like every keyed clip: a turn of any angle that does not
    skate."""
    clip = keyed_clip(body, _turn_spec(f"turn_{abs(degrees):g}", abs(degrees)))
    if degrees >= 0:
        return clip
    return mirrored_clip(body, clip, f"turn_{degrees:g}", clip.description.replace("left", "right"))


KEYED_CLIPS = (
    KeyedSpec(
        "idle",
        "Standing at ease: breathing, weight shifting from foot to foot (loops).",
        (Key(0.0), Key(4.0)),
        loop=True,
        layers=(
            Layer("thorax_flexion", 1.2, 1),
            Layer("base_y", 0.02, 1),
            Layer("pelvis_list", 1.5, 1),
            Layer("neck_rotation", 4.0, 1, 0.25),
            Layer("lumbar_bending", -1.0, 1),
        ),
    ),
    _turn_spec("turn_left", 60.0),
    KeyedSpec(
        "pick_floor",
        "Squat and stoop to take an object off the floor with both hands; rise holding it.",
        (Key(0.0), Key(1.2, STOOP_SQUAT), Key(1.5, STOOP_SQUAT), Key(2.7, HOLD), Key(3.0, HOLD)),
        events={"grasp": 1.2},
    ),
    KeyedSpec(
        "pick_table",
        "Lean over a table, take an object with both hands, hold it in front of the belly.",
        (Key(0.0), Key(0.9, TABLE_LEAN), Key(1.2, TABLE_LEAN), Key(2.1, HOLD), Key(2.4, HOLD)),
        events={"grasp": 0.9},
    ),
    KeyedSpec(
        "place_floor",
        "Lower a held object to the floor, let go and stand up.",
        (Key(0.0, HOLD), Key(1.2, STOOP_SQUAT), Key(1.5, STOOP_SQUAT), Key(2.7), Key(3.0)),
        events={"release": 1.2},
    ),
    KeyedSpec(
        "place_table",
        "Put a held object down on a table, let go and stand up.",
        (Key(0.0, HOLD), Key(0.9, TABLE_LEAN), Key(1.2, TABLE_LEAN), Key(2.1), Key(2.4)),
        events={"release": 0.9},
    ),
    KeyedSpec(
        "inspect",
        "Hold an object in front of the chest, look at it, turn it, lower it again.",
        (
            Key(0.0, HOLD),
            Key(0.8, INSPECT),
            Key(1.6, {**INSPECT, "wrist_deviation": 15, "shoulder_rotation": 28}),
            Key(2.4, {**INSPECT, "wrist_deviation": -15, "shoulder_rotation": 45}),
            Key(3.2, INSPECT),
            Key(4.0, HOLD),
        ),
        events={"look": 0.8, "done": 3.2},
    ),
    KeyedSpec(
        "reach",
        "Reach with the right hand to a point in front at table height, then retract.",
        (Key(0.0), Key(0.8, REACH), Key(1.4, REACH), Key(2.2), Key(2.4)),
        events={"reached": 0.8, "retract": 1.4},
    ),
    KeyedSpec(
        "hand_over",
        "Extend both hands to take or give an object, hold them out, retract.",
        (Key(0.0), Key(0.9, HAND_OVER), Key(2.1, HAND_OVER), Key(3.0), Key(3.3)),
        events={"extended": 0.9, "release": 2.1},
    ),
    KeyedSpec(
        "wave",
        "Wave the raised right hand to call someone (wave/call).",
        (Key(0.0), *_waving(0.7, 3, 0.6), Key(3.2)),
        events={"wave": 0.7},
    ),
    KeyedSpec(
        "look_around",
        "Turn head and shoulders to look left, then right, then ahead again.",
        (
            Key(0.0),
            Key(1.2, LOOK),
            Key(1.8, LOOK),
            Key(3.0, {k: -v for k, v in LOOK.items()}),
            Key(3.6, {k: -v for k, v in LOOK.items()}),
            Key(4.5),
        ),
        events={"look_left": 1.2, "look_right": 3.0},
    ),
)

GAIT_CLIPS = (
    GaitSpec("walk", "Walking at about 1.3 m/s, 112 steps/min (loops; one cycle = 2 steps)."),
    GaitSpec("carry", "Walking while holding an object in front with both hands (loops).", HOLD),
)


def build_clips(body: HumanBody | None = None) -> dict[str, Clip]:
    """Every built-in clip, authored for the default person."""
    body = body or human_body()
    clips = {spec.name: keyed_clip(body, spec) for spec in KEYED_CLIPS}
    clips.update({spec.name: gait_clip(body, spec) for spec in GAIT_CLIPS})
    clips["turn_right"] = mirrored_clip(
        body,
        clips["turn_left"],
        "turn_right",
        clips["turn_left"].description.replace("left", "right"),
    )
    return clips


def main(argv=None) -> None:
    """Rewrite models/human/animations/*.json."""
    del argv
    for clip in build_clips().values():
        print(f"wrote {save_clip(clip)}")


if __name__ == "__main__":
    main(sys.argv[1:])
