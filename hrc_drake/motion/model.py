"""The planner's own model of the robot and the static cell, built from the station spec.

It is a RobotDiagram (plant + SceneGraph) inside a SceneGraphCollisionChecker, separate from
the simulated station: planning never touches the station's context.
"""

from collections.abc import Sequence
from contextlib import contextmanager
from dataclasses import dataclass

import numpy as np
from pydrake.common import Parallelism
from pydrake.geometry import Capsule, Shape
from pydrake.math import RigidTransform
from pydrake.planning import RobotDiagramBuilder, SceneGraphCollisionChecker

from hrc_drake.iisy import FLANGE_FRAME, TCP_FRAME, VARIANTS
from hrc_drake.motion.errors import PlanningFailed
from hrc_drake.station import StationSpec, add_station_models
from hrc_drake.workpieces.geometry import Solid

EDGE_STEP = 0.01
"""Joint-space resolution (rad) of edge collision checks: about 1 cm at the tool."""


APART_INFLUENCE = 0.01
"""m: `apart` measures the pairs of bodies whose padded distance is below this (any positive
value gives the same answers; a small one leaves most pairs to the broad phase)."""
PERSON_GROUP = "person"
HELD_GROUP = "held"
OBJECTS_GROUP = "objects"
PROBE_GROUP = "probe"
TOUCH_DEPTH = 0.01
"""m: the deepest a move may end in an object it works on (the realism audit's limit for what
the robot holds: docs/realism.md); a target deeper in is in the object, not on it."""
SLACK = TOUCH_DEPTH / 2
"""m: how far the robot may press into an object before the checks count it as in it (so
that a carton set down touching its neighbours fits between them, and a tool on a part's top
face is on it)."""
PERSON_HEIGHT = 1.9
"""m: a standing person with some margin overhead."""


@dataclass(frozen=True)
class HeldPart:
    """What the tool holds, as a plan keeps it clear of the cell: its collision shape and
    its pose in the tool's frame (`X_TP`)."""

    shape: Shape
    X_TP: RigidTransform


@dataclass(frozen=True)
class RestingObject:
    """An object resting in the cell, as a free-space path keeps out of it: its solid, its
    pose in the world and its name in messages ("carton 3")."""

    solid: Solid
    X_WO: RigidTransform
    name: str


