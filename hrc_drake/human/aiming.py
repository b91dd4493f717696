"""The person's hands put on targets by inverse kinematics on the body, the feet kept where
they stand, and the joint offsets that aim a clip (`AimedMotion`): what targeting.py and
hand_ways.py both build on.

The IK moves the aiming arms and the trunk; where the hands cannot get there otherwise the
person squats (pelvis height and legs), and a target that still stays out of reach is
`Unreachable`. Feet outrank hands: the person bends rather than sliding a foot.
"""

from dataclasses import dataclass, replace

import numpy as np
from pydrake.math import RigidTransform

from hrc_drake.human.body import FrameTask, HumanBody
from hrc_drake.human.grasp import arm_indices, hand_tasks
from hrc_drake.human.keyed_clips import minimum_jerk
from hrc_drake.human.rotations import compose, decompose
from hrc_drake.human.skeleton import SIDES

HAND_TOLERANCE = 0.02
WAYPOINT_TOLERANCE = 0.06
"""m: hands on their way (rising beside the body, over a surface's edge) need only come
near their waypoints; the arms are then kept clear of the furniture all the way
(hrc_drake.human.clearance)."""
FOOT_TOLERANCE = 0.01
FEET_WEIGHT = (4.0, 4.0, 4.0)
"""Feet outrank hands in the IK: the person bends rather than sliding a foot."""
TRUNK = (
    "pelvis_height",
    "pelvis_tilt",
    "lumbar_flexion",
    "lumbar_bending",
    "thorax_flexion",
    "thorax_rotation",
)
PALM_ORIENTATION = 1.0
"""Weight of a palm's orientation reaching for a target."""
FOREARM = 0.3
"""m: how far behind a hand raised above the shoulders its elbow is put (`forearms_level`):
about a forearm's length and the hand's to its grasp frame (0.26 m and 0.05 m for a
1.75 m person)."""
ELBOW_WEIGHT = 0.3
"""Weight of the raised elbows' place against the hands' (1): they guide the arms' shape,
the hands still go to their targets."""


class Unreachable(ValueError):
    """The person cannot put a hand on the target without stepping."""


@dataclass(frozen=True, eq=False)
class AimedMotion:
    """Joint offsets that aim a clip: at each key time an offset added to the clip's pose;
    in between they ease from key to key (minimum jerk), or run straight through the evenly
    spaced keys of a carried object's way (`paths`; the way itself eases the object)."""

    times: tuple[float, ...]
    offsets: tuple[np.ndarray, ...]
    paths: tuple[tuple[int, int], ...] = ()
    """(first key, last key) of each stretch that is one smooth movement."""
    hands: tuple[str, ...] = ()
    """The sides whose hands are aimed."""
    held: tuple[float, float] = (0.0, 0.0)
    """The clip times between which the aimed hands are on their targets or hold what they
    took (on their way there and back they are free)."""
    resting: "HangingArm | None" = None
    """The arm that is not aimed, hanging at ease: one hand takes or puts down, and the
    other does not reach out with it into the air (towards a robot standing there, a
    user's machine-tending cell)."""

    def holds(self, clip_time: float) -> bool:
        return self.held[0] <= clip_time <= self.held[1]

    def offset(self, clip_time: float) -> np.ndarray:
        times = self.times
        if clip_time <= times[0]:
            return self.offsets[0]
        if clip_time >= times[-1]:
            return self.offsets[-1]
        for first, last in self.paths:
            if times[first] <= clip_time <= times[last]:
                return self._along(first, last, clip_time)
        k = int(np.searchsorted(times, clip_time, side="right")) - 1
        s = minimum_jerk((clip_time - times[k]) / (times[k + 1] - times[k]))
        return self.offsets[k] + s * (self.offsets[k + 1] - self.offsets[k])

    def _along(self, first: int, last: int, clip_time: float) -> np.ndarray:
        span = self.times[last] - self.times[first]
        u = (clip_time - self.times[first]) / span * (last - first)
        k = min(int(u), last - first - 1)
        a, b = self.offsets[first + k], self.offsets[first + k + 1]
        return a + (u - k) * (b - a)

    def with_the_other_arm_at_ease(self, body: HumanBody, idle) -> "AimedMotion":
        """This motion with the arm that is not aimed hanging as in the `idle` clip's first
        pose."""
        (free,) = (side for side in SIDES if side not in self.hands)
        return replace(self, resting=HangingArm.of(body, free, idle.sample(0.0)))

    def pose(self, placed: np.ndarray, clip_time: float) -> np.ndarray:
        q = placed + self.offset(clip_time)
        return q if self.resting is None else self.resting.over(q)


