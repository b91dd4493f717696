"""Inverse kinematics for tool targets: joint positions that put the tcp at a pose.

Solutions respect the joint limits, keep the clearance to the static cell, keep the wrist
(A5) on the side it is on (no wrist flips), and prefer postures near both the current one
and the nominal posture (home), which also keeps A4 and A6 from turning a full circle.
"""

import math

import numpy as np
from pydrake.math import RigidTransform, RotationMatrix
from pydrake.multibody.inverse_kinematics import (
    InverseKinematics,
    MinimumDistanceLowerBoundConstraint,
)
from pydrake.solvers import Solve

from hrc_drake.iisy import LINK_NAMES
from hrc_drake.motion.errors import PlanningFailed

POSITION_TOLERANCE = 1e-4
"""m: IK accuracy; the robot's arrival error comes on top of it."""
ANGLE_TOLERANCE = np.radians(0.1)
WRIST_MARGIN = np.radians(2.0)
"""A5 stays at least this far from its singular zero."""
WRIST = 4
"""Index of A5."""
NEAR_SEEDS = 4
"""Random starts near the nominal posture, tried before starts anywhere."""
SEED_SPREAD = 0.6
"""rad: standard deviation of the extra seeds around the nominal posture."""
TOOL_REACH_MARGIN = 0.25
"""m beyond the nominal reach that still counts as maybe reachable (tool, offsets)."""
CLEARANCE_INFLUENCE = 0.05
"""m beyond the clearance (the checker's padding) at which distances start to count."""
WRIST_SLACK = 0.001
"""m the wrist may lie beyond the arm's length before a pose counts as out of reach, on top
of what the solver's tolerances let it move (rounding, the solver's own feasibility)."""


class ArmLength:
    """Tool poses no joint positions reach, known from the arm's link lengths without a
    solve: the wrist (link_6's origin, fixed in the tool's frame) lies at most the summed
    distances between the joints' origins (each on its joint's axis, so each distance the
    same in every posture) from the shoulder (link_2's origin, on a circle about A1's axis).
    A solve that cannot succeed costs every start of the budget; this costs microseconds."""

    def __init__(self, model):
        plant, context = model.plant, model.plant.CreateDefaultContext()
        plant.SetPositions(context, model.variant.home)
        origins = [
            plant.GetBodyByName(name, model.arm).body_frame().CalcPoseInWorld(context).translation()
            for name in LINK_NAMES[2:]
        ]
        self.length = float(np.linalg.norm(np.diff(origins, axis=0), axis=1).sum())
        a1 = plant.GetJointByName("A1", model.arm)
        X_a1 = a1.frame_on_parent().CalcPoseInWorld(context)
        self.axis_point, self.axis = X_a1.translation(), X_a1.rotation() @ a1.revolute_axis()
        self.shoulder = self._cylindrical(origins[0])
        """(distance from A1's axis, height along it) of the shoulder's circle."""
        wrist = model.tcp.CalcPoseInWorld(context).inverse() @ origins[-1]
        self.wrist_along, wrist_aside = float(wrist[2]), float(np.hypot(wrist[0], wrist[1]))
        """The wrist in the tool's frame: along its axis, and its distance off the axis
        (a circle round it, the tool's turn about its axis being free)."""
        self.slack = (
            wrist_aside
            + math.sqrt(3.0) * POSITION_TOLERANCE
            + abs(self.wrist_along) * ANGLE_TOLERANCE
            + WRIST_SLACK
        )

    def _cylindrical(self, point: np.ndarray) -> tuple[float, float]:
        offset = point - self.axis_point
        along = float(offset @ self.axis)
        return float(np.linalg.norm(offset - along * self.axis)), along

    def beyond(self, pose: RigidTransform) -> bool:
        """Whether no joint positions put the tool at `pose` (its axis within the solver's
        tolerances): the wrist would lie beyond the arm's length from every shoulder
        position."""
        return self.wrist_distance(pose) > self.length + self.slack

    def wrist_distance(self, pose: RigidTransform) -> float:
        """How far from the shoulder's circle the wrist of the tool at `pose` lies (its
        centre, when the wrist lies off the tool's axis)."""
        wrist = pose.translation() + self.wrist_along * pose.rotation().col(2)
        radial, along = self._cylindrical(wrist)
        return math.hypot(radial - self.shoulder[0], along - self.shoulder[1])


