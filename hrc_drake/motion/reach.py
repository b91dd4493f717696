"""Whether the robot reaches a tool target, asked before a run, and if not, why, in words a
person can act on: how far beyond the arm's reach at that height it lies, or what the arm or
tool would touch there.

The answer is the planner's own (hrc_drake.motion.ik with the run's planning budget and
random starts), for the robot as it starts the run: a target it reports unreachable fails
the same way in the run's first move to it.
"""

import numpy as np
from pydrake.math import RigidTransform
from pydrake.multibody.tree import BodyIndex

from hrc_drake.motion.model import HeldPart
from hrc_drake.motion.planner import MotionPlanner

SCAN_STEP = 0.1
RADIUS_TOLERANCE = 0.01
"""m: the reachable distance from the base axis is looked for in steps of SCAN_STEP towards
the axis, then to within RADIUS_TOLERANCE."""


def reach_problem(
    planner: MotionPlanner,
    pose: RigidTransform,
    free_rotation: bool,
    linear: bool = False,
    held: HeldPart | None = None,
) -> str:
    """Why the robot cannot reach `pose` ("" when it can): with `free_rotation` only the
    tool axis must point along the pose's z; at the end of a `linear` move the robot keeps
    no clearance to the cell (it must only not touch it); a free-space move keeps `held`,
    the part the tool holds, as clear of the cell as the tool (the tool's name then stands
    for both)."""
    with planner.model.holding(held):
        return _reach_problem(planner, pose, free_rotation, linear)


def _reach_problem(planner, pose, free_rotation, linear) -> str:
    ik, q_start = planner.ik, planner.station.initial_positions
    if ik.reaches(pose, q_start, free_rotation, *_budget(planner), clearance=not linear):
        return ""
    held = "with the tool pointing down" if free_rotation else "with the tool turned as given"
    q = ik.kinematic_solution(pose, q_start, free_rotation, *_budget(planner))
    if q is not None:
        return f"unreachable {held}: the {_touched(planner, q)} there{_upwards(pose)}"
    return f"out of reach {held}: {_beyond(planner, pose, free_rotation)}{_upwards(pose)}"


def configuration_problem(
    planner: MotionPlanner, q: np.ndarray, held: HeldPart | None = None
) -> str:
    """Why the planner refuses to move the arm to joint positions `q` ("" when it does
    not): outside the joint limits, or touching the cell; with `held`, the part the tool
    holds, kept as clear of the cell as the tool, as a MoveJoints made holding it is."""
    with planner.model.holding(held):
        return _configuration_problem(planner, q)


def _configuration_problem(planner: MotionPlanner, q: np.ndarray) -> str:
    model = planner.model
    if not model.within_limits(q):
        beyond = [
            f"joint {k + 1} at {np.degrees(angle):.0f}° (limits {np.degrees(low):.0f} to "
            f"{np.degrees(high):.0f}°)"
            for k, (angle, low, high) in enumerate(zip(q, model.lower, model.upper, strict=True))
            if not low - 1e-9 <= angle <= high + 1e-9
        ]
        return f"outside the joint limits: {', '.join(beyond)}"
    if not model.collision_free(q):
        return f"the {_touched(planner, q)} there"
    return ""


def _upwards(pose: RigidTransform) -> str:
    """A hint for a target whose rotation turns the tool up: a location's rotation is the
    tool's, and `!Rpy {deg: [0, 0, yaw]}` points it at the ceiling."""
    if pose.rotation().col(2)[2] < 0.5:
        return ""
    return (
        " (this rotation points the tool up: for the tool pointing down give "
        "!Rpy {deg: [180, 0, 0]}, or no rotation)"
    )


def _budget(planner: MotionPlanner) -> tuple:
    """The random starts and their number, as every plan of the run draws them."""
    return np.random.default_rng(planner.seed), planner.options.ik_attempts


def _touched(planner: MotionPlanner, q: np.ndarray) -> str:
    """What of the robot at `q` comes closer to what of the cell than the planner's
    clearance for that pair (none for how the robot is mounted: the first link just above
    its pedestal): `link_5 and vacuum_gripper would touch side_table`, ..."""
    model, clearance = planner.model, planner.options.clearance
    found = model.checker.CalcRobotClearance(q, clearance)
    parts: dict[str, set[str]] = {}
    for a, b, distance in zip(
        found.robot_indices(), found.other_indices(), found.distances(), strict=True
    ):
        if distance < model.checker.GetPaddingBetween(a, b):
            parts.setdefault(_name(model, b, robot=False), set()).add(_name(model, a, robot=True))
    touching = [
        f"{_and(sorted(robot))} would touch {cell}" for cell, robot in sorted(parts.items())
    ]
    return ", the ".join(touching) or "arm would touch the cell"


def _and(names: list[str]) -> str:
    return names[0] if len(names) == 1 else f"{', '.join(names[:-1])} and {names[-1]}"


def _name(model, index, robot: bool) -> str:
    """A robot part by its body's name (link_3, vacuum_gripper), a part of the cell by its
    model's name (side_table)."""
    body = model.plant.get_body(BodyIndex(int(index)))
    if robot and model.held is not None and body.index() == model.tcp.body().index():
        return f"{body.name()} (or the part it holds)"
    if robot:
        return body.name()
    instance = model.plant.GetModelInstanceName(body.model_instance())
    return instance if body.name() == "body" else f"{instance} ({body.name()})"


def _beyond(planner: MotionPlanner, pose: RigidTransform, free_rotation: bool) -> str:
    """How far the target lies from the robot's base axis, and how far the arm reaches at
    its height (the tool held the same way): searched along the line towards the axis."""
    axis = planner.station.base_pose.translation()
    target = pose.translation()
    offset = target[:2] - axis[:2]
    distance = float(np.linalg.norm(offset))
    height = f"at z = {target[2]:.2f} m"

    def reached(radius: float) -> bool:
        xy = axis[:2] + offset * (radius / distance)
        moved = RigidTransform(pose.rotation(), [*xy, target[2]])
        q_start = planner.station.initial_positions
        return (
            planner.ik.kinematic_solution(moved, q_start, free_rotation, *_budget(planner))
            is not None
        )

    outer = next((r for r in np.arange(distance, 0.0, -SCAN_STEP)[1:] if reached(r)), None)
    if distance == 0 or outer is None:
        return f"nothing {height} is within its reach"
    near, far = outer, outer + SCAN_STEP
    while far - near > RADIUS_TOLERANCE:
        middle = (near + far) / 2
        near, far = (middle, far) if reached(middle) else (near, middle)
    return (
        f"{distance:.2f} m from its base axis {height}, where the {planner.model.variant.name} "
        f"reaches {near:.2f} m (move it {distance - near:.2f} m closer)"
    )
