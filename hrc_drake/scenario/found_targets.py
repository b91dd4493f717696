"""The robot's targets made from the objects a NextObject can find, known before a run.

A NextObject's `pose` comes from the world, so hrc_drake.known_values leaves it unknown;
but the objects the scenario places at the start (its `objects` and every place of its
grids) that lie in the NextObject's known area and pass its known filter are the ones it
can find. A target made from that pose (through OffsetPose and the like, whose outputs
follow from their inputs, and SetBlackboard's copies) is worked out for each of them, the
way the tree goes to the move (hrc_drake.scenario.tree_ways: the entries' last writers
before it on that way, so a Fallback's carton offsets are not added to its crates): a
user's kitting cell took parts off shelf boards the robot cannot reach, validate said ok,
and the run failed its RobotMove 50 times. A free-space move made holding a part is
judged with the part hanging from the tool, as the run plans it
(hrc_drake.scenario.robot_put_downs). Objects made at run time are not known: their
targets are left out, as are those whose other inputs are not known on that way."""

import itertools
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from functools import partial
from typing import Any

from hrc_drake.bt import TreeNode
from hrc_drake.bt.actions import SetBlackboard
from hrc_drake.bt.blackboard import UNSET
from hrc_drake.bt.node import Literal
from hrc_drake.bt.ports import coerce
from hrc_drake.known_values import MAX_KNOWN, set_entry, step_of
from hrc_drake.nodes.objects import NextObject
from hrc_drake.nodes.robot import RobotMove, RobotMoveLinear, tool_pose
from hrc_drake.scenario.located import Finding
from hrc_drake.scenario.reach_from_stand import point_text
from hrc_drake.scenario.robot_put_downs import held_type
from hrc_drake.scenario.tree_ways import Way, last_before, parents_of, ways_before, writes
from hrc_drake.tree_types import Pose

LISTED = 3
"""A move's further unreachable targets named by where they lie; the rest are counted."""
MAX_DEPTH = 16
"""The most writers followed back from a move's target (an entry offset from itself in a
chain of SubTrees is followed no further)."""


@dataclass(frozen=True)
class Found:
    """A value a port reads, and the found object it was made from (`found`: "part in
    area 'rack' at (0.00, -0.65, 1.12)"; "" when none) through the nodes `via`."""

    value: Any
    found: str = ""
    via: tuple[str, ...] = ()

    def __str__(self) -> str:
        made = f" made by {' then '.join(self.via)}" if self.via else ""
        return f"from {self.found}{made}"


Finds = Callable[[NextObject], list[tuple[str, Any]]]
"""(label, centre) of each object a NextObject can find: the label as `Found.found` says
it, the centre as its `pose` gives it."""


def found_targets(nodes: list[TreeNode], finds: Finds, known: dict) -> Iterator[tuple]:
    """(move, Found) of every target of a RobotMove or RobotMoveLinear made from an object
    a NextObject can find (`finds`), each once; `known`: the known values of the ports
    (hrc_drake.known_values), read where an entry's last writer is not known but the
    entry has one known value."""
    values = _Values(parents_of(nodes), finds, known)
    for move in (n for n in nodes if isinstance(n, RobotMove | RobotMoveLinear)):
        seen = set()
        for way in ways_before(move, values.parents):
            for found in values.port(move, "target", way, MAX_DEPTH):
                key = (repr(found.value), found.found)
                if found.found and key not in seen:
                    seen.add(key)
                    yield move, found


