"""Where the person's hand goes against where the tree has them stand: a place or reach
target farther from the last walk's end (or the person's start) than a hand reaches
without walking fails the node at run time ("out of reach without walking"), so validate
says it first. So does a pick of an object that a NextObject finds in an area, for the
objects that lie there at the start (a pallet's far row: "hand stays 0.27 m from the
target", every time the person tried), and a place after such a pick, for an object of
the type it finds (a tote put into a shelf's compartment from too close: "the head would
go 3.4 cm into 'shelf'"). A pick's objects are where the tree last left them on its
way to it (`object_source`): found by the NextObject on its own path, or put down since.

Where the person stands is known statically only along the tree's certain paths: the last
walk among the earlier children of the Sequences above the node. A Fallback's earlier
children, a Parallel's others, a loop or a skippable walk make it uncertain, and then
nothing is said.
"""

from collections.abc import Callable, Iterator
from functools import partial

import numpy as np

from hrc_drake.bt import TreeNode
from hrc_drake.bt.controls.sequences import ReactiveControl, SequentialControl
from hrc_drake.bt.decorators import SubTreeNode
from hrc_drake.bt.status import FAILURE
from hrc_drake.human.clip_files import clip_catalog
from hrc_drake.human.targeting import MAX_HORIZONTAL_REACH, TARGETED
from hrc_drake.known_values import Known
from hrc_drake.nodes.objects import NextObject
from hrc_drake.nodes.person import ActorMovement
from hrc_drake.nodes.targeted import ActorPick, ActorPlace, ActorReach
from hrc_drake.scenario.located import Finding, Locator

UNKNOWN = object()
"""Where a subtree leaves the person cannot be known statically."""

Resolve = Callable[[Known], np.ndarray | None]
"""A known pose value to its point in the world (None: not resolvable)."""
Taken = Callable[[TreeNode], list[tuple[str, np.ndarray, Callable]]]
"""The objects a pick node may take, as far as known before the run: a label, the centre,
and what keeps the person from taking it from a place to stand (the walk's known target,
None: the person's start): why the hands cannot get there, or ""."""
Kind = type | Callable[[TreeNode], bool]
"""A kind of node: its class, or what says whether a node is one."""
Placing = Callable[[TreeNode, np.ndarray, list, list], Callable | None]
"""For the last pick before a place node, the place's target point, where the person may
stand at the pick (as `_stand_points`; [] when not known) and every pick known to have run
before the place (what they took is gone from where it lay): what keeps the person from
putting down there what that pick took, from a place to stand (as `Taken`'s), or None when
what the hands hold is not known before the run."""


def clip_step_back(clips: dict) -> float:
    """How far (m) a targeted clip moves the person's base before its hands arrive: the
    run measures the reach from there, so validate allows for it."""
    steps = [0.0]
    for name, event in TARGETED.items():
        clip = clips[name]
        x, y = (clip.joint_names.index(axis) for axis in ("base_x", "base_y"))
        moved = clip.sample(clip.events[event]) - clip.sample(0.0)
        steps.append(float(np.hypot(moved[x], moved[y])))
    return max(steps)


def reach_findings(
    nodes: list[TreeNode],
    known: dict[tuple[int, str], list[Known]],
    resolve: Resolve,
    start: np.ndarray,
    clips: dict | None = None,
    taken: Taken | None = None,
    placing: Placing | None = None,
) -> Iterator[Finding]:
    """A Finding at each ActorPlace/ActorReach whose known target, and each ActorPick whose
    `taken` object, is farther from every place the person can stand there than a hand
    reaches, or that the hands cannot get to from all of them (`known`: the known values by
    (id(node), port); `start`: the person's start on the floor)."""
    limit = MAX_HORIZONTAL_REACH + clip_step_back(clips or clip_catalog())
    parents = parents_of(nodes)
    for node in nodes:
        if isinstance(node, ActorPlace | ActorReach):
            port = "target"
            targets = [(value, resolve(value), None) for value in known.get((id(node), port), ())]
            if isinstance(node, ActorPlace) and placing is not None:
                stands_at = partial(_stands_before, parents, known, resolve, start)
                targets = _placings(node, parents, targets, placing, stands_at)
        elif isinstance(node, ActorPick) and taken is not None:
            port = "object_id"
            targets = taken(node)
        else:
            continue
        stand = _last_before(node, parents, ActorMovement)
        if stand is UNKNOWN:
            continue
        stands = _stand_points(stand, known, resolve, start)
        if not stands:
            continue
        for what, target, hindrance in targets:
            if target is None:
                continue
            distance = min(float(np.hypot(*(target[:2] - s[:2]))) for s, _, _ in stands)
            if distance > limit:
                yield Locator.node(
                    node, port, _too_far(what, target, distance, stands, limit), target
                )
            elif hindrance is not None:
                problems = [(hindrance(value), said) for _, said, value in stands]
                if all(problem for problem, _ in problems):
                    problem, said = problems[0]
                    done = "taken" if isinstance(node, ActorPick) else "put down"
                    message = (
                        f"{what} at {point_text(target)}, {done} where the person stands "
                        f"({said}): {problem}"
                    )
                    yield Locator.node(node, port, message, target)