class ToolTargetSolver:
    """Solves tool targets on one PlanningModel."""

    def __init__(self, model, q_nominal: np.ndarray):
        self.model = model
        self.q_nominal = np.asarray(q_nominal, dtype=float)
        self.arm_length = ArmLength(model)
        self.shoulder = model.plant.GetBodyByName("link_2", model.arm).body_frame()
        self._clearance_constraint = MinimumDistanceLowerBoundConstraint(
            model.checker, 0.0, model.checker_context, None, CLEARANCE_INFLUENCE
        )

    def solve(
        self,
        pose: RigidTransform,
        q_start: np.ndarray,
        free_rotation: bool,
        rng: np.random.Generator,
        attempts: int,
    ) -> np.ndarray:
        """A collision-free solution, starting from the current posture, home, then random
        postures: `attempts` starts in all (a count, not a time, so the outcome never
        depends on how busy the machine is)."""
        self._check_reach(pose, q_start)
        wrist_sign = self._wrist_side(q_start)
        seeds = self._seeds(q_start, rng, attempts)  # drawn all the same: the stream goes on
        for seed in [] if self.arm_length.beyond(pose) else seeds:
            q = self._solve_from(pose, seed, q_start, free_rotation, wrist_sign)
            if q is not None:
                return q
        raise PlanningFailed(
            f"target unreachable: no collision-free inverse kinematics solution for the tool at "
            f"{np.round(pose.translation(), 3).tolist()}"
        )

    def reaches(
        self,
        pose: RigidTransform,
        q_start: np.ndarray,
        free_rotation: bool,
        rng: np.random.Generator,
        attempts: int,
        clearance: bool = True,
    ) -> bool:
        """Whether `solve` with the same arguments finds a solution, found faster: every
        start without the clearance constraint first (one whose solution is collision-free
        settles it, none that solves settles it too), and only then, for the starts whose
        solutions collide, the slow solves that keep the clearance, as `solve` tries them.
        Without `clearance`, a solution need only not touch the cell (the end of a linear
        move, which keeps no clearance)."""
        try:
            self._check_reach(pose, q_start)
        except PlanningFailed:
            return False
        colliding = []
        for seed, q in self._unconstrained(pose, q_start, free_rotation, rng, attempts):
            if q is not None and (self.model.collision_free(q) if clearance else self._apart(q)):
                return True
            if q is not None and clearance:
                colliding.append(seed)
        wrist_sign = self._wrist_side(q_start)
        q_reference = 0.5 * (q_start + self.q_nominal)
        return any(
            (q := self._solve(pose, seed, q_reference, free_rotation, wrist_sign, True)) is not None
            and self.model.collision_free(q)
            for seed in colliding
        )

    def _apart(self, q: np.ndarray) -> bool:
        """The robot at q touches neither the cell nor itself (no clearance kept)."""
        return self.model.apart(q)

    def kinematic_solution(
        self, pose: RigidTransform, q_start: np.ndarray, free_rotation: bool, rng, attempts: int
    ) -> np.ndarray | None:
        """A solution that ignores the cell (collisions and the clearance), from the same
        starts as `solve`: whether the arm could be there at all."""
        solutions = self._unconstrained(pose, q_start, free_rotation, rng, attempts)
        return next((q for _, q in solutions if q is not None), None)

    def _unconstrained(self, pose, q_start, free_rotation, rng, attempts):
        """(start, its solution without the clearance constraint or None) for each start of
        a solve, in turn (None without a solve where the arm is too short)."""
        wrist_sign = self._wrist_side(q_start)
        q_reference = 0.5 * (q_start + self.q_nominal)
        seeds = self._seeds(q_start, rng, attempts)
        beyond = self.arm_length.beyond(pose)
        for seed in seeds:
            yield (
                seed,
                (
                    None
                    if beyond
                    else self._solve(pose, seed, q_reference, free_rotation, wrist_sign, False)
                ),
            )

    def _seeds(self, q_start: np.ndarray, rng: np.random.Generator, attempts: int) -> list:
        """The starts of a solve: the current posture, home, then random postures."""
        return ([q_start, self.q_nominal] + self._random_seeds(rng, attempts - 2))[:attempts]

    def _random_seeds(self, rng: np.random.Generator, count: int) -> list[np.ndarray]:
        """`count` seeds: near the nominal posture first, then anywhere (other elbow and arm
        postures)."""
        lower, upper = self.model.lower, self.model.upper
        near = [
            np.clip(self.q_nominal + rng.normal(0.0, SEED_SPREAD, lower.size), lower, upper)
            for _ in range(min(count, NEAR_SEEDS))
        ]
        return near + [rng.uniform(lower, upper) for _ in range(count - len(near))]

    def solve_near(self, pose: RigidTransform, q_near: np.ndarray) -> np.ndarray | None:
        """The solution nearest `q_near`, seeded there, without the clearance check."""
        return self._solve(pose, q_near, q_near, False, self._wrist_side(q_near), False)

    def _solve_from(self, pose, seed, q_start, free_rotation, wrist_sign) -> np.ndarray | None:
        """Without the clearance constraint first (fast); with it when that collides."""
        q_reference = 0.5 * (q_start + self.q_nominal)
        for with_clearance in (False, True):
            q = self._solve(pose, seed, q_reference, free_rotation, wrist_sign, with_clearance)
            if q is not None and self.model.collision_free(q):
                return q
            if q is None:
                return None
        return None

    def _solve(self, pose, seed, q_reference, free_rotation, wrist_sign, with_clearance):
        model = self.model
        ik = InverseKinematics(model.plant, model.plant_context, with_joint_limits=True)
        world = model.plant.world_frame()
        p = pose.translation()
        ik.AddPositionConstraint(
            model.tcp, np.zeros(3), world, p - POSITION_TOLERANCE, p + POSITION_TOLERANCE
        )
        if free_rotation:
            z_target = pose.rotation().col(2)
            ik.AddAngleBetweenVectorsConstraint(
                world, z_target, model.tcp, [0.0, 0.0, 1.0], 0.0, ANGLE_TOLERANCE
            )
        else:
            ik.AddOrientationConstraint(
                world, pose.rotation(), model.tcp, RotationMatrix(), ANGLE_TOLERANCE
            )
        q = ik.q()
        program = ik.get_mutable_prog()
        if with_clearance:
            program.AddConstraint(self._clearance_constraint, q)
        program.AddQuadraticErrorCost(np.eye(q.size), q_reference, q)
        wrist_low, wrist_high = _wrist_bounds(model, wrist_sign)
        program.AddBoundingBoxConstraint(wrist_low, wrist_high, q[WRIST])
        program.SetInitialGuess(q, seed)
        result = Solve(program)
        return result.GetSolution(q) if result.is_success() else None

    def _check_reach(self, pose: RigidTransform, q_start: np.ndarray) -> None:
        self.model.plant.SetPositions(self.model.plant_context, q_start)
        shoulder = self.shoulder.CalcPoseInWorld(self.model.plant_context).translation()
        distance = np.linalg.norm(pose.translation() - shoulder)
        limit = self.model.variant.reach + TOOL_REACH_MARGIN
        if distance > limit:
            raise PlanningFailed(
                f"target unreachable: {distance:.2f} m from the shoulder, beyond the "
                f"{self.model.variant.name}'s reach"
            )

    def _wrist_side(self, q: np.ndarray) -> float:
        """+1 or -1: the side of A5 to stay on (the current one, else the nominal one)."""
        reference = q[WRIST] if abs(q[WRIST]) > WRIST_MARGIN else self.q_nominal[WRIST]
        return 1.0 if reference >= 0.0 else -1.0


def _wrist_bounds(model, wrist_sign: float) -> tuple[float, float]:
    if wrist_sign > 0:
        return WRIST_MARGIN, model.upper[WRIST]
    return model.lower[WRIST], -WRIST_MARGIN
