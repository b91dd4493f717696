"""Aim pick, place, reach and hand-over: IK on the human body at the clip's key event.

The clip's pose at its key event (grasp, release, reached, extended) is corrected by IK so
each aiming hand's grasp frame is at its target (hrc_drake.human.grasp: palms on an object's
faces), with the feet where they stand; arms, trunk bend and pelvis height (a squat) are
free. The correction fades in before the event and out after the hold, so the whole clip
stays smooth. A clip that takes an object ends in the carry posture; one that puts an
object down starts from it.
"""

from dataclasses import dataclass, replace

import numpy as np
from pydrake.math import RigidTransform

from hrc_drake.human.authoring import minimum_jerk
from hrc_drake.human.body import FrameTask, HumanBody
from hrc_drake.human.clip import Clip
from hrc_drake.human.grasp import CarryArms, arm_indices, hand_tasks
from hrc_drake.human.skeleton import SIDES

TARGETED = {
    "pick_floor": "grasp",
    "pick_table": "grasp",
    "place_floor": "release",
    "place_table": "release",
    "reach": "reached",
    "hand_over": "extended",
}
"""Clips that accept a target, and the event at which the hands arrive."""

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
    """Joint offset reaching the target, full from `event` to `hold_end`, zero at the ends.

    With `carry`, the arms also blend with a carry posture: into it after the hold (the clip
    takes an object, `takes`) or out of it before the event (it puts one down)."""

    delta: np.ndarray
    event: float
    hold_end: float
    duration: float
    carry: CarryArms | None = None
    takes: bool = False
    spacing: tuple = ()
    """(clip times, arm joint corrections, arm indices) that keep two holding palms as far
    apart as the held object is wide while the arms blend with the carry posture."""

    def weight(self, clip_time: float) -> float:
        if clip_time <= self.event:
            return minimum_jerk(clip_time / self.event)
        if clip_time <= self.hold_end:
            return 1.0
        span = max(self.duration - self.hold_end, 1e-6)
        return 1.0 - minimum_jerk((clip_time - self.hold_end) / span)

    def carried(self, q: np.ndarray, clip_time: float) -> np.ndarray:
        """`q` with the arms blended into (or out of) the carry posture."""
        if self.carry is None:
            return q
        if self.takes:
            span = max(self.duration - self.hold_end, 1e-6)
            q = self.carry.over(q, minimum_jerk((clip_time - self.hold_end) / span))
        else:
            q = self.carry.over(q, 1.0 - minimum_jerk(clip_time / self.event))
        if self.spacing:
            times, fixes, arms = self.spacing
            if times[0] < clip_time < times[-1]:
                q = q.copy()
                q[arms] += [np.interp(clip_time, times, column) for column in fixes.T]
        return q

    def blend_window(self) -> tuple[float, float]:
        """When the arms blend with the carry posture while holding the object."""
        return (self.hold_end, self.duration) if self.takes else (0.0, self.event)


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


def aim_clip(
    body: HumanBody, clip: Clip, placed_pose, hands: dict, carry=None, takes=False
) -> TargetedOffset:
    """The joint offset that makes `clip` (placed in the world by `placed_pose`) put each
    hand's grasp frame at its target: `hands` maps a side to (position, orientation or None).

    `placed_pose(q)` maps a clip pose to the world. Raises Unreachable with a reason.
    """
    event_name = TARGETED[clip.name]
    event = clip.events[event_name]
    q_event = placed_pose(clip.sample(event))
    middle = np.mean([position for position, _ in hands.values()], axis=0)
    base = q_event[[body.index("base_x"), body.index("base_y")]]
    distance = float(np.linalg.norm(middle[:2] - base))
    if distance > MAX_HORIZONTAL_REACH:
        raise Unreachable(f"target {distance:.2f} m away, out of reach without walking")
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
    for squat, oriented in ((False, True), (True, True), (True, False)):
        tasks = hand_tasks(hands if oriented else {s: (p, None) for s, (p, _) in hands.items()})
        solved = body.solve(
            q_event,
            tasks + feet,
            _free_joints(body, tuple(hands), squat),
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
    offset = TargetedOffset(
        solved - q_event, event, _hold_end(clip, event_name), clip.duration, carry, takes
    )
    if carry is None or len(hands) < 2:
        return offset
    width = float(np.linalg.norm(hands["left"][0] - hands["right"][0]))
    return replace(offset, spacing=_keeping_width(body, clip, placed_pose, offset, width))


SPACING_SAMPLES = 6
"""Poses solved across a carry blend to keep the palms on the held object's faces."""


def _keeping_width(body: HumanBody, clip: Clip, placed_pose, offset, width: float):
    """Arm corrections at a few times of the carry blend that put the palms `width` apart
    about their midpoint (zero at the blend's ends, where aim and carry posture are exact)."""
    start, end = offset.blend_window()
    times = np.linspace(start, end, SPACING_SAMPLES)
    arms = arm_indices(body, SIDES)
    fixes = np.zeros((len(times), len(arms)))
    for k, t in enumerate(times[1:-1], start=1):
        q = offset.carried(placed_pose(clip.sample(t)) + offset.weight(t) * offset.delta, t)
        left, right = (body.frame_pose(f"{s}_hand_grasp", q).translation() for s in SIDES)
        middle, across = (left + right) / 2, (left - right) / np.linalg.norm(left - right)
        targets = {
            "left": (middle + across * width / 2, None),
            "right": (middle - across * width / 2, None),
        }
        solved = body.solve(q, hand_tasks(targets), arms, iterations=30, posture_weight=1e-4)
        fixes[k] = solved[arms] - q[arms]
    return times, fixes, arms
