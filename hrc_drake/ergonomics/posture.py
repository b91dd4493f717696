"""Posture angles of the person as RULA and REBA define them, measured on the skeleton's
own bodies (`hrc_drake.human.skeleton`) from the world poses the simulation gave them.

Every body frame of the skeleton is x forward, y left, z up in the upright zero pose, so
segment directions come from joint centres (a body's origin is its joint with its parent)
and the trunk's and head's frames. docs/ergonomics.md says how each angle is taken.
"""

from dataclasses import dataclass

import numpy as np

from hrc_drake.human.body import HumanBody
from hrc_drake.human.skeleton import SIDES

TRUNK_BODIES = ("pelvis", "chest", "head")
SIDE_BODIES = ("upper_arm", "forearm", "hand", "thigh", "shank", "foot")
SIDE_FRAMES = ("hand_grasp", "sole")
FLOOR_CONTACT = 0.03
"""m: a sole at most this far above the floor bears weight"""


@dataclass(frozen=True)
class Pose:
    """World rotations (..., 3, 3) and positions (..., 3) of the bodies and frames the
    angles use: of one sample, or stacked along a first axis for many."""

    rotations: dict[str, np.ndarray]
    positions: dict[str, np.ndarray]

    def at(self, i: int) -> "Pose":
        return Pose(
            {n: R[i] for n, R in self.rotations.items()},
            {n: p[i] for n, p in self.positions.items()},
        )


def pose_frames(body: HumanBody) -> tuple[tuple[str, ...], list]:
    """The names and plant frames `poses_of` reads."""
    names = [*TRUNK_BODIES]
    names += [f"{side}_{part}" for side in SIDES for part in SIDE_BODIES]
    frames = [body.plant.GetBodyByName(name).body_frame() for name in names]
    extra = [f"{side}_{frame}" for side in SIDES for frame in SIDE_FRAMES]
    frames += [body.plant.GetFrameByName(name) for name in extra]
    return (*names, *extra), frames


def poses_of(body: HumanBody, positions: np.ndarray) -> Pose:
    """The person's poses at the plant positions (one column per sample), stacked."""
    names, frames = pose_frames(body)
    matrices = np.array(
        [[X.GetAsMatrix4() for X in body.world_poses(frames, q)] for q in positions.T]
    ).reshape(positions.shape[1], len(names), 4, 4)
    return Pose(
        {n: matrices[:, k, :3, :3] for k, n in enumerate(names)},
        {n: matrices[:, k, :3, 3] for k, n in enumerate(names)},
    )


@dataclass(frozen=True)
class ArmAngles:
    """Degrees. `flexion` is the upper arm's elevation from the trunk (negative when it
    points backwards: extension); `abduction` its angle out of the trunk's sagittal plane,
    outwards; `wrist_twist` the forearm's turn from its mid-position (thumb forward, palm
    to the thigh with the arm hanging), positive in pronation (the palm turned down or
    back), negative in supination; `hand_lateral` how far (m) the hand is outside its
    shoulder (negative: inside), `hand_across` whether it reaches past the body's
    midline."""

    flexion: np.ndarray
    abduction: np.ndarray
    elbow_flexion: np.ndarray
    wrist_flexion: np.ndarray
    wrist_deviation: np.ndarray
    wrist_twist: np.ndarray
    hand_lateral: np.ndarray
    hand_across: np.ndarray


@dataclass(frozen=True)
class PostureAngles:
    """Degrees: trunk from the vertical, neck from the trunk; knees from straight. Each
    field is one value, or an array of them for many samples (`at` picks one)."""

    trunk_flexion: np.ndarray
    trunk_side_bend: np.ndarray
    trunk_twist: np.ndarray
    neck_flexion: np.ndarray
    neck_side_bend: np.ndarray
    neck_twist: np.ndarray
    knee_flexion: dict[str, np.ndarray]
    feet_on_floor: dict[str, np.ndarray]
    arms: dict[str, ArmAngles]

    def at(self, i: int) -> "PostureAngles":
        return self.samples()[i]

    def samples(self) -> list["PostureAngles"]:
        """One PostureAngles of plain numbers per sample (for the scalar score rules)."""
        columns = _columns(self)
        return [_row(columns, i) for i in range(len(self.trunk_flexion))]


def _columns(value):
    """Every array of a PostureAngles as a list (one conversion, then cheap indexing)."""
    if isinstance(value, dict):
        return {k: _columns(v) for k, v in value.items()}
    if isinstance(value, ArmAngles | PostureAngles):
        return (type(value), {k: _columns(v) for k, v in value.__dict__.items()})
    return value.tolist()


def _row(columns, i: int):
    if isinstance(columns, dict):
        return {k: _row(v, i) for k, v in columns.items()}
    if isinstance(columns, tuple):
        kind, fields = columns
        return kind(**{k: _row(v, i) for k, v in fields.items()})
    return columns[i]


