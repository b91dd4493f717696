"""What a loaded tree's input ports will read that is known before it runs.

A port reads a literal of the XML, or a blackboard entry. An entry's value is known when
the scenario puts it on the root blackboard (a location, an area, a parameter), when a
SubTree passes a literal to it, when SetBlackboard copies a known value into it, or when a
node whose outputs follow from its inputs alone (`static_outputs`, e.g. OffsetPose) writes
it from inputs that are known in turn; entries are followed through SubTree remapping
(remapped ports share the parent's entry). Values
that come from the world (NextObject's pose) or from scripts are unknown, and left out:
every known value is one the port can really read, never all of them.

`validate` checks these values the way the running nodes will (a port's range, the
robot's reach of a target, a person's place to stand), and names where each came from.
"""

import itertools
from collections.abc import Iterator
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from hrc_drake.bt import Tree
from hrc_drake.bt.actions import SetBlackboard
from hrc_drake.bt.blackboard import UNSET, Entry
from hrc_drake.bt.controls.branches import Switch
from hrc_drake.bt.errors import closest
from hrc_drake.bt.node import EntryRef, Literal, TreeNode
from hrc_drake.bt.ports import coerce
from hrc_drake.bt.script import ScriptCode
from hrc_drake.bt.script_keys import assigned_keys, read_keys
from hrc_drake.tree_types import Pose

MAX_KNOWN = 64
"""Known values kept per entry: a tree offsetting a pose in a loop has ever more of them."""


@dataclass(frozen=True)
class Origin:
    """Where a known value was written: a scenario entry (`section` is `locations`,
    `areas` or `parameters`, `key` its name), or a literal of the tree (`node` the node or
    SubTree whose port `key` gives it, `value` what it gives)."""

    key: str
    section: str = ""
    node: TreeNode | None = field(default=None, compare=False)
    value: Any = field(default=None, compare=False)

    def __str__(self) -> str:
        """`parameter 'speed'`, `location 'tray'` (named by a literal too), `'0;0;0.1'`."""
        if self.section:
            return f"{self.section[:-1]} '{self.key}'"
        if isinstance(self.value, Pose) and self.value.name:
            return f"location '{self.value.name}'"
        return f"'{self.node.config.attributes.get(self.key, self.value)}'"


@dataclass(frozen=True)
class Known:
    """A value a port can read, where it was first written, and the nodes that made it
    from that (`via`: 'OffsetPose (robot.xml:12)', ...)."""

    value: Any
    origin: Origin
    via: tuple[str, ...] = ()

    def __str__(self) -> str:
        """Where it comes from: `location 'tray'`, `the value OffsetPose (robot.xml:12)
        made from location 'tray'`."""
        if not self.via:
            return str(self.origin)
        return f"the value {' then '.join(self.via)} made from {self.origin}"


def known_inputs(tree: Tree, sections: dict[str, str]) -> Iterator[tuple[TreeNode, str, list]]:
    """(node, port, known values) of every input port whose value is known: its literal,
    or what its blackboard entry can hold; `sections` names the section of each root entry
    the scenario set (key -> locations, areas or parameters)."""
    values = _KnownValues(tree, sections)
    for node in tree.node_list:
        for port, binding in node.config.inputs.items():
            if found := values.input(binding, node, port):
                yield node, port, found


def unwritten_inputs(
    tree: Tree, sections: dict[str, str]
) -> Iterator[tuple[TreeNode, str, str, str]]:
    """(node, port, key, why nothing sets it: `_why_unset`) of every input a node reads from
    a blackboard entry that nothing ever sets where it reads: no scenario entry or SubTree
    literal, no node's output, SetBlackboard or script (reading it ends a run: "blackboard
    entry 'key' is not set"); and of every key a node's script (a Script port, a pre- or
    postcondition; `port` names it) reads that nothing sets ("variable 'key' is not
    set"). None when a script's code is itself an entry (what it writes is not known).
    SwitchN's cases are left out: an unset case matches nothing. `sections`: as
    `known_inputs`'s."""
    written = _written_entries(tree)
    if written is None:
        return
    created = {key.lstrip("@") for node in tree.node_list for key in _script_assigned(node)}
    names = created | _written_names(tree, written)
    for node in tree.node_list:
        for port, binding in node.config.inputs.items():
            entry = getattr(binding, "entry", None)
            if entry is None or entry.value is not UNSET or id(entry) in written:
                continue
            if isinstance(node, Switch) and port in node.case_ports:
                continue
            yield node, port, binding.key, _why_unset(binding.key, node, written, names, sections)
        for port, key in _script_reads(node):
            entry = node.blackboard.entry(key)
            if entry is None and key.lstrip("@") in created:
                continue
            if entry is not None and (entry.value is not UNSET or id(entry) in written):
                continue
            yield node, port, key, _why_unset(key, node, written, names, sections)


