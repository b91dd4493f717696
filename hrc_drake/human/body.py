"""A person's kinematics on Drake: forward kinematics and a small damped-least-squares IK.

Joint vectors in hrc_drake.human are in the skeleton's canonical order (`Skeleton.joint_names`,
SI units); `HumanBody.plant_positions` reorders them into the MultibodyPlant's q.
"""

import threading
from dataclasses import dataclass
from functools import lru_cache

import numpy as np
from pydrake.math import RigidTransform, RotationMatrix
from pydrake.multibody.parsing import Parser
from pydrake.multibody.plant import MultibodyPlant
from pydrake.multibody.tree import JacobianWrtVariable

from hrc_drake.human.anthropometry import DEFAULT_HEIGHT, DEFAULT_MASS, build_skeleton
from hrc_drake.human.sdf import MODEL_NAME, human_sdf
from hrc_drake.human.skeleton import SIDES

LARGEST_STEP = 0.5
"""rad: no joint moves further in one step (scaled down as a whole): near a singular arm the
damped step is huge and the solve can leave for a far branch (a right arm reaching a
carton's side at head height swung its abduction to 180 degrees in five steps and ended
1.1 m off)."""
LIMIT_PASSES = 4
"""Times an IK step is solved again without the joints it pushes into their limits."""
SETTLED = 1e-10
"""rad (m for the pelvis): a solve stops once no joint moves further than this in a step.
The posture term holds the damped least squares short of its tasks where it balances what
is left of their error, which then stays above `tolerance` (a hand 0.1 mm off its target):
such solves settled in 5 to 20 steps and ran on to their cap of 60 or 150, moving no joint
by more than 1e-12."""


def parse_human(plant: MultibodyPlant, height: float, mass: float, name: str = MODEL_NAME):
    """Add the person to `plant` (not finalized) and return the model instance."""
    sdf = human_sdf(height, mass).replace(f'<model name="{MODEL_NAME}">', f'<model name="{name}">')
    (instance,) = Parser(plant).AddModelsFromString(sdf, "sdf")
    return instance


@dataclass(frozen=True)
class FrameTask:
    """Drive a frame of the person towards a world pose; zero weights leave an axis free.

    `rotation` is the target orientation; `rotation_weights` weigh the error about the world
    x, y, z axes (e.g. (1, 1, 0) keeps a sole flat but lets it yaw).
    """

    frame: str
    position: np.ndarray
    rotation: RotationMatrix | None = None
    position_weights: tuple[float, float, float] = (1.0, 1.0, 1.0)
    rotation_weights: tuple[float, float, float] = (0.0, 0.0, 0.0)
    point: tuple[float, float, float] = (0.0, 0.0, 0.0)
    """The point of the frame that should reach `position` (frame coordinates)."""
    rotation_axes: RotationMatrix | None = None
    """The axes `rotation_weights` weigh the orientation error about (default: the
    world's), e.g. the target's own, to leave a hand free to turn about its palm's normal."""
    turns_forearm: str = ""
    """The side whose forearm turns to hold this frame's orientation (a palm turned to face
    down), free of FOREARM_STIFFNESS; "" for none."""


FOREARM_STIFFNESS = 30.0
"""How much more the IK's posture term holds a forearm's pronation where it is than any
other joint, unless a task turns that forearm (`FrameTask.turns_forearm`): the clips keep
the forearm at its mid-position, and the aims and ways that were made without the joint
went elsewhere with it free (a 5th-percentile woman's carton 2.3 cm off her palm, a hand
3.5 cm into a box just put down)."""


