"""The gait clips (walk, carry): one loopable cycle through published gait figures.

Hip, knee and ankle angle curves pass through the published key points of one gait cycle,
the right leg half a cycle behind the left; the pelvis height and forward travel are then
derived from the kinematics so that whichever sole point touches the floor stays put, and
the stance foot is planted on its step while the swing foot lifts and settles as the person
stepping at run time does (hrc_drake.human.stepping shares the gait phases).
"""

from dataclasses import dataclass
from math import pi, sqrt

import numpy as np

from hrc_drake.human.body import FrameTask, HumanBody
from hrc_drake.human.clip import Clip
from hrc_drake.human.keyed_clips import RELAXED, minimum_jerk, pose_vector
from hrc_drake.human.legs import Legs
from hrc_drake.human.skeleton import SIDES
from hrc_drake.human.stepping import LIFTING, SETTLING, STANCE

GAIT_FPS = 120.0
"""Walking clips keep four times the frames: between frames a clip is a spline through the
joints, and at 30 (or 60) frames a second a rolling stance foot wanders by 6 mm between the
frames where it stands exactly."""

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


PACE_SWING = 0.08
"""The pelvis's forward speed swings by this fraction of its mean within each step: fastest
just after heel strike (double support), slowest at mid-stance, as the body vaults over the
stance leg (Cavagna et al. 1977: about 10-15 % at normal speed; docs/realism.md)."""

FASTEST = 0.05
"""Phase after each heel strike at which the pelvis moves fastest."""


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


def paced_travel(phase, stride: float):
    """The pelvis's forward travel at each phase of the cycle: the mean speed with a swing of
    PACE_SWING, twice per cycle (once per step)."""
    wave = 4 * pi * (np.asarray(phase) - FASTEST)
    return stride * (phase + PACE_SWING / (4 * pi) * np.sin(wave))


MIN_STANCE_KNEE = np.radians(4.0)
"""The stance knee never straightens further than this: where the paced pelvis would need a
longer leg, it rides lower instead."""


@dataclass(frozen=True)
class _Step:
    """One foot's stance: where its heel and toe stand."""

    heel: np.ndarray
    toe: np.ndarray

    def sole(self, pitch: float, half_foot: float) -> tuple[np.ndarray, np.ndarray]:
        """The sole frame's origin and the foot's forward axis, rolled over the heel (toe
        up, pitch > 0) or over the toe (heel up)."""
        forward = np.array([sqrt(1.0 - pitch * pitch), 0.0, pitch])
        if pitch > 0:
            return self.heel + half_foot * forward, forward
        return self.toe - half_foot * forward, forward


PELVIS_HARMONICS = 4
"""The pelvis rises and falls smoothly, twice per cycle (and its overtones): the published
kinematics alone make it drop by 2 cm at each heel strike, where the support changes legs."""


def _smooth_periodic(values: np.ndarray, harmonics: int) -> np.ndarray:
    """A periodic signal (one cycle) without its harmonics above `harmonics`."""
    spectrum = np.fft.rfft(values)
    spectrum[harmonics + 1 :] = 0.0
    return np.fft.irfft(spectrum, len(values))


def _plant_stance(body: HumanBody, frames: np.ndarray, phase: np.ndarray, stride: float):
    """Pace the pelvis and plant each stance foot under it (the legs solved in closed form).

    The published joint curves put the pelvis where the stance foot's kinematics take it,
    which surges and stalls within every step; here the pelvis travels at the paced speed
    instead and the legs follow: each foot stands on its step from heel strike to toe-off,
    pitched as the published ankle curve pitches it (rolling over the heel, flat, rolling
    over the toe); steps lie where they keep the stance leg closest to its published angles;
    the swing follows the published curves, its sole moved smoothly from where it left the
    floor to where it lands. Where the stance leg would have to be longer, the pelvis rides
    lower.
    """
    legs = Legs(body)
    ix, iz = body.index("base_x"), body.index("pelvis_height")
    paced = frames.copy()
    paced[:, ix] = paced_travel(phase, stride)
    paced[:, iz] = _smooth_periodic(frames[:, iz], PELVIS_HARMONICS)
    ahead = paced[:, ix] - frames[:, ix]
    free = {side: [legs.sole(q, side) for q in paced] for side in SIDES}
    pitch = {side: _stance_pitch(legs, side, frames, phase) for side in SIDES}
    steps, soles = {}, {}
    for side in SIDES:
        leg = _leg_phase(side, phase)
        strike = int(np.argmin(leg))
        heel = legs.sole(frames[strike], side).point(-legs.half_foot)
        heel[0] += ahead[strike]
        heel[2] = 0.0
        steps[side] = _Step(heel, heel + [2 * legs.half_foot, 0.0, 0.0])
        soles[side] = _sole_track(legs, side, leg, free[side], pitch[side], steps[side], stride)
    paced[:, iz] = _pelvis_within_reach(legs, paced, phase, soles)
    for k in range(len(paced)):
        for side in SIDES:
            paced[k] = _reach_sole(legs, paced[k], side, *soles[side][k])
    return paced


WALKING_DORSIFLEXION = np.radians(16.0)
"""The stance ankle bends no further while walking (the heel rises instead): 10-15 degrees
is what gait data show (Perry), and the joint's limit leaves the walk some room."""


