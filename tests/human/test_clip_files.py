"""Motion in and out through `hrc-drake clip`, checked against a third-party BVH library
(pybvh): a CMU-style take it writes imports onto our joints, a clip exported here reads there
with the same joint angles and the same joint positions, and a scenario plays its own clip."""

import numpy as np
import pybvh
import pytest
from pydrake.systems.analysis import Simulator

from hrc_drake.builder import build_diagram
from hrc_drake.cli import main
from hrc_drake.human.body import human_body
from hrc_drake.human.bvh import BVH_FROM_OURS, CENTIMETRES
from hrc_drake.human.clip import load_clip, load_clips
from hrc_drake.human.messages import AnimateCommand
from hrc_drake.scenario import load_scenario

CMU_CHANNELS = "CHANNELS 3 Zrotation Yrotation Xrotation"


def _joint(name: str, offset: str, *children: str, end: str | None = None) -> str:
    text = f"JOINT {name}\n{{\nOFFSET {offset}\n{CMU_CHANNELS}\n" + "".join(children)
    if end is not None:
        text += f"End Site\n{{\nOFFSET {end}\n}}\n"
    return text + "}\n"


def _cmu_leg(side: str, x: float) -> str:
    toe = _joint(f"{side}ToeBase", "0 -0.4 2.3", end="0 0 1.1")
    foot = _joint(f"{side}Foot", f"{x * 0.1} -7.0 0", toe)
    leg = _joint(f"{side}Leg", f"{x * 0.1} -7.2 0", foot)
    up_leg = _joint(f"{side}UpLeg", f"{x * 1.4} -1.8 0.8", leg)
    return _joint(f"{side[0]}HipJoint", "0 0 0", up_leg)


def _cmu_arm(side: str, x: float) -> str:
    hand = _joint(f"{side}Hand", f"{x * 3.3} 0 0", end=f"{x * 1.2} 0 0")
    forearm = _joint(f"{side}ForeArm", f"{x * 4.9} 0 0", hand)
    arm = _joint(f"{side}Arm", f"{x * 3.1} 0 0", forearm)
    return _joint(f"{side}Shoulder", f"{x * 0.3} 1.2 0", arm)


def cmu_skeleton() -> str:
    """A skeleton as the CMU motion-capture database's BVH conversions have it: T-pose, Y up,
    facing +Z, hip joints and two neck bones we do not have, Z-Y-X rotation channels."""
    head = _joint("Head", "0 1.6 0", end="0 1.6 0")
    neck = _joint("Neck", "0 0.5 0", _joint("Neck1", "0 1.7 0", head))
    spine1 = _joint("Spine1", "0 2.1 0", neck, _cmu_arm("Left", 1), _cmu_arm("Right", -1))
    lower_back = _joint("LowerBack", "0 0 0", _joint("Spine", "0 2.0 0", spine1))
    hierarchy = (
        "HIERARCHY\nROOT Hips\n{\nOFFSET 0 0 0\n"
        "CHANNELS 6 Xposition Yposition Zposition Zrotation Yrotation Xrotation\n"
        + lower_back
        + _cmu_leg("Left", 1)
        + _cmu_leg("Right", -1)
        + "}\n"
    )
    rest = " ".join(["0"] * (6 + 3 * hierarchy.count("JOINT")))
    return hierarchy + f"MOTION\nFrames: 1\nFrame Time: 0.0083333\n{rest}\n"


KNEE_DEG = np.array([0.0, 20.0, 40.0, 60.0])