CHEST = (
    "pelvis_tilt",
    "pelvis_list",
    "lumbar_flexion",
    "lumbar_bending",
    "thorax_flexion",
    "thorax_rotation",
)
"""The joints from the pelvis's heading to the chest, in order (the body's joint frames
are not turned: each turns about its own axis in the frame of the one before)."""
SHOULDER = ("shoulder_flexion", "shoulder_abduction", "shoulder_rotation")
"""A shoulder's joints, in order."""
DEEP_BEND, ELBOW_PER_BEND = 0.8, 1.2
"""Beyond DEEP_BEND (rad) of the trunk from upright, the hanging arm's elbow bends by
ELBOW_PER_BEND times as much: stooping to the floor, the hand hung to the floor (0.96 cm
into it, cooperation) and into the wall of a floor bin (a user's packing cell)."""


@dataclass(frozen=True, eq=False)
class HangingArm:
    """An arm hanging at ease as it does standing, however the trunk bends and turns: the
    shoulder turns so that the upper arm keeps its standing orientation in the world. Held
    at its standing joint angles, it went up behind the back of a person stooping over a
    floor bin (a user's packing cell)."""

    arm: np.ndarray
    standing: np.ndarray
    chest: tuple[np.ndarray, list]
    """CHEST's joint indices and axes."""
    shoulder: tuple[np.ndarray, list]
    """The shoulder's joint indices and axes."""
    upper_arm: np.ndarray
    """The upper arm's orientation standing, in the frame of the pelvis's heading."""
    elbow: int

    @classmethod
    def of(cls, body: HumanBody, side: str, standing: np.ndarray) -> "HangingArm":
        chest, shoulder = (
            _joints(body, names) for names in (CHEST, [f"{side}_{n}" for n in SHOULDER])
        )
        upper_arm = _turned(chest, standing) @ _turned(shoulder, standing)
        arm = arm_indices(body, (side,))
        return cls(
            arm, standing[arm], chest, shoulder, upper_arm, body.index(f"{side}_elbow_flexion")
        )

    def over(self, q: np.ndarray) -> np.ndarray:
        """q with this arm hanging."""
        q[self.arm] = self.standing
        chest = _turned(self.chest, q)
        indices, axes = self.shoulder
        q[indices] = decompose(chest.T @ self.upper_arm, axes)[0]
        bend = np.arccos(np.clip(chest[2, 2], -1.0, 1.0))
        q[self.elbow] += ELBOW_PER_BEND * max(bend - DEEP_BEND, 0.0)
        return q


def _joints(body: HumanBody, names) -> tuple[np.ndarray, list]:
    """The joints' indices and axes."""
    indices = np.array([body.index(n) for n in names])
    return indices, [body.plant.GetJointByName(n).revolute_axis() for n in names]


def _turned(joints: tuple[np.ndarray, list], q: np.ndarray) -> np.ndarray:
    """The rotation of a chain of `joints` (indices, axes) at q."""
    indices, axes = joints
    return compose(axes, q[indices])


def _free_joints(body: HumanBody, sides, squat: bool) -> np.ndarray:
    """Arms of the aiming hands and the trunk; with `squat` also pelvis height and legs."""
    names = [n for n in body.joint_names if n in TRUNK and (squat or n != "pelvis_height")]
    parts = [(side, ("shoulder", "elbow", "wrist")) for side in sides]
    if squat:
        parts += [(side, ("hip", "knee", "ankle")) for side in SIDES]
    for side, joints in parts:
        names += [n for n in body.joint_names if n.startswith(side) and any(j in n for j in joints)]
    return np.array([body.index(n) for n in names])


def _feet_tasks(body: HumanBody, q: np.ndarray) -> list[FrameTask]:
    tasks = []
    for side in SIDES:
        X: RigidTransform = body.frame_pose(f"{side}_sole", q)
        tasks.append(
            FrameTask(
                f"{side}_sole",
                X.translation(),
                X.rotation(),
                FEET_WEIGHT,
                rotation_weights=(1.0, 1.0, 1.0),
            )
        )
    return tasks


