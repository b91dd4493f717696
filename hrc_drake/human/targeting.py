"""Aim pick, place, reach and hand-over at a point: IK on the human body at the clip's key event.

The clip's pose at its key event (grasp, release, reached, extended) is corrected by IK so the
hand (or the midpoint of both hands) is at the target with the feet where they stand; arms,
trunk bend and pelvis height (a squat) are free. The correction fades in before the event and
out after the hold, so the whole clip stays smooth.
"""

from dataclasses import dataclass

import numpy as np
from pydrake.math import RigidTransform

from hrc_drake.human.authoring import minimum_jerk
from hrc_drake.human.body import FrameTask, HumanBody
from hrc_drake.human.clip import Clip
from hrc_drake.human.skeleton import SIDES

TARGETED = {
    "pick_floor": ("grasp", SIDES),
    "pick_table": ("grasp", SIDES),
    "place_floor": ("release", SIDES),
    "place_table": ("release", SIDES),
    "reach": ("reached", ("right",)),
    "hand_over": ("extended", ("right",)),
}
"""Clips that accept a target: the event at which the hands arrive, and which hands."""

HAND_TOLERANCE = 0.02
FOOT_TOLERANCE = 0.01
FEET_WEIGHT = (4.0, 4.0, 4.0)
"""Feet outrank hands in the IK: the person bends rather than sliding a foot."""
HOLD_AFTER_EVENT = 0.3
MAX_HORIZONTAL_REACH = 1.2
TRUNK = (
    "pelvis_height",
    "pelvis_tilt",
    "lumbar_flexion",
    "lumbar_bending",
    "thorax_flexion",
    "thorax_rotation",
)


class Unreachable(ValueError):
    """The person cannot put a hand on the target without stepping."""


@dataclass(frozen=True, eq=False)
class TargetedOffset:
    """Joint offset reaching the target, full from `event` to `hold_end`, zero at the ends."""

    delta: np.ndarray
    event: float
    hold_end: float
    duration: float

    def weight(self, clip_time: float) -> float:
        if clip_time <= self.event:
            return minimum_jerk(clip_time / self.event)
        if clip_time <= self.hold_end:
            return 1.0
        span = max(self.duration - self.hold_end, 1e-6)
        return 1.0 - minimum_jerk((clip_time - self.hold_end) / span)


def _hold_end(clip: Clip, event: str) -> float:
    later = sorted(t for t in clip.events.values() if t > clip.events[event])
    return later[0] if later else min(clip.events[event] + HOLD_AFTER_EVENT, clip.duration)


def _free_joints(body: HumanBody, sides, squat: bool) -> np.ndarray:
    """Arms of the aiming hands and the trunk; with `squat` also pelvis height and legs."""
    names = [n for n in body.joint_names if n in TRUNK and (squat or n != "pelvis_height")]
    parts = [(side, ("shoulder", "elbow", "wrist")) for side in sides]
    if squat:
        parts += [(side, ("hip", "knee", "ankle")) for side in SIDES]
    for side, joints in parts:
        names += [n for n in body.joint_names if n.startswith(side) and any(j in n for j in joints)]
    return np.array([body.index(n) for n in names])


def aim_clip(body: HumanBody, clip: Clip, placed_pose, target) -> TargetedOffset:
    """The joint offset that makes `clip` (placed in the world by `placed_pose`) reach `target`.

    `placed_pose(q)` maps a clip pose to the world. Raises Unreachable with a reason.
    """
    event_name, sides = TARGETED[clip.name]
    event = clip.events[event_name]
    q_event = placed_pose(clip.sample(event))
    target = np.asarray(target, dtype=float)
    base = q_event[[body.index("base_x"), body.index("base_y")]]
    distance = float(np.linalg.norm(target[:2] - base))
    if distance > MAX_HORIZONTAL_REACH:
        raise Unreachable(f"target {distance:.2f} m away, out of reach without walking")
    hands = {s: body.frame_pose(f"{s}_hand_grasp", q_event).translation() for s in sides}
    middle = np.mean(list(hands.values()), axis=0)
    tasks = [FrameTask(f"{s}_hand_grasp", target + hands[s] - middle) for s in sides]
    feet = []
    for side in SIDES:
        X: RigidTransform = body.frame_pose(f"{side}_sole", q_event)
        feet.append(
            FrameTask(
                f"{side}_sole",
                X.translation(),
                X.rotation(),
                FEET_WEIGHT,
                rotation_weights=(1.0, 1.0, 1.0),
            )
        )
    for squat in (False, True):
        solved = body.solve(
            q_event,
            tasks + feet,
            _free_joints(body, sides, squat),
            iterations=150,
            posture_weight=1e-3,
        )
        hand_error = body.task_error(solved, tasks)
        feet_error = body.task_error(solved, feet) / FEET_WEIGHT[0]
        if hand_error <= HAND_TOLERANCE and feet_error <= FOOT_TOLERANCE:
            break
    else:
        reason = (
            "only reachable by stepping"
            if hand_error <= HAND_TOLERANCE
            else (f"hand stays {hand_error:.2f} m from the target")
        )
        raise Unreachable(reason)
    return TargetedOffset(solved - q_event, event, _hold_end(clip, event_name), clip.duration)
