"""A scenario's behavior trees: loaded with the HRC node library, checked against the
scenario's named places and against what their agent may command (hrc_drake.wiring), with
the root blackboard filled from the scenario.

Every tree's root blackboard holds the scenario's locations (as Poses), areas and
`parameters`, so a tree can write `{table_top}` as well as the literal `table_top`.
"""

from collections.abc import Iterator
from dataclasses import dataclass, field

from hrc_drake.bt import BTError, Tree, load_tree, validate
from hrc_drake.bt.node import EntryRef
from hrc_drake.bt.ports import convert_from_string
from hrc_drake.bt.registry import NodeModel
from hrc_drake.known_values import Known, known_inputs
from hrc_drake.nodes import hrc_registry
from hrc_drake.nodes.agent import Agent, Places
from hrc_drake.tree_types import AreaRef, Pose
from hrc_drake.wiring import COMMANDED_BY
from hrc_drake.yaml_check import NEW_ENTRIES, REQUIRED, did_you_mean


@dataclass
class AgentTree:
    """The behavior tree an agent runs: a BehaviorTree.CPP v4 XML file (relative to the
    scenario file), which of its trees (default: its main tree), and the tick period.

    `ports` replace port values the XML gives, by node name (every node of that name) and
    port, e.g. `{walk_in: {animation_distance: "1.9"}}`: a tree exposes a parameter by
    naming a node, and `--set trees.human.ports.walk_in.animation_distance=1.9` or a
    `falsify:` parameter can change it without editing the tree."""

    file: str = field(default="", metadata=REQUIRED)
    tree_id: str = ""
    period: float = 0.05
    ports: dict[str, dict[str, str]] = field(default_factory=dict, metadata={NEW_ENTRIES: True})


def blackboard_entries(places: Places, parameters: dict[str, str]) -> dict:
    return {**places.locations, **places.areas, **parameters}


class ParameterError(BTError):
    """A scenario parameter that a tree reads as a type its text cannot be converted to."""

    def __init__(self, key: str, error: BTError):
        super().__init__(f"a tree cannot read it: {error.problem}")
        self.key = key


def load_agent_tree(
    config: AgentTree, agent: str, places: Places, parameters: dict[str, str]
) -> tuple[Tree, Agent]:
    """The agent's tree, its Agent, and its root blackboard filled with the places and
    parameters; a node that commands an actor the agent may not command is a located
    BTError."""
    handle = Agent(agent, places)
    tree = load_tree(
        config.file,
        hrc_registry(),
        tree_id=config.tree_id or None,
        agent=handle,
        port_values=config.ports,
    )
    for error in command_errors(agent, tree):
        raise error
    for key, value in blackboard_entries(places, parameters).items():
        try:
            tree.root_blackboard.set(key, value)
        except BTError as error:  # only parameters are text the tree may not read
            raise ParameterError(key, error) from None
    tree.root_blackboard.remember_initial_state()
    return tree, handle


def command_errors(agent: str, tree: Tree) -> list[BTError]:
    """Nodes that would command an actor `agent` may not command: nothing would carry the
    command out (a RobotMove in the person's tree would run forever)."""
    allowed = COMMANDED_BY[agent]
    errors = []
    for _, _, node in tree.nodes():
        for actor in getattr(type(node), "commands", ()):
            if actor not in allowed:
                problem = (
                    f"the {agent}'s tree may not command the {actor} "
                    f"(it commands: {', '.join(allowed)})"
                )
                errors.append(node.error(problem))
    return errors


Problem = tuple[tuple, str]


def tree_errors(
    trees: dict[str, AgentTree], places: Places, parameters: dict[str, str]
) -> list[BTError | Problem]:
    """Everything wrong with a scenario's trees, without running them: the engine's checks
    (unknown nodes, ports, values, scripts, includes, which tree is the main one), nodes
    that command what their agent may not, names of places that are not defined, and
    parameters and port values (as a scenario Problem: field names and message) that the
    trees cannot read or whose ports do not accept them."""
    errors: list[BTError | Problem] = []
    for agent, config in trees.items():
        found = validate(config.file, hrc_registry(), tree_id=config.tree_id or None)
        if found:
            errors += found
            continue
        try:
            port_problems = list(_port_value_problems(agent, config))
            if port_problems:
                errors += port_problems
                continue
            tree = load_agent_tree(config, agent, places, parameters)[0]
            errors += _place_errors(config, places, tree)
            errors += value_errors(tree, sections(places))
        except ParameterError as error:
            errors.append((("parameters", error.key), error.problem))
        except BTError as error:  # no main tree to run
            errors.append(error.located(file=config.file))
    return errors