def found_reach_findings(
    nodes: list[TreeNode], known: dict, finds: Finds, resolve, problem_of, locate
) -> Iterator[Finding]:
    """A Finding at the target port of each move with a target the robot cannot reach, for
    the first object a NextObject can find there, the others after it by where they lie
    (`resolve`: a Pose to the scenario's, None when it names no location;
    `problem_of(target, free_rotation, linear, held)`: why not, "" when it can, asked once
    per pose, `held` the type of part a free-space move is made holding, else None;
    `locate(node, port, message, point)`)."""
    missed: dict[int, tuple[TreeNode, list]] = {}
    parents = parents_of(nodes)
    for move, found in found_targets(nodes, finds, known):
        pose = resolve(found.value) if isinstance(found.value, Pose) else None
        if pose is None:
            continue
        target, free = tool_pose(pose)
        linear = isinstance(move, RobotMoveLinear)
        held = None if linear else held_type(move, parents, known)
        problem = problem_of(target, free, linear, held)
        if problem:
            missed.setdefault(id(move), (move, []))[1].append(
                (found, target.translation(), problem)
            )
    for move, misses in missed.values():
        found, tip, problem = misses[0]
        text = move.config.attributes.get("target", "")
        message = f"{text} {found} at {point_text(tip)}: {problem}{_and_more(misses[1:])}"
        yield locate(move, "target", message, tip)


def _and_more(misses: list) -> str:
    """The move's other targets the robot cannot reach, by where they lie: one line for
    the move (a user's wrong shelf gave 36 lines, one per part and move)."""
    if not misses:
        return ""
    places = ", ".join(point_text(tip) for _, tip, _ in misses[:LISTED])
    rest = f" and {len(misses) - LISTED} more" if len(misses) > LISTED else ""
    return f"; nor {len(misses)} more of its targets, at {places}{rest}"


class _Values:
    """What a port reads the way the tree went, found objects followed."""

    def __init__(self, parents: dict, finds: Finds, known: dict):
        self.parents = parents
        self.finds = finds
        self.known = known

    def port(self, node: TreeNode, port: str, way: Way, depth: int) -> list[Found]:
        """The values `node`'s input `port` reads (its literal, or its entry's)."""
        binding = node.config.inputs.get(port)
        if isinstance(binding, Literal):
            return [Found(binding.value)]
        entry = getattr(binding, "entry", None)
        if entry is None or depth == 0:
            return []
        writer = last_before(node, self.parents, partial(_writes, entry), way)
        if writer is None:
            return [] if entry.value is UNSET else [Found(entry.value)]
        if not isinstance(writer, TreeNode):
            given = self.known.get((id(node), port), ())
            return [Found(given[0].value)] if len(given) == 1 else []
        return self._written(writer, entry, way, depth - 1)

    def _written(self, writer: TreeNode, entry, way: Way, depth: int) -> list[Found]:
        """What `writer` writes to `entry`: a NextObject the centres of the objects it can
        find, a SetBlackboard what it copies, a node whose outputs follow from its inputs
        what it makes of them; else nothing known."""
        if isinstance(writer, SetBlackboard):
            return self.port(writer, "value", way, depth)
        port = next(p for p, b in writer.config.outputs.items() if b.entry is entry)
        if isinstance(writer, NextObject):
            return [Found(c, f) for f, c in self.finds(writer)] if port == "pose" else []
        if hasattr(type(writer), "static_outputs"):
            return self._made(writer, port, way, depth)
        return []

    def _made(self, node: TreeNode, output: str, way: Way, depth: int) -> list[Found]:
        """What `node` writes to `output` for each combination of what its inputs read
        (at most MAX_KNOWN of them)."""
        types = {p.name: p.type for p in type(node).ports}
        names = list(node.config.inputs)
        inputs = [self.port(node, name, way, depth) for name in names]
        made = []
        for combination in itertools.islice(itertools.product(*inputs), MAX_KNOWN):
            try:
                given = {
                    n: coerce(f.value, types.get(n))
                    for n, f in zip(names, combination, strict=True)
                }
                value = type(node).static_outputs(node.agent, given)[output]
            except (KeyError, ValueError):
                continue  # the node would fail on these inputs: nothing is written
            source = next((f for f in combination if f.found), Found(None))
            made.append(Found(value, source.found, (*source.via, step_of(node))))
        return made


def _writes(entry, node: TreeNode) -> bool:
    """Whether `node` writes `entry`: an action's output, or a SetBlackboard's."""
    return writes(entry, node) or (isinstance(node, SetBlackboard) and set_entry(node) is entry)
