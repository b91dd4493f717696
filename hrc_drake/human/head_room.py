"""The head clear of the furniture: a person leaning in to take a box from a shelf's middle
board passes the forehead under the edge of the board above it, where a clip authored in an
empty room would put it through that edge. Before the arms are checked
(hrc_drake.human.clearance), the planned poses are checked for the head (its neck, skull
and face shapes); where it goes in, the person ducks: the spine and neck bend it out (the
joints above the pelvis, so that no foot moves) while the arms keep both hands where the
plan has them (a hand on its way to a box goes on its way; one that holds keeps its hold).

The head moving fast into an edge needs its correction before it gets there: each joint's
correction is made at most PACE of its size per second, begun before and ended after it is
needed (`_paced`), and the arms are solved again for the paced trunk."""

from functools import lru_cache

import numpy as np

from hrc_drake.human.arm_shapes import HEAD, Prisms, check_arm, corners_in_world, parts_shapes
from hrc_drake.human.body import FrameTask, HumanBody
from hrc_drake.human.clearance import (
    EASE,
    MARGIN,
    NEAR,
    PUSH_STEPS,
    PUSHES,
    TOLERANCE,
    VERIFICATIONS,
    ArmCorrection,
    instants,
)
from hrc_drake.human.grasp import arm_indices
from hrc_drake.human.skeleton import SIDES

SPINE = (
    "lumbar_flexion",
    "lumbar_bending",
    "thorax_flexion",
    "thorax_rotation",
    "neck_flexion",
    "neck_rotation",
)
"""The joints that move the head out: above the pelvis, so no foot moves with them."""
PACE = 3.0
"""1/s: a joint's correction grows and shrinks by at most this share of its largest value
per second (a correction of 0.3 rad at 0.9 rad/s: the pace of a person ducking, not a jerk)."""
HAND_STEPS = 20
"""IK steps that bring the hands back to where the plan has them after the trunk moved."""


def head_correction(body: HumanBody, furniture, pose, start: float, end: float):
    """The correction that keeps the head out of `furniture` while `pose(t)` is played from
    `start` to `end` (None: it keeps clear as it is); it eases in over EASE after `start`
    unless the head is in the furniture there."""
    prisms = Prisms.of(furniture)
    if len(prisms.axes) == 0:
        return None
    times = instants(start, end)
    poses = np.array([pose(float(t)) for t in times])
    inside = np.flatnonzero(_head_depths(body, prisms, poses) > TOLERANCE)
    if len(inside) == 0:
        return None
    spine = _spine(body)
    needed = {}
    corrected = poses
    eased_in = 1.0 if inside[0] == 0 else np.clip((times - start) / EASE, 0.0, 1.0)[:, None]
    for _ in range(VERIFICATIONS):
        for k in inside:
            near = prisms.near(poses[k][:2], NEAR)
            needed[k] = (_ducked(body, near, corrected[k], poses[k]) - poses[k])[spine]
        paced = _paced(times, needed) * eased_in
        corrected = np.array(
            [
                _hands_kept(body, q, offset) if offset.any() else q
                for q, offset in zip(poses, paced, strict=True)
            ]
        )
        inside = np.flatnonzero(_head_depths(body, prisms, corrected) > TOLERANCE)
        if len(inside) == 0:
            break
    return _keyed(times, corrected - poses)


def _head_depths(body: HumanBody, prisms: Prisms, poses: np.ndarray) -> np.ndarray:
    """How deep the head goes into the prisms near each pose (-inf: none is near)."""
    corners = corners_in_world(body, poses, (HEAD,))
    radii, shapes, _ = parts_shapes(body, (HEAD,))
    return prisms.deepest_near(poses[:, :2], NEAR, corners, radii, shapes).max(axis=1)


def _ducked(body: HumanBody, near: Prisms, q: np.ndarray, planned: np.ndarray) -> np.ndarray:
    """q with the head pushed out of `near` by the spine, the hands kept where `planned` has
    them."""
    hands = _hand_tasks(body, planned)
    moved = q
    for _ in range(PUSHES):
        check = check_arm(body, near, moved, HEAD)
        if check.depth <= TOLERANCE:
            break
        target = check.at + (check.depth + MARGIN) * check.out
        tasks = [FrameTask(check.frame, target, point=tuple(check.point)), *hands]
        free = np.concatenate([_spine(body), arm_indices(body, SIDES)])
        moved = body.solve(moved, tasks, free, iterations=PUSH_STEPS, posture_weight=1e-3)
    return moved


def _hands_kept(body: HumanBody, q: np.ndarray, spine_offset: np.ndarray) -> np.ndarray:
    """q with the spine moved by `spine_offset` and the arms solved to keep the hands where q
    has them."""
    moved = q.copy()
    moved[_spine(body)] += spine_offset
    return body.solve(moved, _hand_tasks(body, q), arm_indices(body, SIDES), iterations=HAND_STEPS)


def _hand_tasks(body: HumanBody, q: np.ndarray) -> list[FrameTask]:
    """Both hands' grasp frames kept where q has them, and as they are turned."""
    tasks = []
    for side in SIDES:
        X = body.frame_pose(f"{side}_hand_grasp", q)
        tasks.append(
            FrameTask(f"{side}_hand_grasp", X.translation(), X.rotation(), (1.0,) * 3, (1.0,) * 3)
        )
    return tasks


def _paced(times: np.ndarray, needed: dict) -> np.ndarray:
    """The spine's offset at each of `times` (times × joints): for each joint, the largest
    of the `needed` ones (index of its time -> offset) shrunk by PACE per second from its
    own time, so that it begins before it is needed and ends after it."""
    at = times[list(needed)]
    offsets = np.array(list(needed.values()))
    reach = np.clip(1.0 - np.abs(times[:, None] - at[None, :]) * PACE, 0.0, None)
    shrunk = reach[:, :, None] * offsets[None, :, :]
    largest = np.abs(shrunk).argmax(axis=1)
    return np.take_along_axis(shrunk, largest[:, None, :], axis=1)[:, 0, :]


def _keyed(times: np.ndarray, offsets: np.ndarray) -> ArmCorrection:
    """The offsets as a correction: keys from the last zero before the first change to the
    first zero after the last, or, if the offsets still change the pose at the end, one
    EASE after it (the pose at the end is the one the next activity takes over from)."""
    changed = np.flatnonzero(np.abs(offsets).max(axis=1) > 0.0)
    first, last = max(changed[0] - 1, 0), min(changed[-1] + 1, len(times) - 1)
    keys = [(float(times[k]), offsets[k]) for k in range(first, last + 1)]
    if changed[-1] == len(times) - 1:
        keys.append((float(times[-1]) + EASE, np.zeros_like(offsets[-1])))
    return ArmCorrection(tuple(t for t, _ in keys), tuple(o for _, o in keys))


@lru_cache(maxsize=4)
def _spine(body: HumanBody) -> np.ndarray:
    return np.array([body.index(n) for n in SPINE])