class PlanningModel:
    """Robot + tool + static cell: kinematics, limits and collision checks for planning."""

    def __init__(self, station: StationSpec, clearance: float):
        self.variant = VARIANTS[station.variant]
        self.clearance = clearance
        builder = RobotDiagramBuilder(time_step=0.0)
        arm, robot_instances = add_station_models(builder.plant(), builder.parser(), station)
        builder.plant().Finalize()
        self.checker = SceneGraphCollisionChecker(
            model=builder.Build(),
            robot_model_instances=robot_instances,
            edge_step_size=EDGE_STEP,
            env_collision_padding=clearance,
            self_collision_padding=0.0,
            # One context: planning runs inside a simulation step, and sweeps already
            # use every core with one process each.
            implicit_context_parallelism=Parallelism(1),
        )
        self.plant = self.checker.plant()
        self.arm = arm
        if self.plant.num_positions() != len(self.variant.joint_names):
            raise ValueError("the static cell must be welded: the planner plans the arm alone")
        self._unpad_mounting(station.initial_positions)
        self.checker_context = self.checker.MakeStandaloneModelContext()
        self.diagram_context = self.checker.model().CreateDefaultContext()
        self.plant_context = self.checker.model().mutable_plant_context(self.diagram_context)
        tcp_instance = robot_instances[-1]
        self.tcp = self.plant.GetFrameByName(
            TCP_FRAME if station.has_tool else FLANGE_FRAME, tcp_instance
        )
        self.held: HeldPart | None = None
        """The part the tool holds in the collision checks, while `holding` it."""
        self.lower = np.array(self.variant.position_lower)
        self.upper = np.array(self.variant.position_upper)
        self.velocity_limits = np.array(self.variant.velocity_limits)
        self.acceleration_limits = np.array(self.variant.acceleration_limits)

    def _unpad_mounting(self, q_initial) -> None:
        """No clearance for pairs already closer than it where the scenario starts.

        Those are how the robot is mounted (the first link turning just above the pedestal
        it stands on); with the clearance they would make every configuration collide.
        They are still checked for contact.
        """
        clearance = self.checker.CalcRobotClearance(q_initial, 0.0)
        for robot_body, other_body, distance in zip(
            clearance.robot_indices(),
            clearance.other_indices(),
            clearance.distances(),
            strict=True,
        ):
            if distance < 0.0:
                self.checker.SetPaddingBetween(robot_body, other_body, 0.0)

    def tool_pose(self, q) -> RigidTransform:
        self.plant.SetPositions(self.plant_context, q)
        return self.tcp.CalcPoseInWorld(self.plant_context)

    def tool_pose_and_speed(self, q, v) -> tuple[RigidTransform, float]:
        """`tool_pose` and the tool centre point's translational speed (m/s), from one
        setting of the plant's state (each setting recomputes the kinematics)."""
        self.plant.SetPositionsAndVelocities(self.plant_context, np.concatenate([q, v]))
        velocity = self.tcp.CalcSpatialVelocityInWorld(self.plant_context)
        pose = self.tcp.CalcPoseInWorld(self.plant_context)
        return pose, float(np.linalg.norm(velocity.translational()))

    def apart(self, q) -> bool:
        """Whether the robot at q is apart from the cell and from itself by more than the
        padding between them (Drake's padded distance ϕ > 0). Only pairs nearer than
        APART_INFLUENCE are measured: the nearest pair's ϕ, and so the answer, is the same
        as with every pair measured, at a fifth of the cost."""
        distances = self.checker.CalcRobotClearance(q, APART_INFLUENCE).distances()
        return not distances.size or float(distances.min()) > 0.0

    @contextmanager
    def person_obstacle(self, xy, radius: float):
        """The person standing at `xy` as a capsule in the collision checks, for one plan
        (no person: None)."""
        if xy is None:
            yield
            return
        X_WP = RigidTransform([xy[0], xy[1], PERSON_HEIGHT / 2])
        shape = Capsule(radius, PERSON_HEIGHT - 2 * radius)
        self.checker.AddCollisionShapeToBody(PERSON_GROUP, self.plant.world_body(), shape, X_WP)
        try:
            yield
        finally:
            self.checker.RemoveAllAddedCollisionShapes(PERSON_GROUP)

    @contextmanager
    def holding(self, part: HeldPart | None):
        """The part the tool holds as part of the tool in the collision checks, for one plan:
        the cell's clearance applies to it as to the tool (and it may not touch the arm)."""
        if part is None:
            yield
            return
        self.held = part
        X_BT = self.tcp.GetFixedPoseInBodyFrame()
        self.checker.AddCollisionShapeToBody(
            HELD_GROUP, self.tcp.body(), part.shape, X_BT @ part.X_TP
        )
        try:
            yield
        finally:
            self.checker.RemoveAllAddedCollisionShapes(HELD_GROUP)
            self.held = None

    @contextmanager
    def among(self, objects: Sequence[RestingObject], start, goal=None):
        """The objects resting in the cell in the collision checks, for one plan, but those the
        robot (or the part it holds) touches at `start` or `goal`: what it takes or sets down,
        what it has just let go. One it would be deeper than TOUCH_DEPTH into at `goal` fails
        the plan: that is a target in an object, not on it. The robot may come up to an
        object, not SLACK into it: the clearance is for the cell's furniture, so each object
        is shrunk by it and SLACK first. Yields how many objects are in the checks."""
        ends = [q for q in (start, goal) if q is not None]
        shrink = self.clearance + SLACK
        shrunk = [(o.solid.shrunk(shrink).drake_shape(), o.X_WO) for o in objects]
        kept = shrunk
        self._add_shapes(OBJECTS_GROUP, kept)
        try:
            if not all(self.collision_free(q) for q in ends):
                self.checker.RemoveAllAddedCollisionShapes(OBJECTS_GROUP)
                kept = [s for s, o in zip(shrunk, objects, strict=True) if self._clear(s, o, ends)]
                self._add_shapes(OBJECTS_GROUP, kept)
            yield len(kept)
        finally:
            self.checker.RemoveAllAddedCollisionShapes(OBJECTS_GROUP)

    def _add_shapes(self, group: str, shapes) -> None:
        for shape, X_WO in shapes:
            self.checker.AddCollisionShapeToBody(group, self.plant.world_body(), shape, X_WO)

    def _clear(self, shape, resting: RestingObject, ends) -> bool:
        """Whether the robot at every one of `ends` (start, then goal) is clear of this one
        shape; PlanningFailed when it would be deeper than TOUCH_DEPTH into it at the goal."""
        self._add_shapes(PROBE_GROUP, [shape])
        try:
            depths = [self._depth(q) for q in ends]
        finally:
            self.checker.RemoveAllAddedCollisionShapes(PROBE_GROUP)
        at_goal = depths[-1] if len(ends) > 1 else None
        if at_goal is not None and at_goal > TOUCH_DEPTH:
            raise PlanningFailed(
                f"at the target the robot (or the part it holds) would be "
                f"{100 * at_goal:.1f} cm into {resting.name} resting there (limit "
                f"{100 * TOUCH_DEPTH:.0f} cm): move or turn the target"
            )
        return all(depth is None for depth in depths)

    def _depth(self, q) -> float | None:
        """How deep the robot at q is into the objects added to the checks (shapes on the
        world body; the cell's furniture has bodies of its own), None when no deeper than
        SLACK. Each object is shrunk by the padding and SLACK, so the padded distance to it
        is the distance to the object itself plus SLACK."""
        clearance = self.checker.CalcRobotClearance(q, 0.0)
        world = self.plant.world_body().index()
        depths = [
            SLACK - float(distance)
            for other, distance in zip(
                clearance.other_indices(), clearance.distances(), strict=True
            )
            if other == world
        ]
        return max(depths) if depths else None

    def collision_free(self, q) -> bool:
        return self.checker.CheckConfigCollisionFree(q)

    def edge_collision_free(self, q_from, q_to) -> bool:
        return self.checker.CheckEdgeCollisionFree(q_from, q_to)

    def within_limits(self, q) -> bool:
        return bool(np.all(q >= self.lower - 1e-9) and np.all(q <= self.upper + 1e-9))