class HumanBody:
    """Forward and inverse kinematics of one person (own plant, never part of a Diagram)."""

    def __init__(self, height: float = DEFAULT_HEIGHT, mass: float = DEFAULT_MASS):
        self.skeleton = build_skeleton(height, mass)
        self.joint_names = self.skeleton.joint_names
        self.plant = MultibodyPlant(0.0)
        parse_human(self.plant, height, mass)
        self.plant.Finalize()
        self.context = self.plant.CreateDefaultContext()
        self.plant_index = np.array(
            [self.plant.GetJointByName(n).position_start() for n in self.joint_names]
        )
        dofs = self.skeleton.dofs
        self.lower = np.array([dof.limits[0] for dof in dofs])
        self.upper = np.array([dof.limits[1] for dof in dofs])
        self.is_revolute = np.array([dof.kind == "revolute" for dof in dofs])
        self.sizes = self.skeleton.dimensions
        self.pronation = {side: self.index(f"{side}_wrist_pronation") for side in SIDES}
        self.stiffness = np.ones(len(dofs))
        self.stiffness[list(self.pronation.values())] = FOREARM_STIFFNESS

    def index(self, joint: str) -> int:
        return self.joint_names.index(joint)

    def plant_positions(self, q: np.ndarray) -> np.ndarray:
        """Canonical joint vector -> the plant's position vector."""
        plant_q = np.empty(len(q))
        plant_q[self.plant_index] = q
        return plant_q

    def set(self, q: np.ndarray) -> None:
        self.plant.SetPositions(self.context, self.plant_positions(q))

    def world_poses(self, frames, plant_q: np.ndarray) -> list[RigidTransform]:
        """World poses of the plant's `frames` at its position vector `plant_q`."""
        self.plant.SetPositions(self.context, plant_q)
        return [frame.CalcPoseInWorld(self.context) for frame in frames]

    def frame_pose(self, frame: str, q: np.ndarray | None = None) -> RigidTransform:
        if q is not None:
            self.set(q)
        return self.plant.GetFrameByName(frame).CalcPoseInWorld(self.context)

    def sole_points(self, q: np.ndarray) -> dict[str, np.ndarray]:
        """World positions of the heel and toe under each foot: `{'left_heel': xyz, ...}`."""
        self.set(q)
        half = self.sizes["foot"] / 2
        points = {}
        for side in SIDES:
            frame = self.plant.GetFrameByName(f"{side}_sole")
            X = frame.CalcPoseInWorld(self.context)
            points[f"{side}_heel"] = X @ np.array([-half, 0.0, 0.0])
            points[f"{side}_toe"] = X @ np.array([half, 0.0, 0.0])
        return points

    def standing_pose(self) -> np.ndarray:
        """Upright, arms relaxed at the sides, soles on the floor."""
        q = np.zeros(len(self.joint_names))
        q[self.index("pelvis_height")] = self.sizes["hip_height"]
        return q

    def solve(
        self,
        q: np.ndarray,
        tasks: list[FrameTask],
        free: np.ndarray,
        iterations: int = 30,
        posture_weight: float = 1e-3,
        tolerance: float = 1e-5,
    ) -> np.ndarray:
        """Damped least squares over the `free` joint indices, inside the joint limits.

        The posture term keeps unconstrained directions near the start pose `q`, so authored
        style survives the correction. Stops within `tolerance`, once `SETTLED` or after
        `iterations` steps.
        """
        q_ref = q.copy()
        q = q.copy()
        weights = posture_weight * self._stiffness(tasks)
        for _ in range(iterations):
            error, jacobian = self._task_errors(q, tasks)
            if np.linalg.norm(error) < tolerance:
                break
            step = self._step(q, q_ref, free, error, jacobian, weights)
            moved = np.clip(q[free] + step, self.lower[free], self.upper[free])
            settled = np.abs(moved - q[free]).max(initial=0.0) <= SETTLED
            q[free] = moved
            if settled:
                break
        return q

    def _stiffness(self, tasks: list[FrameTask]) -> np.ndarray:
        """Each joint's stiffness for the posture term: the forearms' pronation held where it
        is but for those the tasks turn."""
        turned = {task.turns_forearm for task in tasks} - {""}
        if not turned:
            return self.stiffness
        stiffness = self.stiffness.copy()
        stiffness[[self.pronation[side] for side in turned]] = 1.0
        return stiffness

    def _step(self, q, q_ref, free, error, jacobian, weights) -> np.ndarray:
        """One damped least-squares step of the `free` joints; joints at a limit that the
        step would push further into it are held and the step solved again without them
        (clipped, they would absorb the step and leave the task where it was: a hand
        reaching up that only leans the trunk back against its limit)."""
        moving = np.ones(len(free), dtype=bool)
        step = np.zeros(len(free))
        for _ in range(LIMIT_PASSES):
            J = jacobian[:, free[moving]]
            held = weights[free[moving]]
            posture = held * (q_ref[free[moving]] - q[free[moving]])
            lhs = J.T @ J + np.diag(held + 1e-6)
            step[:] = 0.0
            step[moving] = np.linalg.solve(lhs, J.T @ error + posture)
            pushing = ((q[free] <= self.lower[free]) & (step < 0)) | (
                (q[free] >= self.upper[free]) & (step > 0)
            )
            if not pushing.any():
                break
            moving &= ~pushing
        largest = np.abs(step).max(initial=0.0)
        return step if largest <= LARGEST_STEP else step * (LARGEST_STEP / largest)

    def task_error(self, q: np.ndarray, tasks: list[FrameTask]) -> float:
        """Largest weighted position error of the tasks (m)."""
        self.set(q)
        worst = 0.0
        for task in tasks:
            X = self.plant.GetFrameByName(task.frame).CalcPoseInWorld(self.context)
            weighted = (task.position - X @ np.array(task.point)) * np.array(task.position_weights)
            worst = max(worst, float(np.linalg.norm(weighted)))
        return worst

    def _task_errors(self, q: np.ndarray, tasks: list[FrameTask]):
        self.set(q)
        world = self.plant.world_frame()
        errors, rows = [], []
        for task in tasks:
            frame = self.plant.GetFrameByName(task.frame)
            X = frame.CalcPoseInWorld(self.context)
            point = np.array(task.point)
            J = self.plant.CalcJacobianSpatialVelocity(
                self.context, JacobianWrtVariable.kQDot, frame, point, world, world
            )[:, self.plant_index]
            wp = np.array(task.position_weights)
            errors.append(wp * (task.position - X @ point))
            rows.append(wp[:, None] * J[3:])
            if task.rotation is not None:
                error, rotation_rows = _rotation_error(task, X.rotation(), J[:3])
                errors.append(error)
                rows.append(rotation_rows)
        return np.concatenate(errors), np.vstack(rows)