SUBTREE_HINT = (
    "'{key}' is set outside this SubTree, whose blackboard is its own: pass it in on the "
    'SubTree ({key}="{{{key}}}") or give the SubTree _autoremap="true"'
)


UNSET_WHY = (
    "no scenario parameter, location or area, SubTree port, node output, SetBlackboard or "
    "script writes it"
)
SCENARIO_WHY = (
    "the scenario {section} '{key}' is on the root blackboard, which this SubTree does not "
    'see (its blackboard is its own): remap it on the SubTree ({key}="{{{key}}}") or give '
    'the SubTree _autoremap="true"'
)


def _why_unset(key: str, node: TreeNode, written, names: set[str], sections) -> str:
    """Why the entry `key` that `node` reads is never set: a scenario entry of that name
    is not remapped into the SubTree that reads it (a user's waiting SubTree read the
    scenario's 'wait_weights' and was told no scenario parameter writes it), or nothing
    writes it (with `_hint`'s guess)."""
    name = key.lstrip("@")
    root = node.blackboard.root
    scenario = root.local_entries().get(name)
    if node.blackboard is not root and scenario is not None and scenario.value is not UNSET:
        section = sections.get(name, "parameters")[:-1]
        return SCENARIO_WHY.format(section=section, key=name)
    hint = _hint(key, node, written, names)
    return f"{UNSET_WHY} ({hint})" if hint else UNSET_WHY


def _hint(key: str, node: TreeNode, written: set[int], names: set[str]) -> str | None:
    """What the user probably meant by an unset `key` (None: no guess): a key written on
    another blackboard was set outside a SubTree that does not see it (a user's inspection
    SubTree read a route its caller set, and was told "did you mean 'robot_speed'?"); else
    the nearest key that is set where the node reads."""
    if key.lstrip("@") in names:
        return SUBTREE_HINT.format(key=key.lstrip("@"))
    near = closest(key, _set_keys(node, written))
    return f"did you mean '{near}'?" if near else None


def _written_names(tree: Tree, written: set[int]) -> set[str]:
    """The keys written on every blackboard of the tree: of the written entries, and those a
    SetBlackboard writes before anything declares them (a script's: `created`)."""
    declared = {
        key
        for node in tree.node_list
        for key, entry in node.blackboard.local_entries().items()
        if id(entry) in written
    }
    return declared | {_set_key(n) for n in tree.node_list if isinstance(n, SetBlackboard)}


def _written_entries(tree: Tree) -> set[int] | None:
    """The ids of the entries some node writes (outputs, SetBlackboard, scripts)."""
    written = set()
    for node in tree.node_list:
        written.update(id(binding.entry) for binding in node.config.outputs.values())
        if isinstance(node, SetBlackboard) and (entry := set_entry(node)) is not None:
            written.add(id(entry))
        if any(code is None for _, code in _script_codes(node)):
            return None
        for key in _script_assigned(node):
            if (entry := node.blackboard.entry(key)) is not None:
                written.add(id(entry))
    return written


def _script_codes(node: TreeNode) -> list[tuple[str, str | None]]:
    """(attribute or port, code) of every script of a node (None: code read from an
    entry)."""
    config = node.config
    codes = [(name, script.code) for name, script in config.preconditions]
    codes += [(name, script.code) for name, script in config.postconditions.items()]
    script_ports = {p.name for p in getattr(type(node), "ports", ()) if p.type is ScriptCode}
    for port in sorted(script_ports & set(config.inputs)):
        binding = config.inputs[port]
        codes.append((port, binding.value if isinstance(binding, Literal) else None))
    return codes


def _script_assigned(node: TreeNode) -> list[str]:
    """The keys the node's scripts assign."""
    return [key for _, code in _script_codes(node) if code for key in assigned_keys(code)]


def _script_reads(node: TreeNode) -> Iterator[tuple[str, str]]:
    """(attribute or port, key) of every blackboard key the node's scripts read (enum names
    are not keys)."""
    enums = getattr(node.config.tree, "enums", {})
    for port, code in _script_codes(node):
        for key in dict.fromkeys(read_keys(code or "")):
            if key not in enums:
                yield port, key