def hands_on(
    body: HumanBody,
    q: np.ndarray,
    hands: dict,
    turning: bool | None = None,
    tolerance: float = HAND_TOLERANCE,
) -> np.ndarray:
    """q with the aiming hands' grasp frames on their targets, within `tolerance`, the feet
    where they stand (a squat if the hands cannot reach otherwise). With `turning` the palms
    may turn about their normals (the fingers pointing where the arms put them best); by
    default two palms on an object's faces do. Raises Unreachable."""
    feet = _feet_tasks(body, q)
    both = len(hands) == 2 if turning is None else turning
    for squat, oriented in ((False, True), (True, True), (True, False)):
        aimed = hands if oriented else {s: (p, None) for s, (p, _) in hands.items()}
        tasks = hand_tasks(aimed, PALM_ORIENTATION, turn_in_palm=both)
        solved = _solved(body, q, tasks, feet, _free_joints(body, tuple(hands), squat))
        hand_error = body.task_error(solved, tasks)
        if hand_error > tolerance and not squat and _overhead(body, q, hands):
            solved = _solved(body, q, tasks, feet, arm_indices(body, tuple(hands)))
            solved = _solved(body, solved, tasks, feet, _free_joints(body, tuple(hands), squat))
            hand_error = body.task_error(solved, tasks)
        feet_error = body.task_error(solved, feet) / FEET_WEIGHT[0]
        if hand_error <= tolerance and feet_error <= FOOT_TOLERANCE:
            return solved
    if hand_error <= tolerance:
        raise Unreachable("only reachable by stepping")
    raise Unreachable(f"out of reach: the hand stays {hand_error:.2f} m from the target")


def forearms_level(body: HumanBody, q: np.ndarray, hands: dict, heading: float) -> np.ndarray:
    """q with the hands near their targets above the shoulders, each elbow raised behind its
    hand, level with it (FOREARM back along `heading`): where the IK from the clip's pose
    lifts them with the elbows low, the forearms rise steeply to the hands and pass through
    the edge of the surface the targets are on (a box on a shelf's 1.6 m top board: the
    arms 2.6-10.2 cm into the shelf, standing 0.35-0.75 m from it, a 1.75 m person). The
    start of the IK that puts them on the targets (`hands_on` keeps near it). q as it is
    when no target is above its shoulder."""
    if not _overhead(body, q, hands):
        return q
    back = FOREARM * np.array([np.cos(heading), np.sin(heading), 0.0])
    elbows = [
        FrameTask(f"{side}_forearm", np.asarray(p) - back, position_weights=(ELBOW_WEIGHT,) * 3)
        for side, (p, _) in hands.items()
    ]
    tasks = hand_tasks(hands, PALM_ORIENTATION, turn_in_palm=True) + elbows
    return body.solve(
        q, tasks + _feet_tasks(body, q), _free_joints(body, tuple(hands), False), iterations=300
    )


def arms_toward(body: HumanBody, q: np.ndarray, hands: dict) -> np.ndarray:
    """q with the `hands` arms moved as close to their targets (position, orientation or
    None) as the arms alone get, the trunk and legs as they are: hands lowered by the whole
    body bent the trunk and threw the head down and back up (putting a part down on a 0.75 m
    table, 4.2 m/s)."""
    tasks = hand_tasks(hands, PALM_ORIENTATION)
    return _solved(body, q, tasks, _feet_tasks(body, q), arm_indices(body, tuple(hands)))


def _overhead(body: HumanBody, q: np.ndarray, hands: dict) -> bool:
    """Whether a hand aims above its shoulder: there the trunk, free with the arms from the
    start, leans back against its limits before the arms rise (a carton's sides at 1.70 m,
    0.55 m ahead: the hands stayed 13 cm short); solved from the arms' own solve, they reach
    within 1 cm."""
    return any(
        p[2] > body.frame_pose(f"{side}_upper_arm", q).translation()[2]
        for side, (p, _) in hands.items()
    )


def _solved(body: HumanBody, q: np.ndarray, tasks, feet, free: np.ndarray) -> np.ndarray:
    return body.solve(q, tasks + feet, free, iterations=150, posture_weight=1e-3)


def offset_to(body, placed_pose, clip, time, start, targets, fallback):
    """The offset at clip `time` that puts the hands on `targets` (IK from the clip's pose
    there plus `start`), or `fallback` where they cannot get there without stepping."""
    placed = placed_pose(clip.sample(time))
    try:
        return hands_on(body, placed + start, targets) - placed
    except Unreachable:
        return fallback
