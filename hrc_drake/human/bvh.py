"""BVH motion capture import and export for the human skeleton.

Export writes our skeleton (bones named as in Mixamo/CMU: Hips, Spine, Spine1, Head, LeftArm,
LeftForeArm, LeftHand, LeftUpLeg, LeftLeg, LeftFoot, ...) Y-up, facing +Z, in centimetres,
ZXY rotation channels. Import reads any BVH whose bones carry the common names: it composes
each bone's world orientation, corrects for the file's rest pose (a T-pose, say) by the
rotation between its bone directions and ours, and splits the rotation between two mapped
bones into our joint angles (the solution inside the range of motion, nearest to the previous
frame). Bones we do not have (LeftShoulder, Spine2, Neck, fingers) are folded into the next
mapped bone; the root translation is scaled by the ratio of leg lengths.
"""

import re
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from hrc_drake.human.body import HumanBody, human_body
from hrc_drake.human.clip import Clip
from hrc_drake.human.rotations import (
    AXES,
    axis_rotation,
    compose,
    decompose,
    minimal_rotation,
    padded_axes,
)

BVH_FROM_OURS = np.array([[0.0, 1.0, 0.0], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]])
"""Our frame (x forward, y left, z up) -> BVH frame (X left, Y up, Z forward)."""

CENTIMETRES = 100.0
ROTATION_ORDER = "ZXY"
ROOT_ROTATION = ("base_yaw", "pelvis_tilt", "pelvis_list")
ROOT_TRANSLATION = ("base_x", "base_y", "pelvis_height")


@dataclass(frozen=True)
class Bone:
    """A BVH bone standing for one of our bodies; `names` are accepted spellings on import."""

    body: str
    names: tuple[str, ...]
    tip: str
    """The body whose joint the bone points at, `end:<part>` for a leaf, "" for the root (whose
    rest orientation is the file's own: upright, facing forward)."""


def _sided_bones(side: str) -> tuple[Bone, ...]:
    cap = side.capitalize()
    return (
        Bone(f"{side}_upper_arm", (f"{cap}Arm", f"{cap}UpperArm"), f"{side}_forearm"),
        Bone(f"{side}_forearm", (f"{cap}ForeArm", f"{cap}LowerArm"), f"{side}_hand"),
        Bone(f"{side}_hand", (f"{cap}Hand",), "end:hand"),
        Bone(f"{side}_thigh", (f"{cap}UpLeg", f"{cap}UpperLeg", f"{cap}Thigh"), f"{side}_shank"),
        Bone(f"{side}_shank", (f"{cap}Leg", f"{cap}LowerLeg", f"{cap}Shin"), f"{side}_foot"),
        Bone(f"{side}_foot", (f"{cap}Foot",), "end:foot"),
    )


BONES = (
    Bone("pelvis", ("Hips", "Hip", "Pelvis", "Root"), ""),
    Bone("abdomen", ("Spine", "LowerBack", "Abdomen"), "chest"),
    Bone("chest", ("Spine1", "Chest", "Spine2", "UpperChest", "Spine3"), "head"),
    Bone("head", ("Head",), "end:head"),
    *_sided_bones("left"),
    *_sided_bones("right"),
)


# --- our skeleton as BVH bones -------------------------------------------------------------


class _Rig:
    """Per-bone facts of our skeleton: DoF indices and axes, rest offsets and tips."""

    def __init__(self, body: HumanBody):
        self.body = body
        skeleton = body.skeleton
        self.parent_bone = {}
        bone_bodies = {bone.body for bone in BONES}
        for bone in BONES[1:]:
            parent = skeleton.body(bone.body).parent
            while parent not in bone_bodies:
                parent = skeleton.body(parent).parent
            self.parent_bone[bone.body] = parent
        self.dofs = {bone.body: self._dofs(bone.body) for bone in BONES}
        self.offset = {bone.body: self._offset(bone.body) for bone in BONES}
        self.ends = {
            "end:hand": np.array([0.0, 0.0, -body.sizes["hand"]]),
            "end:foot": np.array(
                [body.sizes["foot"] - body.sizes["heel_back"], 0.0, -body.sizes["ankle_height"]]
            ),
            "end:head": np.array([0.0, 0.0, body.skeleton.height * 0.17]),
        }

    def _dofs(self, name: str):
        if name == "pelvis":
            names = ROOT_ROTATION
        else:
            names = []
            body = self.body.skeleton.body(name)
            while True:
                names = [dof.name for dof in body.dofs] + names
                if body.parent == self.parent_bone[name]:
                    break
                body = self.body.skeleton.body(body.parent)
        dofs = {dof.name: dof for dof in self.body.skeleton.dofs}
        return [self.body.index(n) for n in names], [np.array(dofs[n].axis, float) for n in names]

    def _offset(self, name: str) -> np.ndarray:
        """Joint position relative to the parent bone's joint, in the rest pose (our frame)."""
        skeleton = self.body.skeleton
        if name == "pelvis":
            return np.zeros(3)
        offset, body = np.zeros(3), skeleton.body(name)
        while True:
            offset += body.origin
            if body.parent == self.parent_bone[name]:
                return offset
            body = skeleton.body(body.parent)

    def tip(self, bone: Bone) -> np.ndarray:
        return self.ends[bone.tip] if bone.tip.startswith("end:") else self.offset[bone.tip]

    def local_rotation(self, name: str, q: np.ndarray) -> np.ndarray:
        indices, axes = self.dofs[name]
        return compose(axes, q[indices])