def test_a_cmu_take_written_by_pybvh_imports_onto_our_joints(tmp_path):
    (tmp_path / "rest.bvh").write_text(cmu_skeleton())
    take = pybvh.read_bvh_file(tmp_path / "rest.bvh")
    frames = len(KNEE_DEG)
    angles = np.zeros((frames, len(take.joint_names), 3))
    column = {"Z": 0, "Y": 1, "X": 2}
    angles[:, take.joint_names.index("LeftLeg"), column["X"]] = np.radians(KNEE_DEG)
    angles[:, take.joint_names.index("LeftArm"), column["Z"]] = np.radians(-50.0)
    angles[:, take.joint_names.index("RightArm"), column["Z"]] = np.radians(50.0)
    take.root_pos = np.tile([3.0, 16.5, -2.0], (frames, 1)) + np.outer(range(frames), [0, 0, 1])
    take.joint_angles = angles
    take.frame_time = 1 / 120
    take.write(tmp_path / "cmu_take.bvh")

    assert (
        main(["clip", "import", str(tmp_path / "cmu_take.bvh"), "-o", str(tmp_path / "t.json")])
        == 0
    )
    clip = load_clip(tmp_path / "t.json")
    q = {name: clip.frames[:, i] for i, name in enumerate(clip.joint_names)}
    assert clip.name == "cmu_take" and clip.fps == pytest.approx(120.0)
    assert np.degrees(q["left_knee_flexion"]) == pytest.approx(KNEE_DEG, abs=0.5)
    assert np.degrees(q["right_knee_flexion"]) == pytest.approx(0.0, abs=0.5)
    assert np.degrees(q["left_shoulder_abduction"]) == pytest.approx(40.0, abs=0.5)
    assert np.degrees(q["right_shoulder_abduction"]) == pytest.approx(40.0, abs=0.5)
    # The take starts where the person stands and walks forward (the file's +Z).
    assert (q["base_x"][0], q["base_y"][0]) == pytest.approx((0.0, 0.0))
    assert np.all(np.diff(q["base_x"]) > 0) and np.abs(q["base_y"]).max() < 1e-9


@pytest.mark.parametrize("name", ["walk", "pick_floor", "wave"])
def test_an_exported_clip_reads_in_pybvh_with_the_same_joint_angles(tmp_path, name):
    assert main(["clip", "export", name, "-o", str(tmp_path / f"{name}.bvh")]) == 0
    take = pybvh.read_bvh_file(tmp_path / f"{name}.bvh")
    clip = load_clips()[name]
    q = {joint: clip.frames[:, i] for i, joint in enumerate(clip.joint_names)}
    assert take.frame_count == len(clip.frames) and take.fps == pytest.approx(clip.fps)
    zxy = take.joint_angles  # channels Z, X, Y: X is our y axis, about which the knees bend
    for side, bvh_side in (("left", "Left"), ("right", "Right")):
        knee = zxy[:, take.joint_names.index(f"{bvh_side}Leg")]
        assert knee[:, 1] == pytest.approx(q[f"{side}_knee_flexion"], abs=1e-5)
        assert np.abs(knee[:, [0, 2]]).max() < 1e-5
    body = human_body()
    columns = [clip.joint_names.index(joint) for joint in body.joint_names]
    positions = take.node_positions() / CENTIMETRES @ BVH_FROM_OURS  # -> our frame, metres
    nodes = [node.name for node in take.nodes]
    for bone, ours in (("LeftLeg", "left_shank"), ("RightHand", "right_hand"), ("Head", "head")):
        for k in range(0, len(clip.frames), 7):
            expected = body.frame_pose(ours, clip.frames[k, columns]).translation()
            assert positions[k, nodes.index(bone)] == pytest.approx(expected, abs=1e-4)


def test_a_scenario_plays_its_own_clip(tmp_path):
    assert main(["clip", "export", "wave", "-o", str(tmp_path / "greet.bvh")]) == 0
    scenario_file = tmp_path / "greeting.yaml"
    scenario_file.write_text(
        "name: greeting\nrobot: {variant: lbr_iisy3_r760}\n"
        "human: {start: [1.5, 0.0, 180.0], clips: [greet.bvh]}\n"
    )
    diagram = build_diagram(load_scenario(scenario_file))
    simulator = Simulator(diagram)
    context = simulator.get_context()
    command = diagram.GetInputPort("human_actor.human_tree_command")
    command.FixValue(context, AnimateCommand(seq=1, animation_name="greet"))
    simulator.AdvanceTo(2.0)
    status = diagram.GetOutputPort("human_status").Eval(context)
    assert status.animation == "greet" and status.results.last.outcome != "rejected"
    assert status.right_hand[2] > 1.6  # the right hand is raised above the head to wave


def test_a_bad_clip_file_is_one_line_naming_the_scenario_field(tmp_path, capsys):
    (tmp_path / "broken.bvh").write_text("HIERARCHY\nROOT Hips\n{\n")
    scenario = tmp_path / "s.yaml"
    scenario.write_text(
        "name: s\nrobot: {variant: lbr_iisy3_r760}\nhuman:\n  clips: [broken.bvh]\n"
    )
    assert main(["validate", str(scenario)]) == 2
    error = capsys.readouterr().err.strip()
    assert error.startswith(f"hrc-drake: error: {scenario}:4: human.clips[0]: ")
    assert "broken.bvh: not a usable clip" in error and "\n" not in error
    assert main(["clip", "import", str(tmp_path / "broken.bvh")]) == 2