def _port_value_problems(agent: str, config: AgentTree) -> Iterator[Problem]:
    """Port values the scenario gives (`ports`) for nodes and ports the tree has, in text
    the port's type reads."""
    if not config.ports:
        return
    named = named_nodes(config)
    for name, values in config.ports.items():
        for port, text in values.items():
            problem = port_value_problem(named, agent, name, port, text)
            if problem:
                yield ("trees", agent, "ports", name, port), problem


def named_nodes(config: AgentTree) -> dict[str, NodeModel]:
    """The node types of the agent's tree by node name (the first node of each name)."""
    registry = hrc_registry()
    named = {}
    for _, _, node in load_tree(config.file, registry, tree_id=config.tree_id or None).nodes():
        named.setdefault(node.name, registry[node.config.registration_id])
    return named


def port_value_problem(named: dict, agent: str, name: str, port: str, text: str) -> str:
    """What is wrong with giving input `port` of the nodes called `name` the value `text`
    ("" when nothing is)."""
    model = named.get(name)
    if model is None:
        return f"no node named '{name}' in the {agent}'s tree{did_you_mean(name, named)}"
    inputs = {info.name: info for info in model.ports.values() if info.is_input}
    if port not in inputs:
        return f"'{model.id}' has no input port '{port}' (it has: {', '.join(inputs) or 'none'})"
    try:
        value = convert_from_string(text, inputs[port].type)
    except ValueError as error:
        return str(error)
    accepts = inputs[port].accepts
    return accepts.problem(value) if accepts is not None else ""


def sections(places: Places) -> dict[str, str]:
    """The scenario section of each root blackboard entry that is a place (key -> section);
    the others are parameters."""
    return {**dict.fromkeys(places.locations, "locations"), **dict.fromkeys(places.areas, "areas")}


def value_errors(tree: Tree, sections: dict[str, str]) -> list[BTError | Problem]:
    """Values known before the run that a port reading them from the blackboard does not
    accept (literals were checked when the tree was built), each where it was written: a
    parameter at its line in the scenario (naming the node that reads it), a SubTree's
    literal at the SubTree, one a node made from them at the node that reads it."""
    errors = []
    for node, port, known in known_inputs(tree, sections):
        if not isinstance(node.config.inputs[port], EntryRef):
            continue
        for value in known:
            if problem := node.input_problem(port, value.value):
                errors.append(_value_error(node, port, value, problem))
    return _once(errors)


def _value_error(node, port: str, known: Known, problem: str) -> BTError | Problem:
    config = node.config
    reader = (
        f"{config.registration_id} '{node.path}' reads it as {port} ({config.file}:{config.line})"
    )
    origin = known.origin
    if origin.section and not known.via:
        return (origin.section, origin.key), f"{problem}: {reader}"
    if origin.node is not None and not known.via:
        return origin.node.error(f"{problem}: {reader}", port=origin.key)
    return node.error(f"{problem} ({known})" if known.via else problem, port=port)


def _once(errors: list) -> list:
    """Each error once (a SubTree used twice reads the same parameter twice)."""
    unique = {str(error) if isinstance(error, BTError) else repr(error): error for error in errors}
    return list(unique.values())


def _place_errors(config: AgentTree, places: Places, tree: Tree) -> list[BTError | Problem]:
    """Places the tree names that the scenario lacks: at the tree's node and port, or at
    the scenario's `ports` entry that gave the value."""
    errors = []
    for _, _, node in tree.nodes():
        for port, binding in node.config.inputs.items():
            value = getattr(binding, "value", None)
            problem = _unknown_place(places, value)
            if problem and port in config.ports.get(node.name, {}):
                errors.append((("trees", tree.agent.name, "ports", node.name, port), problem))
            elif problem:
                errors.append(node.error(problem, port=port))
    return errors


def _unknown_place(places: Places, value) -> str:
    if isinstance(value, Pose) and value.name and value.name not in places.locations:
        return f"unknown location '{value.name}' (scenario locations: {_names(places.locations)})"
    if isinstance(value, AreaRef) and value.name not in places.areas:
        return f"unknown area '{value.name}' (scenario areas: {_names(places.areas)})"
    return ""


def _names(names) -> str:
    return ", ".join(sorted(names)) or "none"