def _set_keys(node: TreeNode, written: set[int]) -> list[str]:
    """The keys the node's blackboard and the root's hold that are set or written."""
    entries = {**node.blackboard.root.local_entries(), **node.blackboard.local_entries()}
    return [
        key for key, entry in entries.items() if entry.value is not UNSET or id(entry) in written
    ]


class _KnownValues:
    """Known values of entries, computed on demand and kept."""

    def __init__(self, tree: Tree, sections: dict[str, str]):
        self.tree = tree
        self.initial: dict[int, Known] = dict(_initial_values(tree, sections))
        self.writers: dict[int, list[tuple[TreeNode, str]]] = {}
        for node in tree.node_list:
            if hasattr(type(node), "static_outputs"):
                for port, binding in node.config.outputs.items():
                    self.writers.setdefault(id(binding.entry), []).append((node, port))
        for node in tree.node_list:
            if isinstance(node, SetBlackboard) and (entry := set_entry(node)) is not None:
                self.writers.setdefault(id(entry), []).append((node, "value"))
        self.known: dict[int, list[Known]] = {}

    def of(self, entry: Entry) -> list[Known]:
        key = id(entry)
        if key not in self.known:
            found = [self.initial[key]] if key in self.initial else []
            self.known[key] = found  # an entry written from itself sees its first values
            for node, port in self.writers.get(key, ()):
                found += self._outputs(node, port)
            self.known[key] = _distinct(found)[:MAX_KNOWN]
        return self.known[key]

    def _outputs(self, node: TreeNode, port: str) -> list[Known]:
        """What `node` writes to `port` for each combination of its known inputs (what
        SetBlackboard copies: its known `value`s, as the entry it writes reads them)."""
        if isinstance(node, SetBlackboard):
            return _copied(self.input(node.config.inputs["value"], node, "value"), node)
        bindings = node.config.inputs.items()
        inputs = {name: self.input(binding, node, name) for name, binding in bindings}
        if not all(inputs.values()):
            return []
        names = list(inputs)
        step = step_of(node)
        found = []
        for combination in itertools.islice(itertools.product(*inputs.values()), MAX_KNOWN):
            given = dict(zip(names, combination, strict=True))
            try:
                values = {name: known.value for name, known in given.items()}
                value = type(node).static_outputs(self.tree.agent, values)[port]
            except (KeyError, ValueError):
                continue  # the node would fail on these inputs: nothing is written
            first = next((k for k in combination if k.origin.section), combination[0])
            found.append(Known(value, first.origin, (*first.via, step)))
        return found

    def input(self, binding, node: TreeNode, port: str) -> list[Known]:
        if isinstance(binding, Literal):
            return [Known(binding.value, Origin(port, node=node, value=binding.value))]
        return self.of(binding.entry)


def set_entry(node: SetBlackboard) -> Entry | None:
    """The entry a SetBlackboard writes, if declared."""
    key = _set_key(node)
    return node.blackboard.entry(key) if key else None


def _set_key(node: SetBlackboard) -> str:
    """The key a SetBlackboard writes (`output_key="key"` or `"{key}"`)."""
    binding = node.config.inputs.get("output_key")
    return binding.key if isinstance(binding, EntryRef) else getattr(binding, "value", "")


def _copied(values: list[Known], node: SetBlackboard) -> list[Known]:
    entry = set_entry(node)
    found = []
    for known in values:
        try:
            value = coerce(known.value, entry.type)
        except ValueError:
            continue  # the node would fail to write it
        found.append(Known(value, known.origin, (*known.via, step_of(node))))
    return found


def step_of(node: TreeNode) -> str:
    """`OffsetPose (robot.xml:12)`: a node that made a value, as messages name it."""
    return f"{node.registration_id} ({Path(node.config.file).name}:{node.config.line})"


def _initial_values(tree: Tree, sections: dict[str, str]) -> Iterator[tuple[int, Known]]:
    """The entries set when the tree was loaded: the scenario's on the root blackboard, the
    SubTrees' literal ports on theirs."""
    subtree_nodes = {node.path: node for node in tree.node_list if node.kind == "SubTree"}
    for index, instance in enumerate(tree.subtrees):
        for key, entry in instance.blackboard.local_entries().items():
            if entry.value is UNSET:
                continue
            if index == 0:
                origin = Origin(key, section=sections.get(key, "parameters"))
            else:
                origin = Origin(key, node=subtree_nodes[instance.path], value=entry.value)
            yield id(entry), Known(entry.value, origin)


def _distinct(found: list[Known]) -> list[Known]:
    seen, kept = set(), []
    for known in found:
        key = repr(known.value)
        if key not in seen:
            seen.add(key)
            kept.append(known)
    return kept