def _placings(place, parents, targets, placing: Placing, stands_at) -> list:
    """`targets` of a place node with what keeps the person from putting down there what
    the last pick before it took (unchanged when no pick is known to come before);
    `stands_at(pick)`: where the person may stand at that pick."""
    pick = held_at(place, parents)
    if not isinstance(pick, ActorPick):
        return targets
    at_pick, picks = stands_at(pick), _all_before(place, parents, ActorPick)
    return [(v, p, None if p is None else placing(pick, p, at_pick, picks)) for v, p, _ in targets]


def _all_before(node: TreeNode, parents: dict, kind: Kind) -> list[TreeNode]:
    """The nodes of `kind` in the earlier children of the Sequences above `node`: they have
    run when it starts (a tote put where an earlier pick took one from was planned on top
    of that one, and validate said an arm would go into it, a cell of our own)."""
    found, child = [], node
    while (parent := parents.get(id(child))) is not None:
        if _is_sequence(parent):
            found += [n for s in _earlier_siblings(parent, child) for n in _all_of(s, kind)]
        elif not isinstance(parent, SubTreeNode):
            break
        child = parent
    return found


def _all_of(node: TreeNode, kind: Kind) -> list[TreeNode]:
    """The nodes of `kind` in the subtree of `node`."""
    own = [node] if _is(node, kind) else []
    return own + [n for c in node.children_nodes() for n in _all_of(c, kind)]


def _stands_before(parents, known, resolve, start, node) -> list:
    """Where the person may stand when `node` starts ([] when not known)."""
    stand = _last_before(node, parents, ActorMovement)
    return [] if stand is UNKNOWN else _stand_points(stand, known, resolve, start)


def _stand_points(stand, known, resolve, start) -> list[tuple[np.ndarray, str, Known | None]]:
    """The points the person can stand at (with what says so, and the walk's known target
    there): the walk's known targets, or the start when no walk comes before."""
    if stand is None:
        return [(np.asarray(start, dtype=float), "the person's start", None)]
    points = []
    for value in known.get((id(stand), "target"), ()):
        point = resolve(value)
        if point is None:
            return []
        config = stand.config
        said = f"{value}, {config.registration_id} at {config.file}:{config.line}"
        points.append((point, said, value))
    return points


def point_text(point) -> str:
    """A point as validate's messages give it: (x, y, z) to the centimetre."""
    return "(" + ", ".join(f"{v:.2f}" for v in point) + ")"


def _too_far(value, target, distance: float, stands, limit: float) -> str:
    where = point_text(target)
    nearest = min(stands, key=lambda s: np.hypot(*(target[:2] - s[0][:2])))[1]
    return (
        f"{value} at {where} is {distance:.2f} m from where the person stands ({nearest}); "
        f"a hand reaches at most {limit:.2f} m without walking: walk closer first"
    )


def walk_before(node: TreeNode, parents: dict) -> TreeNode | None | object:
    """The last walk that has run when `node` starts (None: the person stands at their
    start; UNKNOWN: not known statically)."""
    return _last_before(node, parents, ActorMovement)


def parents_of(nodes: list[TreeNode]) -> dict[int, TreeNode]:
    """Each node's parent, by id(child)."""
    return {id(child): node for node in nodes for child in node.children_nodes()}