def _bvh_name(bone: Bone) -> str:
    return bone.names[0]


def _euler_zxy(rotation_ours: np.ndarray) -> np.ndarray:
    rotation = BVH_FROM_OURS @ rotation_ours @ BVH_FROM_OURS.T
    return np.degrees(decompose(rotation, [AXES[a] for a in ROTATION_ORDER])[0])


def clip_to_bvh(clip: Clip, body: HumanBody | None = None) -> str:
    """BVH text of a clip (our skeleton, centimetres, Y up, facing +Z)."""
    rig = _Rig(body or human_body())
    lines = ["HIERARCHY"]
    children = {
        name: [b for b in BONES[1:] if rig.parent_bone[b.body] == name] for name in rig.dofs
    }

    def write(bone: Bone, depth: int) -> None:
        pad = "  " * depth
        offset = CENTIMETRES * BVH_FROM_OURS @ rig.offset[bone.body]
        if bone.body == "pelvis":
            lines.append(f"ROOT {_bvh_name(bone)}")
            channels = "CHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation"
        else:
            lines.append(f"{pad}JOINT {_bvh_name(bone)}")
            channels = "CHANNELS 3 Zrotation Xrotation Yrotation"
        lines.extend([f"{pad}{{", f"{pad}  OFFSET {_numbers(offset)}", f"{pad}  {channels}"])
        for child in children[bone.body]:
            write(child, depth + 1)
        if bone.tip.startswith("end:"):
            end = CENTIMETRES * BVH_FROM_OURS @ rig.ends[bone.tip]
            lines.extend(
                [
                    f"{pad}  End Site",
                    f"{pad}  {{",
                    f"{pad}    OFFSET {_numbers(end)}",
                    f"{pad}  }}",
                ]
            )
        lines.append(f"{pad}}}")

    write(BONES[0], 0)
    order = _depth_first(BONES[0], children)
    lines += ["MOTION", f"Frames: {len(clip.frames)}", f"Frame Time: {1.0 / clip.fps:.8f}"]
    translation = [clip.joint_names.index(n) for n in ROOT_TRANSLATION]
    for q in _in_body_order(clip, rig.body):
        values = [CENTIMETRES * BVH_FROM_OURS @ q[translation]]
        values += [_euler_zxy(rig.local_rotation(bone.body, q)) for bone in order]
        lines.append(_numbers(np.concatenate(values)))
    return "\n".join(lines) + "\n"


def _in_body_order(clip: Clip, body: HumanBody) -> np.ndarray:
    columns = [clip.joint_names.index(name) for name in body.joint_names]
    return clip.frames[:, columns]


def _depth_first(bone: Bone, children) -> list[Bone]:
    order = [bone]
    for child in children[bone.body]:
        order += _depth_first(child, children)
    return order


def _numbers(values) -> str:
    return " ".join(f"{v:.6f}" for v in values)


# --- import ------------------------------------------------------------------------------------


@dataclass
class _Joint:
    name: str
    parent: int
    offset: np.ndarray
    channels: list[str]
    end: np.ndarray | None = None


def _parse(text: str) -> tuple[list[_Joint], np.ndarray, float]:
    tokens = text.split()
    joints: list[_Joint] = []
    stack: list[int] = []
    i, in_end = 0, False
    while tokens[i] != "MOTION":
        token = tokens[i]
        if token in ("ROOT", "JOINT"):
            joints.append(_Joint(tokens[i + 1], stack[-1] if stack else -1, np.zeros(3), []))
            i += 2
        elif token == "End":
            in_end, i = True, i + 2
        elif token == "{":
            stack.append(-2 if in_end else len(joints) - 1)
            i += 1
        elif token == "}":
            stack.pop()
            in_end, i = False, i + 1
        elif token == "OFFSET":
            offset = np.array([float(v) for v in tokens[i + 1 : i + 4]])
            if stack[-1] == -2:
                joints[stack[-2]].end = offset
            else:
                joints[-1].offset = offset
            i += 4
        elif token == "CHANNELS":
            count = int(tokens[i + 1])
            joints[-1].channels = tokens[i + 2 : i + 2 + count]
            i += 2 + count
        else:
            i += 1
    frame_count = int(tokens[tokens.index("Frames:", i) + 1])
    frame_time = float(tokens[tokens.index("Time:", i) + 1])
    start = tokens.index("Time:", i) + 2
    width = sum(len(j.channels) for j in joints)
    values = np.array(tokens[start : start + frame_count * width], dtype=float)
    return joints, values.reshape(frame_count, width), frame_time


