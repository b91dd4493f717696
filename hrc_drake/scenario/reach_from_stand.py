"""Where the person's hand goes against where the tree has them stand: a place or reach
target farther from the last walk's end (or the person's start) than a hand reaches
without walking fails the node at run time ("out of reach without walking"), so validate
says it first. So does a pick of an object that a NextObject finds in an area, for the
objects that lie there at the start (a pallet's far row: "hand stays 0.27 m from the
target", every time the person tried), and a place after such a pick, for an object of
the type it finds (a tote put into a shelf's compartment from too close: "the head would
go 3.4 cm into 'shelf'").

Where the person stands is the last walk, and what a pick takes what the last node that
wrote its `object_id` entry found or made (or where a put-down since left it), among the
earlier children of the Sequences above the node. A choice (Fallback, WeightedRandom,
Switch) before the node may have run any one of its children to success, and a node inside
one runs after its own branch, never a sibling's: each way (`ways_before`) is followed,
each object it leaves (a NextObject's area, a SpawnObject's pose, a put-down's target)
judged on its own, its line naming where it comes from; the walks the ways end with are
judged together, as a walk's several targets are (which walk goes with which object is
often a condition of the tree). A Fallback's tries before the one that succeeded failed,
and may have run a walk or writer among them or not: where the way's own branch has none,
nothing is said; nor after a Parallel, a loop or a skippable walk, nor past MAX_WAYS ways.
"""

from collections.abc import Callable, Iterator
from functools import partial

import numpy as np

from hrc_drake.bt import TreeNode
from hrc_drake.bt.controls.branches import Switch
from hrc_drake.bt.controls.sequences import ReactiveControl, SequentialControl
from hrc_drake.bt.decorators import SubTreeNode
from hrc_drake.bt.status import FAILURE
from hrc_drake.human.clip_files import clip_catalog
from hrc_drake.human.targeting import MAX_HORIZONTAL_REACH, TARGETED
from hrc_drake.known_values import Known
from hrc_drake.nodes.general import WeightedRandom
from hrc_drake.nodes.objects import NextObject, SpawnObject
from hrc_drake.nodes.person import ActorMovement
from hrc_drake.nodes.targeted import ActorPick, ActorPlace, ActorReach
from hrc_drake.scenario.located import Finding, Locator

UNKNOWN = object()
"""Where a subtree leaves the person cannot be known statically."""
MAX_WAYS = 32
"""The most ways through the choices before a node that are judged one by one."""

Way = dict[int, int]
"""For each choice (Fallback, WeightedRandom, Switch; by id) the tree may make before a
node, the index of the child that succeeded; a choice not in it is not known."""

