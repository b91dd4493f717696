"""Posture angles of the person as RULA and REBA define them, measured on the skeleton's
own bodies (`hrc_drake.human.skeleton`) from the world poses the simulation gave them.

Every body frame of the skeleton is x forward, y left, z up in the upright zero pose, so
segment directions come from joint centres (a body's origin is its joint with its parent)
and the trunk's and head's frames. docs/ergonomics.md says how each angle is taken.
"""

from dataclasses import dataclass
from math import atan2, degrees

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
    """World rotations (3x3) and positions of the bodies and frames the angles use."""

    rotations: dict[str, np.ndarray]
    positions: dict[str, np.ndarray]


def pose_frames(body: HumanBody) -> tuple[tuple[str, ...], list]:
    """The names and plant frames `pose_of` reads."""
    names = [*TRUNK_BODIES]
    names += [f"{side}_{part}" for side in SIDES for part in SIDE_BODIES]
    frames = [body.plant.GetBodyByName(name).body_frame() for name in names]
    extra = [f"{side}_{frame}" for side in SIDES for frame in SIDE_FRAMES]
    frames += [body.plant.GetFrameByName(name) for name in extra]
    return (*names, *extra), frames


def pose_of(body: HumanBody, names: tuple[str, ...], frames: list, plant_q) -> Pose:
    """The person's pose at the plant positions `plant_q` (one forward kinematics)."""
    poses = body.world_poses(frames, plant_q)
    return Pose(
        {n: X.rotation().matrix() for n, X in zip(names, poses, strict=True)},
        {n: X.translation() for n, X in zip(names, poses, strict=True)},
    )


@dataclass(frozen=True)
class ArmAngles:
    """Degrees. `flexion` is the upper arm's elevation from the trunk (negative when it
    points backwards: extension); `abduction` its angle out of the trunk's sagittal plane,
    outwards; `hand_lateral` how far (m) the hand is outside its shoulder (negative:
    inside), `hand_across` whether it reaches past the body's midline."""

    flexion: float
    abduction: float
    elbow_flexion: float
    wrist_flexion: float
    wrist_deviation: float
    hand_lateral: float
    hand_across: bool


@dataclass(frozen=True)
class PostureAngles:
    """Degrees: trunk from the vertical, neck from the trunk; knees from straight."""

    trunk_flexion: float
    trunk_side_bend: float
    trunk_twist: float
    neck_flexion: float
    neck_side_bend: float
    neck_twist: float
    knee_flexion: dict[str, float]
    feet_on_floor: dict[str, bool]
    arms: dict[str, ArmAngles]


def _unit(v: np.ndarray) -> np.ndarray:
    return v / np.linalg.norm(v)


def _angle(a: np.ndarray, b: np.ndarray) -> float:
    return degrees(np.arccos(np.clip(np.dot(_unit(a), _unit(b)), -1.0, 1.0)))


def _horizontal(v: np.ndarray) -> np.ndarray:
    return _unit(np.array([v[0], v[1], 0.0]))


def posture_angles(pose: Pose) -> PostureAngles:
    R, p = pose.rotations, pose.positions
    chest = R["chest"]
    trunk = chest[:, 2]  # the thorax's long axis: vertical when upright
    forward = _horizontal(R["pelvis"][:, 0])
    left = np.cross([0.0, 0.0, 1.0], forward)
    head_up = chest.T @ R["head"][:, 2]
    head_forward = chest.T @ R["head"][:, 0]
    return PostureAngles(
        trunk_flexion=degrees(atan2(trunk @ forward, trunk[2])),
        trunk_side_bend=abs(degrees(atan2(trunk @ left, trunk[2]))),
        trunk_twist=_twist(R["pelvis"], chest),
        neck_flexion=degrees(atan2(head_up[0], head_up[2])),
        neck_side_bend=abs(degrees(atan2(head_up[1], head_up[2]))),
        neck_twist=abs(degrees(atan2(head_forward[1], head_forward[0]))),
        knee_flexion={side: _knee(p, side) for side in SIDES},
        feet_on_floor={side: p[f"{side}_sole"][2] <= FLOOR_CONTACT for side in SIDES},
        arms={side: _arm(R, p, side) for side in SIDES},
    )


def _twist(pelvis: np.ndarray, chest: np.ndarray) -> float:
    """The shoulders' line turned against the hips' line about the trunk's axis."""
    hips = pelvis[:, 1] - (pelvis[:, 1] @ chest[:, 2]) * chest[:, 2]
    return _angle(chest[:, 1], hips)


def _knee(p: dict, side: str) -> float:
    thigh = p[f"{side}_shank"] - p[f"{side}_thigh"]
    shank = p[f"{side}_foot"] - p[f"{side}_shank"]
    return _angle(thigh, shank)


def _arm(R: dict, p: dict, side: str) -> ArmAngles:
    """The arm's angles in the chest's frame (RULA and REBA take the arm from the trunk)."""
    chest, origin = R["chest"], p["chest"]
    out = 1.0 if side == "left" else -1.0
    shoulder = chest.T @ (p[f"{side}_upper_arm"] - origin)
    elbow = chest.T @ (p[f"{side}_forearm"] - origin)
    wrist = chest.T @ (p[f"{side}_hand"] - origin)
    grasp = chest.T @ (p[f"{side}_hand_grasp"] - origin)
    upper = _unit(elbow - shoulder)
    elevation = _angle(upper, np.array([0.0, 0.0, -1.0]))
    sideways = out * upper[1]
    backwards = upper[0] < 0 and -upper[0] > max(sideways, 0.0)
    hand = R[f"{side}_forearm"].T @ -R[f"{side}_hand"][:, 2]  # the hand's axis, forearm frame
    return ArmAngles(
        flexion=-elevation if backwards else elevation,
        abduction=degrees(np.arcsin(np.clip(sideways, -1.0, 1.0))),
        elbow_flexion=_angle(upper, wrist - elbow),
        wrist_flexion=abs(degrees(atan2(hand[1], -hand[2]))),
        wrist_deviation=abs(degrees(atan2(hand[0], -hand[2]))),
        hand_lateral=out * (grasp[1] - shoulder[1]),
        hand_across=out * grasp[1] < 0,
    )
