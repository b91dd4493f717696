"""BVH: our clips survive export and import; foreign T-pose files map onto our joints."""

import numpy as np
import pytest

from hrc_drake.human.bvh import bvh_to_clip, clip_to_bvh, export_bvh, import_bvh
from hrc_drake.human.clip import load_clips


@pytest.mark.parametrize("name", sorted(load_clips()))
def test_export_then_import_gives_the_same_trajectories(name):
    clip = load_clips()[name]
    back = bvh_to_clip(clip_to_bvh(clip), name)
    assert back.fps == pytest.approx(clip.fps)
    assert np.degrees(np.max(np.abs(back.frames - clip.frames))) < 0.1


def test_files_round_trip(tmp_path):
    clip = load_clips()["walk"]
    export_bvh(clip, tmp_path / "walk.bvh")
    back = import_bvh(tmp_path / "walk.bvh", loop=True, animation_distance=1.4)
    assert back.name == "walk" and back.loop
    assert np.allclose(back.frames, clip.frames, atol=np.radians(0.1))


def _chain(name, offset, children=(), end=None):
    body = f"JOINT {name}\n{{\nOFFSET {offset}\nCHANNELS 3 Zrotation Xrotation Yrotation\n"
    body += "".join(children)
    if end:
        body += f"End Site\n{{\nOFFSET {end}\n}}\n"
    return body + "}\n"


def _arm(side, x):
    hand = _chain(f"mixamorig:{side}Hand", f"{x * 25} 0 0", end=f"{x * 18} 0 0")
    forearm = _chain(f"mixamorig:{side}ForeArm", f"{x * 26} 0 0", [hand])
    arm = _chain(f"mixamorig:{side}Arm", f"{x * 12} 0 0", [forearm])
    return _chain(f"mixamorig:{side}Shoulder", f"{x * 6} 10 0", [arm])


def _leg(side, x):
    foot = _chain(f"mixamorig:{side}Foot", "0 -42 0", end="0 -6 15")
    leg = _chain(f"mixamorig:{side}Leg", "0 -42 0", [foot])
    return _chain(f"mixamorig:{side}UpLeg", f"{x * 9} -4 0", [leg])


def _t_pose_file(frame_values: dict[str, tuple[float, float, float]]) -> str:
    """A Mixamo-like T-pose skeleton (cm, Y up, facing +Z) with one frame of rotations."""
    head = _chain("mixamorig:Head", "0 10 2", end="0 18 0")
    neck = _chain("mixamorig:Neck", "0 14 0", [head])
    spine2 = _chain("mixamorig:Spine2", "0 12 0", [neck, _arm("Left", 1), _arm("Right", -1)])
    spine1 = _chain("mixamorig:Spine1", "0 11 0", [spine2])
    spine = _chain("mixamorig:Spine", "0 10 0", [spine1])
    hierarchy = (
        "HIERARCHY\nROOT mixamorig:Hips\n{\nOFFSET 0 0 0\n"
        "CHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation\n"
        + spine
        + _leg("Left", 1)
        + _leg("Right", -1)
        + "}\n"
    )
    names = [
        line.split()[-1].split(":")[-1]
        for line in hierarchy.splitlines()
        if line.startswith(("ROOT", "JOINT"))
    ]
    values = [0.0, 92.0, 0.0]
    for name in names:
        values += list(frame_values.get(name, (0.0, 0.0, 0.0)))
    return hierarchy + "MOTION\nFrames: 1\nFrame Time: 0.0333333\n" + " ".join(map(str, values))


def test_foreign_t_pose_maps_onto_our_joints():
    text = _t_pose_file(
        {
            "LeftArm": (-50.0, 0.0, 0.0),
            "RightArm": (50.0, 0.0, 0.0),
            "LeftLeg": (0.0, 30.0, 0.0),
            "LeftUpLeg": (0.0, -20.0, 0.0),
        }
    )
    clip = bvh_to_clip(text, "mocap")
    q = dict(zip(clip.joint_names, np.degrees(clip.frames[0]), strict=True))
    assert q["left_shoulder_abduction"] == pytest.approx(40.0, abs=0.5)
    assert q["right_shoulder_abduction"] == pytest.approx(40.0, abs=0.5)
    assert q["left_knee_flexion"] == pytest.approx(30.0, abs=0.5)
    assert q["left_hip_flexion"] == pytest.approx(20.0, abs=0.5)
    assert q["right_knee_flexion"] == pytest.approx(0.0, abs=0.5)
    assert clip.frames[0, clip.joint_names.index("pelvis_height")] == pytest.approx(
        0.92 * (0.491 * 1.75) / 0.84, abs=1e-6
    )


def test_missing_bone_is_reported():
    text = _t_pose_file({}).replace("mixamorig:LeftFoot", "mixamorig:LeftPaw")
    with pytest.raises(ValueError, match="left_foot"):
        bvh_to_clip(text, "broken")
