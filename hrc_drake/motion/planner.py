"""Motion planning with Drake alone: inverse kinematics, collision-free joint paths, timing.

`MotionPlanner.plan(command, q_start)` turns a move command into a TimedPath at nominal
speed, or raises PlanningFailed with a reason a person can act on. Planning is deterministic:
its random sampling draws from a Generator seeded afresh for every plan from the planner's
stream of the run's seed (hrc_drake.seeding), and its budgets are
counts (inverse-kinematics starts, search-tree nodes, TOPP-RA grid points), never wall time,
so a plan comes out the same on a busy machine or a loaded sweep worker.
"""

import contextlib

import numpy as np
from pydrake.math import RigidTransform, RotationMatrix

from hrc_drake.motion.errors import PlanningFailed
from hrc_drake.motion.ik import ToolTargetSolver
from hrc_drake.motion.linear import linear_waypoints
from hrc_drake.motion.messages import MoveJoints, MoveLinear, MoveTo
from hrc_drake.motion.model import HeldPart, PlanningModel, RestingObject
from hrc_drake.motion.options import MotionOptions
from hrc_drake.motion.roadmap import collision_free_waypoints
from hrc_drake.motion.timing import TimedPath, polyline_path, spline_path, time_path
from hrc_drake.station import StationSpec

HOLDING = "(with the part the robot holds, kept as clear of the cell as the tool)"
"""Said of a free-space move that failed with a part held: the tool alone may have made it."""
AMONG_OBJECTS = (
    "no path to the target keeps the robot out of the objects resting in the cell (one "
    "without them was found): lift what it holds higher over them first, or move them"
)
"""Said of a free-space move only the resting objects kept from its target."""
ARRIVED = 1e-6
"""Joint distance (rad) below which a target counts as the start: nothing to move."""