def _dot(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    return np.einsum("...i,...i->...", a, b)


def _unit(v: np.ndarray) -> np.ndarray:
    return v / np.linalg.norm(v, axis=-1, keepdims=True)


def _angle(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    return np.degrees(np.arccos(np.clip(_dot(_unit(a), _unit(b)), -1.0, 1.0)))


def _in(R: np.ndarray, v: np.ndarray) -> np.ndarray:
    """World vectors `v` in the frames rotated by `R` (R^T v)."""
    return np.einsum("...ji,...j->...i", R, v)


def _atan2(y, x) -> np.ndarray:
    return np.degrees(np.arctan2(y, x))


def posture_angles(pose: Pose) -> PostureAngles:
    R, p = pose.rotations, pose.positions
    chest = R["chest"]
    trunk = chest[..., :, 2]  # the thorax's long axis: vertical when upright
    forward = R["pelvis"][..., :, 0] * np.array([1.0, 1.0, 0.0])
    forward = _unit(forward)
    left = np.cross(np.array([0.0, 0.0, 1.0]), forward)
    head_up = _in(chest, R["head"][..., :, 2])
    head_forward = _in(chest, R["head"][..., :, 0])
    return PostureAngles(
        trunk_flexion=_atan2(_dot(trunk, forward), trunk[..., 2]),
        trunk_side_bend=np.abs(_atan2(_dot(trunk, left), trunk[..., 2])),
        trunk_twist=_twist(R["pelvis"], chest),
        neck_flexion=_atan2(head_up[..., 0], head_up[..., 2]),
        neck_side_bend=np.abs(_atan2(head_up[..., 1], head_up[..., 2])),
        neck_twist=np.abs(_atan2(head_forward[..., 1], head_forward[..., 0])),
        knee_flexion={side: _knee(p, side) for side in SIDES},
        feet_on_floor={side: p[f"{side}_sole"][..., 2] <= FLOOR_CONTACT for side in SIDES},
        arms={side: _arm(R, p, side) for side in SIDES},
    )


def _twist(pelvis: np.ndarray, chest: np.ndarray) -> np.ndarray:
    """The shoulders' line turned against the hips' line about the trunk's axis."""
    axis = chest[..., :, 2]
    hips = pelvis[..., :, 1] - _dot(pelvis[..., :, 1], axis)[..., None] * axis
    return _angle(chest[..., :, 1], hips)


def _knee(p: dict, side: str) -> np.ndarray:
    thigh = p[f"{side}_shank"] - p[f"{side}_thigh"]
    shank = p[f"{side}_foot"] - p[f"{side}_shank"]
    return _angle(thigh, shank)


def _arm(R: dict, p: dict, side: str) -> ArmAngles:
    """The arm's angles in the chest's frame (RULA and REBA take the arm from the trunk)."""
    chest, origin = R["chest"], p["chest"]
    out = 1.0 if side == "left" else -1.0
    shoulder = _in(chest, p[f"{side}_upper_arm"] - origin)
    elbow = _in(chest, p[f"{side}_forearm"] - origin)
    wrist = _in(chest, p[f"{side}_hand"] - origin)
    grasp = _in(chest, p[f"{side}_hand_grasp"] - origin)
    upper = _unit(elbow - shoulder)
    elevation = _angle(upper, np.array([0.0, 0.0, -1.0]))
    sideways = out * upper[..., 1]
    backwards = (upper[..., 0] < 0) & (-upper[..., 0] > np.maximum(sideways, 0.0))
    forearm, hand_frame = R[f"{side}_forearm"], R[f"{side}_hand"]
    # The forearm's pronation: the hand's y axis (the palm's normal, about which the wrist
    # deviates, square to the axis it flexes about) turned about the forearm's long axis.
    # Flexion tilts that axis along the forearm and deviation turns about it, so neither
    # changes its bearing about the forearm (short of flexion by 90 deg, past the joint's
    # range): the bearing is the pronation alone.
    palm = _in(forearm, hand_frame[..., :, 1])
    twist = np.arctan2(-palm[..., 0], palm[..., 1])
    # Flexion and deviation are taken in the forearm turned with it (the radius carries
    # the wrist as the forearm pronates): the hand's axis with that turn undone.
    axis = _in(forearm, -hand_frame[..., :, 2])
    c, s = np.cos(twist), np.sin(twist)
    hand = np.stack(
        [c * axis[..., 0] + s * axis[..., 1], c * axis[..., 1] - s * axis[..., 0], axis[..., 2]],
        axis=-1,
    )
    return ArmAngles(
        flexion=np.where(backwards, -elevation, elevation),
        abduction=np.degrees(np.arcsin(np.clip(sideways, -1.0, 1.0))),
        elbow_flexion=_angle(upper, wrist - elbow),
        wrist_flexion=np.abs(_atan2(hand[..., 1], -hand[..., 2])),
        wrist_deviation=np.abs(_atan2(hand[..., 0], -hand[..., 2])),
        wrist_twist=-out * np.degrees(twist),  # the left forearm pronates about -z
        hand_lateral=out * (grasp[..., 1] - shoulder[..., 1]),
        hand_across=out * grasp[..., 1] < 0,
    )