Resolve = Callable[[Known], np.ndarray | None]
"""A known pose value to its point in the world (None: not resolvable)."""
Taken = Callable[[TreeNode, Way], list[tuple[str, np.ndarray, Callable]]]
"""The objects a pick node may take the way the tree went, as far as known before the run:
a label, the centre,
and what keeps the person from taking it from a place to stand (the walk's known target,
None: the person's start): why the hands cannot get there, or ""."""
Kind = type | Callable[[TreeNode], bool]
"""A kind of node: its class, or what says whether a node is one."""
Placing = Callable[[TreeNode, np.ndarray, list, list, Way], Callable | None]
"""For the last pick before a place node, the place's target point, where the person may
stand at the pick (as `_stand_points`; [] when not known), every pick known to have run
before the place (what they took is gone from where it lay) and the way the tree went:
what keeps the person from putting down there what that pick took, from a place to stand
(as `Taken`'s), or None when what the hands hold is not known before the run."""


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
    at: Locator,
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
    reaches, or that the hands cannot get to from all of them, each way the tree may go
    to the node (`known`: the known values by (id(node), port); `start`: the person's start
    on the floor), located by `at` (a parameter's at its line)."""
    limit = MAX_HORIZONTAL_REACH + clip_step_back(clips or clip_catalog())
    parents = parents_of(nodes)
    for node in nodes:
        if isinstance(node, ActorPick) and taken is not None:
            port = "object_id"
            targets = _each_way(node, parents, partial(taken, node))
        elif isinstance(node, ActorPlace | ActorReach):
            port = "target"
            targets = [(value, resolve(value), None) for value in known.get((id(node), port), ())]
            if isinstance(node, ActorPlace) and placing is not None:
                stands_at = partial(_stands_before, parents, known, resolve, start)
                placings = partial(_placings, node, parents, targets, placing, stands_at)
                targets = _each_way(node, parents, placings)
        else:
            continue
        stands = _stands_before(parents, known, resolve, start, node)
        if stands:
            yield from _judged(at, node, port, targets, stands, limit)


def _judged(at: Locator, node, port: str, targets, stands, limit: float) -> Iterator[Finding]:
    """The Findings of `reach_findings` at `node`, whose `targets` (with what keeps the
    person from each, and a note of where its object comes from) are done from wherever of
    `stands` the person stands."""
    for what, target, hindrance, *note in targets:
        if target is None:
            continue
        distance = min(float(np.hypot(*(target[:2] - s[:2]))) for s, _, _ in stands)
        if distance > limit:
            yield at.read(node, port, what, _too_far(what, target, distance, stands, limit), target)
        elif hindrance is not None:
            problems = [(hindrance(value), said) for _, said, value in stands]
            if all(problem for problem, _ in problems):
                problem, said = problems[0]
                done = "taken" if isinstance(node, ActorPick) else "put down"
                message = (
                    f"{what} at {point_text(target)}, {done} where the person stands "
                    f"({said}){''.join(note)}: {problem}"
                )
                yield at.read(node, port, what, message, target)


def _each_way(node, parents, targets: Callable[[Way], list]) -> list:
    """The `targets` of `node` each way the tree may go to it, each once."""
    found: dict[tuple, tuple] = {}
    for way in ways_before(node, parents):
        for what, point, *rest in targets(way):
            key = (str(what), None if point is None else tuple(point), *rest[1:])
            found.setdefault(key, (what, point, *rest))
    return list(found.values())


def _chosen_object(place, parents, way: Way) -> str:
    """What the hands hold at `place` when a choice of the tree found or made it (its
    finder is known only the `way` the tree went), else ""."""
    pick = held_at(place, parents, way)
    finder = finder_of(pick, parents, way) if isinstance(pick, ActorPick) else None
    if finder is None or finder_of(pick, parents) is finder:
        return ""
    config = finder.config
    return f", holding what {config.registration_id} at {config.file}:{config.line} gave"


def _placings(place, parents, targets, placing: Placing, stands_at, way: Way) -> list:
    """`targets` of a place node with what keeps the person from putting down there what
    the last pick before it took the `way` the tree went (none when no pick is known to
    come before), and a note of where that came from (`_chosen_object`); `stands_at(pick,
    ways)`: where the person may stand at that pick (the way the tree went to it)."""
    pick = held_at(place, parents, way)
    if not isinstance(pick, ActorPick):
        return targets
    at_pick, picks = stands_at(pick, [way]), _all_before(place, parents, ActorPick)
    note = _chosen_object(place, parents, way)
    return [
        (v, p, None if p is None else placing(pick, p, at_pick, picks, way), note)
        for v, p, _ in targets
    ]


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


def _stands_before(parents, known, resolve, start, node, ways=None) -> list:
    """Where the person may stand when `node` starts, whichever of `ways` (all) the tree
    went to it ([] when not known for one of them)."""
    points: dict[str, tuple] = {}
    for way in ways_before(node, parents) if ways is None else ways:
        stand = walk_before(node, parents, way)
        more = [] if stand is UNKNOWN else _stand_points(stand, known, resolve, start)
        if not more:
            return []
        points.update((said, (point, said, value)) for point, said, value in more)
    return list(points.values())


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
    nearest = min(stands, key=lambda s: np.hypot(*(target[:2] - s[0][:2])))[1]
    return (
        f"{value} at {point_text(target)} is {distance:.2f} m from where the person stands "
        f"({nearest}); a hand reaches at most {limit:.2f} m without walking: walk closer first"
    )


def walk_before(node: TreeNode, parents: dict, way: Way | None = None) -> TreeNode | None | object:
    """The last walk that has run when `node` starts the `way` the tree went (None: the
    person stands at their start; UNKNOWN: not known statically)."""
    return last_before(node, parents, ActorMovement, way)


def ways_before(node: TreeNode, parents: dict) -> list[Way]:
    """Every way through the choices the tree makes before `node` (a choice's children
    each, and the choices in them), or [{}] when they make more than MAX_WAYS ways."""
    ways: list[Way] = [{}]
    child = node
    while (parent := parents.get(id(child))) is not None:
        if _is_sequence(parent):
            for sibling in _earlier_siblings(parent, child):
                ways = _ways_of(sibling, ways)
                if len(ways) > MAX_WAYS:
                    return [{}]
        child = parent
    return ways


def _ways_of(node: TreeNode, ways: list[Way]) -> list[Way]:
    """`ways` each continued through the choices in the subtree of `node`."""
    if len(ways) > MAX_WAYS:
        return ways
    children = node.children_nodes()
    if _is_choice(node):
        chose = [[way | {id(node): i} for way in ways] for i in range(len(children))]
        return [w for c, chosen in zip(children, chose, strict=True) for w in _ways_of(c, chosen)]
    for c in children:
        ways = _ways_of(c, ways)
    return ways


def parents_of(nodes: list[TreeNode]) -> dict[int, TreeNode]:
    """Each node's parent, by id(child)."""
    return {id(child): node for node in nodes for child in node.children_nodes()}


def held_at(node: TreeNode, parents: dict, way: Way | None = None) -> TreeNode | None | object:
    """The pick whose object the hands hold when `node` starts (as `last_before`)."""
    return last_before(node, parents, ActorPick, way)


def object_source(
    pick: TreeNode, parents: dict, way: Way | None = None
) -> TreeNode | None | object:
    """Where what `pick` takes was last left on the `way` to it (as `last_before`): the
    node that last wrote the entry it reads (a NextObject on another branch of a Fallback or
    WeightedRandom has not run), or a put-down of what an earlier pick of that entry took
    (a carton put on a table is taken from the table, not from where it was found)."""
    entry = _entry(pick, "inputs")
    if entry is None:
        return UNKNOWN
    return last_before(pick, parents, partial(_leaves_object, entry, parents, way), way)


def finder_of(pick: TreeNode, parents: dict, way: Way | None = None) -> TreeNode | None:
    """The NextObject that found, or the SpawnObject that made, what `pick` takes the `way`
    the tree went, through the put-downs of it since (None: not known, or a literal id)."""
    source = object_source(pick, parents, way)
    if isinstance(source, ActorPlace):
        return finder_of(held_at(source, parents, way), parents, way)
    return source if isinstance(source, NextObject | SpawnObject) else None


def _leaves_object(entry, parents: dict, way: Way | None, node: TreeNode) -> bool:
    """Whether `node` writes `entry` (an action; a SubTree's port only passes it on) or puts
    down what a pick that read it took."""
    if isinstance(node, ActorPlace):
        held = held_at(node, parents, way)
        return isinstance(held, ActorPick) and _entry(held, "inputs") is entry
    outputs = node.config.outputs.values()
    return not node.children_nodes() and any(getattr(o, "entry", None) is entry for o in outputs)


def _entry(node: TreeNode, ports: str):
    """The blackboard entry of `node`'s object_id port among its `ports` (None: a literal)."""
    return getattr(getattr(node.config, ports).get("object_id"), "entry", None)


def last_before(
    node: TreeNode, parents: dict, kind: Kind, way: Way | None = None
) -> TreeNode | None | object:
    """The last node of `kind` that has run when `node` starts the `way` the tree went (a
    walk: the person stands at its end; a pick: the hands hold what it took). None: none
    before it (the person stands at their start); UNKNOWN: not known statically."""
    way = way or {}
    child = node
    while (parent := parents.get(id(child))) is not None:
        if _is_sequence(parent):
            for sibling in reversed(_earlier_siblings(parent, child)):
                if (last := _last_of(sibling, kind, way)) is not None:
                    return last
        elif _is_choice(parent):
            if failed_tries(parent, child, kind):
                return UNKNOWN  # a Fallback's failed tries
        elif not isinstance(parent, SubTreeNode) and not _runs_first(parent, child):
            return UNKNOWN  # a Parallel's others, a loop
        child = parent
    return None


def _last_of(node: TreeNode, kind: Kind, way: Way) -> TreeNode | None | object:
    """The last node of `kind` that has run once `node` succeeded the `way` the tree went
    (None: there is none in it)."""
    if not _holds(node, kind):
        return None
    if _is(node, kind):
        return node if not node.config.preconditions else UNKNOWN
    if isinstance(node, SubTreeNode):
        return _last_of(node.child, kind, way)
    if _is_sequence(node):
        for child in reversed(node.children_nodes()):
            if _holds(child, kind):
                return _last_of(child, kind, way)
    if _is_choice(node) and id(node) in way:
        chosen = node.children_nodes()[way[id(node)]]
        if chosen.config.preconditions:
            return UNKNOWN
        last = _last_of(chosen, kind, way)
        return UNKNOWN if last is None and failed_tries(node, chosen, kind) else last
    return UNKNOWN


def _is_choice(node: TreeNode) -> bool:
    """A Fallback, WeightedRandom or Switch: it succeeds when one of its children does."""
    fallback = isinstance(node, SequentialControl) and node.stops_on is not FAILURE
    return fallback or isinstance(node, WeightedRandom | Switch)


def failed_tries(parent: TreeNode, child: TreeNode, kind: Kind) -> list[TreeNode]:
    """The tries of a Fallback `parent` before `child` holding a node of `kind`: they failed
    when `child` runs, having run it or not (a restocking SpawnObject after the NextObject
    that found nothing); another node has none."""
    if not (isinstance(parent, SequentialControl) and parent.stops_on is not FAILURE):
        return []
    return [s for s in _earlier_siblings(parent, child) if _holds(s, kind)]


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


def _earlier_siblings(parent: TreeNode, child: TreeNode) -> list[TreeNode]:
    children = parent.children_nodes()
    return children[: [id(c) for c in children].index(id(child))]


def _runs_first(parent: TreeNode, child: TreeNode) -> bool:
    """Whether nothing of `parent` runs before `child` (a Sequence's first child);
    decorators that repeat or loop do not count (the walk may come from an earlier round)."""
    return isinstance(parent, SequentialControl) and not _earlier_siblings(parent, child)