def _reach_sole(legs: Legs, q: np.ndarray, side: str, position, forward) -> np.ndarray:
    """q with the leg putting the sole at `position` pointing along `forward`; where that
    bends a standing foot's ankle further than WALKING_DORSIFLEXION, or the leg is too short
    for a foot on its toe, the foot rolls further over its toe (which stays where it stands)
    with the ankle there, or the knee at MIN_STANCE_KNEE."""
    solved = legs.solve(q, side, position, forward)
    ankle = legs.joints[side][4]
    toe = np.asarray(position) + legs.half_foot * np.asarray(forward)
    if toe[2] > 1e-3 or forward[2] > 0:
        return solved
    if solved[ankle] > WALKING_DORSIFLEXION:
        angle = WALKING_DORSIFLEXION
    elif np.linalg.norm(legs.sole(solved, side).position - position) > 1e-4:
        angle = legs.ankle_for_knee(solved, side, toe, legs.half_foot, MIN_STANCE_KNEE)
        if angle is None:
            return solved
    else:
        return solved
    heading = np.array([forward[0], forward[1], 0.0])
    return legs.solve_rolling(solved, side, toe, legs.half_foot, heading, angle, forward[2])


HEEL_RISE = 0.35
"""Leg phase at which the stance heel starts to rise (terminal stance, Perry); from the heel
rocker until then the foot stands flat."""


def _stance_pitch(legs, side, frames, phase) -> np.ndarray:
    """The foot's pitch (sine of its forward axis' rise) per frame: the published pose's,
    except that a stance foot stands flat between the heel rocker and heel rise."""
    pitch = np.array([legs.sole(q, side).forward[2] for q in frames])
    leg = _leg_phase(side, phase)
    rocking = (leg < HEEL_RISE) & (pitch > 0.0) & (leg < 0.5 * HEEL_RISE)
    rising = (leg >= HEEL_RISE) & (pitch < 0.0)
    standing = leg < STANCE
    return np.where(standing & ~rocking & ~rising, 0.0, pitch)


def _sole_track(legs, side, leg, free, pitch, step, stride):
    """Per frame, where the `side` sole goes (origin, forward axis): on its step in stance,
    the published swing's sole in the air, shifted from where the foot leaves its step to
    where it lands on the next one (a stride ahead)."""
    strike = int(np.argmin(leg))
    track = {}
    for k in np.flatnonzero(leg < STANCE):
        position, forward = step.sole(pitch[k], legs.half_foot)
        before_strike = k < strike  # still on the step one stride behind (the loop's start)
        track[k] = (position - [stride * before_strike, 0.0, 0.0], forward)
    lift = max(track, key=lambda k: leg[k])
    leaving = track[lift][0] - free[lift].position
    arriving = track[strike][0] - free[strike].position
    landing = track[strike][0] + [stride * (strike == 0), 0.0, 0.0]
    for k in np.flatnonzero(leg >= STANCE):
        w = minimum_jerk((leg[k] - STANCE) / (1.0 - STANCE))
        position = free[k].position + (1 - w) * leaving + w * arriving
        lifted = minimum_jerk((leg[k] - LIFTING[0]) / (LIFTING[1] - LIFTING[0]))
        settle = minimum_jerk((leg[k] - SETTLING[0]) / (SETTLING[1] - SETTLING[0]))
        position[:2] += (1 - lifted) * (track[lift][0][:2] - position[:2])
        position[:2] += settle * (landing[:2] - position[:2])
        forward = free[k].forward + (1 - lifted) * (track[lift][1] - free[k].forward)
        forward += settle * (track[strike][1] - forward)
        forward /= np.linalg.norm(forward)
        lowest = min(position[2] + s * legs.half_foot * forward[2] for s in (-1, 1))
        position[2] -= min(lowest, 0.0)
        track[k] = (position, forward)
    return [track[k] for k in range(len(leg))]


def _pelvis_within_reach(legs, frames, phase, soles) -> np.ndarray:
    """The pelvis height, lowered smoothly wherever a leg could not reach its sole's place
    with the knee bent at least MIN_STANCE_KNEE."""
    iz = legs.root[3]
    lower = np.zeros(len(frames))
    for k, q in enumerate(frames):
        for side in SIDES:
            if HEEL_RISE <= _leg_phase(side, phase[k]) < STANCE:
                continue  # on its toe: it rolls further rather than the pelvis dropping
            highest = legs.highest_pelvis(q, side, *soles[side][k], MIN_STANCE_KNEE)
            lower[k] = max(lower[k], q[iz] - highest)
    return frames[:, iz] - _smooth_cover(lower)


def _smooth_cover(values: np.ndarray, passes: int = 200) -> np.ndarray:
    """A smooth periodic curve at or above `values` that hugs them (repeated averaging of
    neighbours, never below the values)."""
    cover = values.copy()
    for _ in range(passes):
        cover = np.maximum(values, (np.roll(cover, 1) + 2 * cover + np.roll(cover, -1)) / 4)
    return cover


def gait_clip(body: HumanBody, spec: GaitSpec, oversample: int = 2) -> Clip:
    """One loopable gait cycle whose stance sole does not slide (see module docstring)."""
    frames_per_cycle = round(GAIT_CYCLE * GAIT_FPS)
    fine = np.arange(frames_per_cycle * oversample) / (frames_per_cycle * oversample)
    curves = _keep_feet_on_track(body, _gait_joint_curves(body, fine, spec))
    fitted, stride = _fit_root_to_floor(body, curves, fine)
    cycle = _plant_stance(body, fitted, fine, stride)[::oversample]
    last = cycle[0].copy()
    last[body.index("base_x")] += stride
    frames = np.vstack([cycle, last])
    events = {"left_heel_strike": 0.0, "right_heel_strike": GAIT_CYCLE / 2}
    return Clip(
        spec.name, body.joint_names, frames, GAIT_FPS, True, events, stride, spec.description
    )