def _plain_name(name: str) -> str:
    """`mixamorig:LeftArm` / `Character1_LeftArm` -> `leftarm`."""
    return re.split(r"[:|]", name)[-1].split("_")[-1].lower()


def _match_bones(joints: list[_Joint]) -> dict[str, int]:
    by_name = {_plain_name(j.name): k for k, j in enumerate(joints)}
    matched = {}
    for bone in BONES:
        found = next((by_name[n.lower()] for n in bone.names if n.lower() in by_name), None)
        if found is None:
            raise ValueError(
                f"BVH has no bone for our {bone.body} (looked for {', '.join(bone.names)})"
            )
        matched[bone.body] = found
    return matched


def _world_rotations(joints: list[_Joint], frame: np.ndarray) -> list[np.ndarray]:
    rotations, column = [], 0
    for joint in joints:
        local = np.eye(3)
        for channel in joint.channels:
            if channel.endswith("rotation"):
                local = local @ axis_rotation(AXES[channel[0].upper()], np.radians(frame[column]))
            column += 1
        rotations.append(local if joint.parent < 0 else rotations[joint.parent] @ local)
    return rotations


def _rest_direction(joints: list[_Joint], index: int, target: int | None) -> np.ndarray:
    """Rest-pose direction from joint `index` to joint `target`, or to the end of its chain."""
    offset = np.zeros(3)
    if target is not None:
        k = target
        while k != index:
            offset += joints[k].offset
            k = joints[k].parent
        return offset
    k = index
    while joints[k].end is None:
        k = next(c for c, joint in enumerate(joints) if joint.parent == k)
        offset += joints[k].offset
    return offset + joints[k].end


def _choose(solutions: list[np.ndarray], count: int, lower, upper, previous) -> np.ndarray:
    """The decomposition inside the limits, with zero padded angles, nearest the last frame."""

    def score(angles):
        used = angles[:count]
        outside = np.sum(np.maximum(lower - used, 0) + np.maximum(used - upper, 0))
        padding = np.sum(np.abs(angles[count:]))
        near = 0.0 if previous is None else 1e-3 * np.sum(np.abs(used - previous))
        return outside + padding + near

    return min(solutions, key=score)[:count]


def bvh_to_clip(
    text: str,
    name: str,
    body: HumanBody | None = None,
    loop: bool = False,
    events: dict | None = None,
    animation_distance: float = 0.0,
) -> Clip:
    """A clip for our skeleton from BVH text with the common bone names."""
    rig = _Rig(body or human_body())
    joints, values, frame_time = _parse(text)
    matched = _match_bones(joints)
    ours_from_bvh = BVH_FROM_OURS.T
    rest = {"pelvis": np.eye(3)}
    for bone in BONES[1:]:
        tip = None if bone.tip.startswith("end:") else matched[bone.tip]
        theirs = ours_from_bvh @ _rest_direction(joints, matched[bone.body], tip)
        rest[bone.body] = minimal_rotation(rig.tip(bone), theirs)
    root = joints[matched["pelvis"]]
    leg = np.linalg.norm(joints[matched["left_shank"]].offset) + np.linalg.norm(
        joints[matched["left_foot"]].offset
    )
    scale = (rig.body.sizes["thigh"] + rig.body.sizes["shank"]) / leg
    frames = np.zeros((len(values), len(rig.body.joint_names)))
    previous = {}
    for k, frame in enumerate(values):
        worlds = _world_rotations(joints, frame)
        ours = {
            b.body: ours_from_bvh @ worlds[matched[b.body]] @ BVH_FROM_OURS @ rest[b.body]
            for b in BONES
        }
        q = frames[k]
        position = frame[[i for i, c in enumerate(root.channels) if c.endswith("position")]]
        q[[rig.body.index(n) for n in ROOT_TRANSLATION]] = scale * ours_from_bvh @ position
        for bone in BONES:
            parent = rig.parent_bone.get(bone.body)
            local = ours[bone.body] if parent is None else ours[parent].T @ ours[bone.body]
            indices, axes = rig.dofs[bone.body]
            solutions = decompose(local, padded_axes(axes))
            angles = _choose(
                solutions,
                len(indices),
                rig.body.lower[indices],
                rig.body.upper[indices],
                previous.get(bone.body),
            )
            q[indices] = angles
            previous[bone.body] = angles
        frames[k] = q
    yaw = rig.body.index("base_yaw")
    frames[:, yaw] = np.unwrap(frames[:, yaw])
    return Clip(
        name,
        rig.body.joint_names,
        frames,
        1.0 / frame_time,
        loop,
        dict(events or {}),
        animation_distance,
    )


def export_bvh(clip: Clip, path: Path) -> None:
    Path(path).write_text(clip_to_bvh(clip))


def import_bvh(path: Path, **metadata) -> Clip:
    """Read a BVH file into a clip named after the file (`metadata`: loop, events, ...)."""
    path = Path(path)
    return bvh_to_clip(path.read_text(), path.stem, **metadata)
