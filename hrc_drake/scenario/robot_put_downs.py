"""What the robot's tree puts down, known before a run: a RobotRelease lets go of what the
last RobotGrip before it took (an object of the one type the NextObject or SpawnObject
before that grip finds or makes) where the last move before the release took the tool.
The part hangs from the tool with its top at the target (a robot target is where the
tool's tip goes, a part's top face: docs/building-a-cell.md). Where its bottom would lie
inside the cell's fixed geometry deeper than the realism audit allows, `validate` says so
at the move's target: a user's `drop_spot`, given as the part's centre, put the part 3 cm
into the table, and the run lifted it out when it was let go.

A RobotMove made holding a part keeps the part as clear of the cell as the tool
(hrc_drake.motion.planner); where that keeps the robot from a target the tool alone
reaches, `validate` says so at the target, as the run's move would fail; so does a
MoveJoints made holding a part, at a configuration where the part touches the cell."""

from collections.abc import Callable, Iterator

import numpy as np
from pydrake.math import RigidTransform

from hrc_drake.bt import TreeNode
from hrc_drake.known_values import Known
from hrc_drake.motion.model import HeldPart
from hrc_drake.nodes.objects import NextObject, SpawnObject
from hrc_drake.nodes.robot import (
    TOOL_DOWN,
    RobotGrip,
    RobotMove,
    RobotMoveJoints,
    RobotMoveLinear,
    RobotRelease,
    tool_pose,
)
from hrc_drake.scenario.cell_findings import SURFACE_SEARCH, CellScene, below_top
from hrc_drake.scenario.located import Finding
from hrc_drake.scenario.reach_from_stand import point_text
from hrc_drake.scenario.switch_ways import finder_type
from hrc_drake.scenario.tree_ways import last_before, parents_of
from hrc_drake.scene_geometry import OBJECT_DEPTH_LIMIT
from hrc_drake.tree_types import Pose
from hrc_drake.workpieces.geometry import Solid, footprint

Locate = Callable[[TreeNode, str, Known, str, object], Finding]
"""Makes the Finding of a node's port reading a known value (message, point)."""


def put_downs(nodes: list[TreeNode], known: dict) -> Iterator[tuple[TreeNode, str, Known]]:
    """(the move, the type of what the robot holds, a known target of the move) of every
    RobotRelease whose last move and grip before it, and the finder before that grip, are
    known in the tree."""
    parents = parents_of(nodes)
    for release in (n for n in nodes if isinstance(n, RobotRelease)):
        move, kind = put_down_of(release, parents, known) or (None, None)
        for value in known.get((id(move), "target"), ()) if kind else ():
            yield move, kind, value


def put_down_of(release: TreeNode, parents: dict, known: dict) -> tuple[TreeNode, str] | None:
    """(the last move before `release`, the type of what it lets go of) when the move, the
    grip before it and the finder before that grip are known in the tree."""
    move = last_before(release, parents, _kind(RobotMove | RobotMoveLinear))
    grip = last_before(release, parents, RobotGrip)
    if not (isinstance(move, TreeNode) and isinstance(grip, TreeNode)):
        return None
    kind = _gripped_type(grip, parents, known)
    return (move, kind) if kind else None


def carried_moves(
    nodes: list[TreeNode], known: dict, moves=RobotMove, port: str = "target"
) -> Iterator[tuple[TreeNode, str, Known]]:
    """(the move, the type of what the robot holds, a known value of its `port`) of every
    free-space move of the class `moves` made holding a part (`held_type`)."""
    parents = parents_of(nodes)
    for move in (n for n in nodes if isinstance(n, moves)):
        kind = held_type(move, parents, known)
        for value in known.get((id(move), port), ()) if kind else ():
            yield move, kind, value


def held_type(move: TreeNode, parents: dict, known: dict) -> str | None:
    """The type of part the robot holds when `move` starts: the last grip or release
    before it is a grip whose finder is known (else None)."""
    grip = last_before(move, parents, _kind(RobotGrip | RobotRelease))
    return _gripped_type(grip, parents, known) if isinstance(grip, RobotGrip) else None


def holding(kind: str, problem: str) -> str:
    """Why a free-space move fails with the part it holds, as validate says it."""
    return f"with the {kind} it holds, {problem}"