def held_at(node: TreeNode, parents: dict) -> TreeNode | None | object:
    """The pick whose object the hands hold when `node` starts (as `_last_before`)."""
    return _last_before(node, parents, ActorPick)


def object_source(pick: TreeNode, parents: dict) -> TreeNode | None | object:
    """Where what `pick` takes was last left on the way to it (as `_last_before`): the node
    that last wrote the entry it reads (a NextObject on another branch of a Fallback or
    WeightedRandom has not run), or a put-down of what an earlier pick of that entry took
    (a carton put on a table is taken from the table, not from where it was found)."""
    entry = _entry(pick, "inputs")
    if entry is None:
        return UNKNOWN
    return _last_before(pick, parents, partial(_leaves_object, entry, parents))


def finder_of(pick: TreeNode, parents: dict) -> TreeNode | None:
    """The NextObject that found what `pick` takes, through the put-downs of it since
    (None: not known, or a literal id)."""
    source = object_source(pick, parents)
    if isinstance(source, ActorPlace):
        return finder_of(held_at(source, parents), parents)
    return source if isinstance(source, NextObject) else None


def _leaves_object(entry, parents: dict, node: TreeNode) -> bool:
    """Whether `node` writes `entry` (an action; a SubTree's port only passes it on) or puts
    down what a pick that read it took."""
    if isinstance(node, ActorPlace):
        held = held_at(node, parents)
        return isinstance(held, ActorPick) and _entry(held, "inputs") is entry
    outputs = node.config.outputs.values()
    return not node.children_nodes() and any(getattr(o, "entry", None) is entry for o in outputs)


def _entry(node: TreeNode, ports: str):
    """The blackboard entry of `node`'s object_id port among its `ports` (None: a literal)."""
    return getattr(getattr(node.config, ports).get("object_id"), "entry", None)


def _last_before(node: TreeNode, parents: dict, kind: Kind) -> TreeNode | None | object:
    """The last node of `kind` that has run when `node` starts (a walk: the person stands
    at its end; a pick: the hands hold what it took). None: none before it (the person
    stands at their start); UNKNOWN: not known statically."""
    child = node
    while (parent := parents.get(id(child))) is not None:
        if _is_sequence(parent):
            for sibling in reversed(_earlier_siblings(parent, child)):
                if (last := _last_of(sibling, kind)) is not None:
                    return last
        elif not isinstance(parent, SubTreeNode) and not _runs_first(parent, child):
            return UNKNOWN  # a Fallback's failed tries, a Parallel's others, a loop
        child = parent
    return None


def _last_of(node: TreeNode, kind: Kind) -> TreeNode | None | object:
    """The last node of `kind` that has run once `node` succeeded (None: there is none in
    it)."""
    if not _holds(node, kind):
        return None
    if _is(node, kind):
        return node if not node.config.preconditions else UNKNOWN
    if isinstance(node, SubTreeNode):
        return _last_of(node.child, kind)
    if _is_sequence(node):
        for child in reversed(node.children_nodes()):
            if _holds(child, kind):
                return _last_of(child, kind)
    return UNKNOWN


def _holds(node: TreeNode, kind: Kind) -> bool:
    """Whether a node of `kind` is in the subtree of `node`."""
    return _is(node, kind) or any(_holds(c, kind) for c in node.children_nodes())


def _is(node: TreeNode, kind: Kind) -> bool:
    return isinstance(node, kind) if isinstance(kind, type) else kind(node)


def _is_sequence(node: TreeNode) -> bool:
    """A Sequence of any kind without skippable children: its earlier children have
    succeeded when a later one runs."""
    sequence = isinstance(node, SequentialControl | ReactiveControl) and node.stops_on is FAILURE
    return sequence and not any(c.config.preconditions for c in node.children_nodes())


def _runs_first(parent: TreeNode, child: TreeNode) -> bool:
    """Whether nothing of `parent` runs before `child` (a Fallback's first child);
    decorators that repeat or loop do not count (the walk may come from an earlier round)."""
    return isinstance(parent, SequentialControl) and not _earlier_siblings(parent, child)


def _earlier_siblings(parent: TreeNode, child: TreeNode) -> list[TreeNode]:
    children = parent.children_nodes()
    return children[: [id(c) for c in children].index(id(child))]
