"""Which nodes of a tree have run when a node starts, as far as is known before the run:
the last walk (where the person stands), the last pick (what the hands hold), and what last
left the object a pick takes (a NextObject's find, a SpawnObject's make, a put-down). A
choice (Fallback, WeightedRandom, Switch) before the node may have run any one of its
children to success: each way (`ways_before`) through them is followed on its own; a
Fallback's tries before the child that succeeded failed, as the run meets it when a try
starts by looking for an object: its NextObject found none (what its Sequences ran before
that has run). Not known (UNKNOWN): a Fallback's tries that fail otherwise, a Parallel's
others, a loop's earlier rounds (decorators that run their child once, `RUN_ONCE`, are
passed through)."""

from collections.abc import Callable
from functools import partial

from hrc_drake.bt import TreeNode
from hrc_drake.bt.controls.branches import Switch
from hrc_drake.bt.controls.sequences import ReactiveControl, SequentialControl
from hrc_drake.bt.decorators import Delay, ForceStatus, Inverter, SubTreeNode, Timeout
from hrc_drake.bt.status import FAILURE
from hrc_drake.nodes.general import WeightedRandom
from hrc_drake.nodes.objects import NextObject, SpawnObject
from hrc_drake.nodes.person import ActorMovement
from hrc_drake.nodes.targeted import ActorPick, ActorPlace

UNKNOWN = object()
"""Where a subtree leaves the person cannot be known statically."""
MAX_WAYS = 32
"""The most ways through the choices before a node that are judged one by one."""
Way = dict[int, int]
"""For each choice (Fallback, WeightedRandom, Switch; by id) the tree may make before a
node, the index of the child that succeeded; a choice not in it is not known."""
Kind = type | Callable[[TreeNode], bool]
"""A kind of node: its class, or what says whether a node is one."""
RUN_ONCE = (Inverter, ForceStatus, Timeout, Delay)
"""Decorators that start their child at once, never again (a user's pick in a ForceSuccess
was not checked)."""


def all_before(node: TreeNode, parents: dict, kind: Kind) -> list[TreeNode]:
    """The nodes of `kind` in the earlier children of the Sequences above `node`, through
    the choices it is in: they have run when it starts (a tote put where an earlier pick
    took one from was planned on top of that one, and validate said an arm would go into
    it, a cell of our own; a KLT a Fallback's try looks for on a rack, where the Sequence
    round it had put an empty one down, a user's kitting cell)."""
    found, child = [], node
    while (parent := parents.get(id(child))) is not None:
        if _is_sequence(parent):
            found += [n for s in _earlier_siblings(parent, child) for n in _all_of(s, kind)]
        elif not (isinstance(parent, (SubTreeNode, *RUN_ONCE)) or _is_choice(parent)):
            break
        child = parent
    return found


def _all_of(node: TreeNode, kind: Kind) -> list[TreeNode]:
    """The nodes of `kind` in the subtree of `node`."""
    own = [node] if _is(node, kind) else []
    return own + [n for c in node.children_nodes() for n in _all_of(c, kind)]


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
    return writes(entry, node)


def writes(entry, node: TreeNode) -> bool:
    """Whether `node` is an action or condition writing `entry` (a SubTree's port only
    passes it on)."""
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
            if (last := _last_in(_earlier_siblings(parent, child), kind, way)) is not None:
                return last
        elif _is_choice(parent):
            if (tried := _last_of_tries(parent, child, kind, way)) is not None:
                return tried  # a Fallback's failed tries
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
        return _last_of_tries(node, chosen, kind, way) if last is None else last
    return UNKNOWN


def _last_of_tries(parent: TreeNode, child: TreeNode, kind: Kind, way: Way):
    """The last node of `kind` that has run in the tries of a Fallback `parent` that failed
    before `child` ran, each failing the way the run meets first: its first NextObject
    finding nothing (no housing of the first child's type left on a user's rack, its second
    child, taking another type there, was never judged); None: none ran."""
    for try_ in reversed(failed_tries(parent, child, kind)):
        if (last := _last_until_finder(try_, kind, way)) is not None:
            return last
    return None


def _last_until_finder(node: TreeNode, kind: Kind, way: Way) -> TreeNode | None | object:
    """The last node of `kind` that has run when `node` fails at its first NextObject,
    which found nothing: what its Sequences ran before it (None: none; UNKNOWN: where
    `node` fails is not known, no NextObject starts it)."""
    if isinstance(node, NextObject):
        return UNKNOWN if node.config.preconditions else None
    if isinstance(node, SubTreeNode):
        return _last_until_finder(node.child, kind, way)
    finders = [c for c in node.children_nodes() if _holds(c, NextObject)]
    if not (_is_sequence(node) and finders):
        return UNKNOWN
    if (last := _last_until_finder(finders[0], kind, way)) is not None:
        return last
    return _last_in(_earlier_siblings(node, finders[0]), kind, way)


def _last_in(siblings: list[TreeNode], kind: Kind, way: Way) -> TreeNode | None | object:
    """The last node of `kind` that has run once `siblings`, children of a Sequence, all
    succeeded (None: none of them holds one)."""
    for sibling in reversed(siblings):
        if (last := _last_of(sibling, kind, way)) is not None:
            return last
    return None


def _is_choice(node: TreeNode) -> bool:
    """A Fallback, WeightedRandom or Switch: it succeeds when one of its children does."""
    fallback = isinstance(node, SequentialControl) and node.stops_on is not FAILURE
    return fallback or isinstance(node, WeightedRandom | Switch)


def failed_before(node: TreeNode, parents: dict, kind: Kind) -> list[TreeNode]:
    """The nodes of `kind` in the tries that failed before the branch of each Fallback above
    `node` that holds it (coexistence's restock SpawnObject, in a Sequence after the
    NextObject that found nothing, was judged with the objects it looked for still there)."""
    found, child = [], node
    while (parent := parents.get(id(child))) is not None:
        found += [n for try_ in failed_tries(parent, child, kind) for n in _all_of(try_, kind)]
        child = parent
    return found


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
    """Whether nothing of `parent` runs before `child` (a Sequence's first child, a RUN_ONCE
    decorator's; not a loop's: the walk may come from an earlier round)."""
    return isinstance(parent, RUN_ONCE) or (
        isinstance(parent, SequentialControl) and not _earlier_siblings(parent, child)
    )