def _gripped_type(grip: TreeNode, parents: dict, known: dict) -> str | None:
    """The one type of part `grip` takes: what the NextObject or SpawnObject before it
    finds or makes."""
    finder = last_before(grip, parents, _kind(NextObject | SpawnObject))
    return finder_type(known, finder if isinstance(finder, TreeNode) else None)


def put_down_findings(
    nodes: list[TreeNode], known: dict, resolve, solids: dict, scene: CellScene, locate: Locate
) -> Iterator[Finding]:
    """A Finding at each move's target where the robot lets go of a part deeper in the
    cell's fixed geometry than OBJECT_DEPTH_LIMIT (`resolve`: a Pose to the scenario's, None
    when it names no location; `solids`: each object type's shape)."""
    for move, kind, value in put_downs(nodes, known):
        pose = resolve(value.value) if isinstance(value.value, Pose) else None
        if pose is None or kind not in solids:
            continue
        target, _ = tool_pose(pose)
        found = held_part_depth(scene, solids[kind], target)
        if found is not None:
            tip = target.translation()
            yield locate(move, "target", value, _into(value, kind, tip, *found), tip)


def carried_move_findings(
    nodes: list[TreeNode], known: dict, resolve, problem_of, locate: Locate
) -> Iterator[Finding]:
    """A Finding at each target the robot moves to holding a part where the part, kept as
    clear of the cell as the tool, keeps the robot from reaching it (`problem_of(target,
    free_rotation, kind)`: why not, in `holding`'s words; "" when it can or the tool alone
    cannot either)."""
    for move, kind, value in carried_moves(nodes, known):
        pose = resolve(value.value) if isinstance(value.value, Pose) else None
        if pose is None:
            continue
        target, free = tool_pose(pose)
        problem = problem_of(target, free, kind)
        if problem:
            tip = target.translation()
            yield locate(move, "target", value, f"{value} at {point_text(tip)}: {problem}", tip)


def carried_configuration_findings(
    nodes: list[TreeNode], known: dict, problem_of, locate: Locate
) -> Iterator[Finding]:
    """A Finding at each named configuration the robot moves to holding a part where the
    part, hanging from the tool as it was taken and kept as clear of the cell as the tool,
    touches the cell: the run's MoveJoints fails there (`problem_of(name, kind)`: why, in
    `holding`'s words; "" when it does not, or the arm alone touches it too)."""
    for move, kind, value in carried_moves(nodes, known, RobotMoveJoints, "configuration"):
        problem = problem_of(value.value, kind)
        if problem:
            yield locate(move, "configuration", value, f"{value}: {problem}")


def hanging_from_the_tool(solid: Solid) -> HeldPart:
    """A part held as the vacuum holds it, its top at the tool and its sides along the
    tool's x and y (a robot target is a part's top face: docs/building-a-cell.md)."""
    return HeldPart(
        solid.drake_shape(), RigidTransform(TOOL_DOWN.inverse(), [0, 0, solid.height / 2])
    )


def _kind(classes) -> Callable[[TreeNode], bool]:
    """A node of any of `classes` (a union), as `last_before` takes a kind."""
    return lambda node: isinstance(node, classes)


def held_part_depth(scene: CellScene, solid: Solid, target: RigidTransform):
    """(what, how far) the bottom of a part held with its top at the tool's `target` lies
    below the top of the cell's fixed geometry at its deepest (its middle and the corners of
    its outline), when deeper than OBJECT_DEPTH_LIMIT; else None."""
    R = target.rotation()
    centre = target.translation() + R.matrix()[:, 2] * solid.height / 2
    outline = footprint(solid, RigidTransform(R @ TOOL_DOWN.inverse(), centre))
    bottom = centre[2] - solid.height / 2
    points = [np.array([x, y, bottom]) for x, y in (centre[:2], *outline)]
    depths = [d for p in points if (d := below_top(scene, p, SURFACE_SEARCH)) is not None]
    deepest = max(depths, key=lambda d: d[1], default=None)
    return deepest if deepest is not None and deepest[1] > OBJECT_DEPTH_LIMIT else None


def _into(value: Known, kind: str, tip, what: str, depth: float) -> str:
    return (
        f"{value} at {point_text(tip)}: the {kind} the robot lets go of there (its top at the "
        f"tool) would be {100 * depth:.1f} cm into {what} (limit {100 * OBJECT_DEPTH_LIMIT:.0f} "
        f"cm; the run lifts it out): to rest it on top, raise the target to z = "
        f"{tip[2] + depth:.3f}"
    )