class MotionPlanner:
    """Plans the moves of one station's robot among its static cell."""

    def __init__(self, station: StationSpec, options: MotionOptions, seed: np.random.SeedSequence):
        self.station = station
        self.options = options
        self.seed = seed
        self.model = PlanningModel(station, options.clearance)
        self.ik = ToolTargetSolver(self.model, np.array(self.model.variant.home))

    def plan(
        self,
        command,
        q_start,
        person_xy=None,
        held: HeldPart | None = None,
        objects: tuple[RestingObject, ...] = (),
    ):
        """The timed path for `command` from `q_start`; None when already there. With
        `person_xy`, the person standing there is an obstacle for this plan. A free-space
        move keeps `held`, what the tool holds, as clear of the cell as the tool, and the
        robot out of the resting `objects` on its way (not at its ends); a linear move takes
        a part off or sets it down on what it rests on, as the tree tells it, and neither
        ends deeper in a resting object than a touch. A held
        part still on (or near) what it was taken off fails at once, where the arm alone is
        clear (the path search says when it is not), and says how to go on."""
        if person_xy is not None:
            self._check_target_clear_of(person_xy, command)
        carried = None if isinstance(command, MoveLinear) else held
        arm_clear = carried is not None and self.model.collision_free(np.asarray(q_start))
        with self.model.holding(carried):
            if arm_clear and not self.model.collision_free(np.asarray(q_start)):
                raise PlanningFailed(
                    "the part the robot holds starts closer to the cell than the planning "
                    f"clearance ({self.options.clearance:.2f} m): lift it clear with "
                    "MoveLinear first"
                )
            with self.model.person_obstacle(person_xy, self.options.person_radius):
                try:
                    return self._plan(command, q_start, objects, held)
                except PlanningFailed as failure:
                    if carried is None:
                        raise
                    raise PlanningFailed(f"{failure} {HOLDING}") from None

    def _check_target_clear_of(self, person_xy, command) -> None:
        """A tool target inside the person's space fails at once (no IK search)."""
        pose = getattr(command, "pose", None)
        if pose is None:
            return
        gap = np.linalg.norm(pose.translation()[:2] - np.asarray(person_xy)[:2])
        if gap < self.options.person_radius + self.options.clearance:
            x, y = person_xy[:2]
            raise PlanningFailed(
                f"the target is in the space of the person standing at ({x:.2f}, {y:.2f}) "
                "(collision with the person)"
            )

    def _plan(self, command, q_start, objects, held) -> TimedPath | None:
        q_start = np.asarray(q_start, dtype=float)
        rng = np.random.default_rng(self.seed)
        if isinstance(command, MoveLinear):
            waypoints = self._linear(command, q_start)
            if len(waypoints) < 2:
                return None
            self._check_ends_among(objects, q_start, waypoints[-1], held)
            return self._timed(spline_path(waypoints))
        q_goal = self._goal(command, q_start, rng, objects)
        if np.linalg.norm(q_goal - q_start) < ARRIVED:
            return None
        return self._timed(self._path_among(objects, q_start, q_goal, rng))

    def _path_among(self, objects, q_start, q_goal, rng):
        """A collision-free path that keeps out of the resting objects on its way. When there
        is none, a search without them tells the user whether the objects are why."""
        with self.model.among(objects, q_start, q_goal) as kept:
            waypoints = self._waypoints(q_start, q_goal, rng)
            if waypoints is not None:
                return self._smoothest_safe_path(waypoints)
        if kept and self._waypoints(q_start, q_goal, rng) is not None:
            raise PlanningFailed(AMONG_OBJECTS)
        raise PlanningFailed("no collision-free path to the target was found")

    def _check_ends_among(self, objects, q_start, q_goal, held) -> None:
        """A linear move ends on what it takes or sets down, not in it: PlanningFailed where
        the robot, or the part it holds, would end deeper in a resting object than a touch
        (a user's RobotMoveLinear set a part 4.5 cm into the one lying on the table)."""
        with self.model.holding(held), self.model.among(objects, q_start, q_goal):
            pass

    def _waypoints(self, q_start, q_goal, rng):
        return collision_free_waypoints(self.model, q_start, q_goal, rng, self.options.search_nodes)

    def _goal(self, command, q_start, rng, objects) -> np.ndarray:
        if isinstance(command, MoveJoints):
            return self._joint_goal(command)
        if isinstance(command, MoveTo):
            return self._tool_goal(command, q_start, rng, objects)
        raise PlanningFailed(f"not a move command: {type(command).__name__}")

    def _tool_goal(self, command: MoveTo, q_start, rng, objects) -> np.ndarray:
        """Joint positions for the tool target that keep the robot, and what it holds, out of
        the resting objects; where none does, any (the path's `among` judges what it touches
        there). A tool free to turn about its axis is tried turned by quarter turns from
        where it points now, which is how a box held from above fits beside others (a user's
        pallet had its cartons set down 4.5 cm into each other: deep in, nothing tells the
        solver which way to turn)."""
        with self.model.among(objects, q_start) as seen:
            try:
                return self._solve(command.pose, command.free_tool_rotation, q_start, rng)
            except PlanningFailed:
                if not seen:
                    raise
            if command.free_tool_rotation:
                for pose in self._quarter_turns(command.pose, q_start):
                    with contextlib.suppress(PlanningFailed):
                        return self._solve(pose, False, q_start, rng)
        return self._solve(command.pose, command.free_tool_rotation, q_start, rng)

    def _quarter_turns(self, pose: RigidTransform, q_start) -> list[RigidTransform]:
        """`pose` with the tool turned about its axis as it is turned at `q_start`, then by
        a quarter turn, the other quarter turn and a half turn from there."""
        axis = pose.rotation().matrix()[:, 2]
        x_now = self.model.tool_pose(q_start).rotation().matrix()[:, 0]
        x_now = x_now - axis * (x_now @ axis)
        if np.linalg.norm(x_now) < 1e-6:
            return []
        x_now = x_now / np.linalg.norm(x_now)
        return [
            RigidTransform(
                RotationMatrix(np.column_stack([x, np.cross(axis, x), axis])), pose.translation()
            )
            for x in (x_now, np.cross(axis, x_now), -np.cross(axis, x_now), -x_now)
        ]

    def _solve(self, pose: RigidTransform, free_rotation: bool, q_start, rng) -> np.ndarray:
        return self.ik.solve(pose, q_start, free_rotation, rng, self.options.ik_attempts)

    def _joint_goal(self, command: MoveJoints) -> np.ndarray:
        if command.q is not None:
            q = np.asarray(command.q, dtype=float)
            if q.shape != self.model.lower.shape:
                raise PlanningFailed(f"MoveJoints needs {self.model.lower.size} joint positions")
        else:
            q = self._named_configuration(command.configuration)
        if not self.model.within_limits(q):
            raise PlanningFailed("target joint positions are outside the joint limits")
        if not self.model.collision_free(q):
            raise PlanningFailed("target joint positions collide with the cell")
        return q

    def _named_configuration(self, name: str | None) -> np.ndarray:
        known = self.station.configuration_names
        if name not in known:
            raise PlanningFailed(
                f"unknown configuration '{name}' (known: {', '.join(sorted(known))})"
            )
        return self.station.configuration(name)

    def _linear(self, command: MoveLinear, q_start) -> list[np.ndarray]:
        return linear_waypoints(
            self.model, self.ik, q_start, command.pose, self.options.linear_tolerance
        )

    def _smoothest_safe_path(self, waypoints: list[np.ndarray]):
        """The C² spline when it stays collision-free, else the exact polyline."""
        if len(waypoints) > 2:
            spline = spline_path(waypoints)
            if self._sampled_path_collision_free(spline):
                return spline
        return polyline_path(waypoints)

    def _sampled_path_collision_free(self, path) -> bool:
        length = path.end_time() - path.start_time()
        samples = [path.value(s).ravel() for s in np.linspace(0.0, length, int(length / 0.01) + 2)]
        return all(
            self.model.within_limits(q) and self.model.edge_collision_free(a, b)
            for a, b, q in zip(samples, samples[1:], samples[1:], strict=False)
        )

    def _timed(self, path) -> TimedPath:
        timed = time_path(path, self.model, self.options.tool_speed_limit)
        if timed is None:
            raise PlanningFailed("time-parameterisation of the path failed")
        return timed
