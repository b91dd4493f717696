"""The built-in clips (models/human/animations/*.json): the catalogue and its writer.

Every clip is authored for the default person: the keyed ones from key poses
(hrc_drake.human.keyed_clips), walking and carrying from published gait figures
(hrc_drake.modelgen.gait); `turn_right` is `turn_left` mirrored.
"""

from pathlib import Path

from hrc_drake.human.body import HumanBody, human_body
from hrc_drake.human.clip import Clip, save_clip
from hrc_drake.human.keyed_clips import (
    HOLD,
    Key,
    KeyedSpec,
    Layer,
    keyed_clip,
    mirrored_clip,
    turn_spec,
)
from hrc_drake.modelgen.gait import GaitSpec, gait_clip

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
    turn_spec("turn_left", 60.0),
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
        "Raise the hands in front of the chest, look at what they hold, turn it, lower them "
        "again (holding something, the arms keep the carry posture).",
        (
            Key(0.0),
            Key(0.8, INSPECT),
            Key(1.6, {**INSPECT, "wrist_deviation": 15, "shoulder_rotation": 28}),
            Key(2.4, {**INSPECT, "wrist_deviation": -15, "shoulder_rotation": 45}),
            Key(3.2, INSPECT),
            Key(4.0),
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


def write_clips(models_dir: Path) -> list[Path]:
    """Write every built-in clip into `models_dir`/human/animations; returns the paths."""
    folder = models_dir / "human" / "animations"
    folder.mkdir(parents=True, exist_ok=True)
    return [save_clip(clip, folder) for clip in build_clips().values()]