def _rotation_error(task: FrameTask, R: RotationMatrix, rows: np.ndarray):
    """The weighted orientation error of a frame at R and its rows of the Jacobian (`rows`:
    the frame's angular velocity). An axis of `rotation_axes` that weighs nothing is left
    free: the error is then how far the frame's own axis is turned from the target's
    (the angle between them, about their cross product), whatever the turn about it; the
    angle-axis of the whole difference, projected, mixes a large turn about that axis into
    the others and the solve diverges (two palms on a box at head height: 4 to 60 degrees
    off their faces, more the longer it ran)."""
    weights = np.array(task.rotation_weights)
    if task.rotation_axes is not None and (weights == 0.0).sum() == 1:
        free = int(np.argmin(weights))
        axis, target = R.col(free), task.rotation_axes.col(free)
        turn = np.cross(axis, target)
        sine = np.linalg.norm(turn)
        error = turn / sine * np.arctan2(sine, axis @ target) if sine > 1e-12 else np.zeros(3)
        across = np.eye(3) - np.outer(axis, axis)
        weight = weights.max()
        return weight * error, weight * (across @ rows)
    delta = (task.rotation @ R.transpose()).ToAngleAxis()
    error, rows = delta.axis() * delta.angle(), rows
    if task.rotation_axes is not None:
        axes = task.rotation_axes.matrix()
        error, rows = axes.T @ error, axes.T @ rows
    return weights * error, weights[:, None] * rows


def human_body(height: float = DEFAULT_HEIGHT, mass: float = DEFAULT_MASS) -> HumanBody:
    """Shared kinematics of a person of this size (building a plant takes ~50 ms), one per
    thread: its context holds a pose, so two simulations at once (a Dask worker's threads)
    must not share it."""
    return _human_body(height, mass, threading.get_ident())


@lru_cache(maxsize=16)
def _human_body(height: float, mass: float, thread: int) -> HumanBody:
    return HumanBody(height, mass)
