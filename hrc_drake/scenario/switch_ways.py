"""Which child a Switch on an object's type runs, known before the run: a tree that reads
the type of what a NextObject found (or a SpawnObject made) with ObjectAttribute and
switches on it runs the case of that type, never another (a user's assembly cell put a
large housing down in the branch for small ones, and validate said it would go into the
table). The ways (`tree_ways.ways_before`) to a node through a Switch that cannot go to it
are left out; a Switch on anything else may go any way."""

from functools import partial

from hrc_drake.bt import TreeNode
from hrc_drake.bt.controls.branches import Switch
from hrc_drake.nodes.objects import ObjectAttribute, parse_filter
from hrc_drake.scenario.tree_ways import Way, finder_of, last_before, ways_before, writes


def finder_type(known: dict, finder: TreeNode | None) -> str | None:
    """The one object type that `finder`, a NextObject or a SpawnObject, filters for or
    makes, as its known values say (None: not one type, or no finder)."""
    types = {parse_filter(w.value).get("type") for w in known.get((id(finder), "filter"), ())}
    types |= {made.value for made in known.get((id(finder), "type"), ())}
    return types.pop() if len(types) == 1 else None


def ways_to(node: TreeNode, parents: dict, known: dict) -> list[Way]:
    """The ways through the tree's choices before `node` (`ways_before`) on which every
    Switch above it, or chosen on the way, runs the child the way goes through (`known`:
    the known values by (id(node), port))."""
    nodes = {id(n): n for n in parents.values()}
    above, child = [], node
    while (parent := parents.get(id(child))) is not None:
        if isinstance(parent, Switch):
            above.append((parent, _index(parent, child)))
        child = parent
    ways = []
    for way in ways_before(node, parents):
        chosen = [(nodes[i], c) for i, c in way.items() if isinstance(nodes.get(i), Switch)]
        runs = partial(_runs, parents=parents, known=known, way=way)
        if all(runs(switch) in (None, index) for switch, index in above + chosen):
            ways.append(way)
    return ways


def _index(parent: TreeNode, child: TreeNode) -> int:
    """Which child of `parent` `child` is (by identity: a SubTree used twice is two)."""
    return [id(c) for c in parent.children_nodes()].index(id(child))


def _runs(switch: Switch, parents: dict, known: dict, way: Way) -> int | None:
    """The child `switch` runs the `way` the tree went when its variable is the type of an
    object whose finder's type is known and its cases are known (None: not known)."""
    entry = getattr(switch.config.inputs.get("variable"), "entry", None)
    reader = last_before(switch, parents, partial(writes, entry), way) if entry else None
    if not isinstance(reader, ObjectAttribute):
        return None
    attribute = {k.value for k in known.get((id(reader), "attribute"), ())}
    kind = finder_type(known, finder_of(reader, parents, way))
    cases = [[k.value for k in known.get((id(switch), port), ())] for port in switch.case_ports]
    if attribute != {"type"} or kind is None or any(len(case) != 1 for case in cases):
        return None
    return next((i for i, [case] in enumerate(cases) if str(case) == kind), len(cases))
