"""Behavior tree engine for BehaviorTree.CPP v4 XML, in pure Python (imports no Drake).

Semantics follow BehaviorTree.CPP 4.x (see docs/bt-semantics.md), except
that time comes only from ``Tree.tick(now)`` (Delay, Timeout, Sleep run on simulation
time) and randomness only from the tree's numpy Generator; one ``tick`` is BT.CPP's
``tickExactlyOnce``.

Loading and running::

    tree = load_tree("trees/robot.xml", registry, seed=7, context=my_context)
    status = tree.tick(now=0.05)      # Status.RUNNING / SUCCESS / FAILURE / SKIPPED
    tree.halt(); tree.reset()         # back to the state after construction
    tree.root_blackboard.set("goal", pose)
    for uid, path, node in tree.nodes(): ...

``TreeFactory(registry)`` loads several files (``load_file``/``load_string``, with
``<include>``) and builds any of their trees (``create_tree(tree_id)``);
``validate(source, registry)`` returns every :class:`BTError` without running.

Writing nodes: subclass ``SyncActionNode``/``ConditionNode`` (``tick``),
``StatefulActionNode`` (``on_start``/``on_running``/``on_halted``), ``ControlNode`` or
``DecoratorNode``; declare ``ports = (InputPort("target", type=Pose), OutputPort(...))``,
with ``accepts=Range(0, 1)`` or ``OneOf(words)`` where a port takes only some values
(checked on literals when the tree is built and on every blackboard read; a node adds rules
of its own in ``input_problem``); inside, use ``get_input(name)``,
``set_output(name, value)``, ``self.now``, ``self.rng`` (the tree's Generator) and
``self.agent`` (whatever the application set as ``tree.agent``: the agent the tree drives,
e.g. actor status and a command outbox). Register with ``registry.register(MyNode)`` or
``registry.register_function("Id", fn, kind=...)``; enums for scripts with
``registry.register_enum(E)``; port types read from XML text with
``register_type(Pose, Pose.from_string, "Pose")``.

Observing: ``tree.add_observer(obs)`` with ``obs.on_transition(time, node, previous,
new)``; ``BtlogWriter(path)`` (Groot2 .btlog), ``JsonLinesWriter(path)``,
``NodeCounters()``; ``render_tree(tree, "tree.svg", color_by="status")``;
``tree_nodes_model_xml(registry)`` for Groot2's node palette.

Errors: one class, :class:`BTError`, whose message is one line
``file:line: tree 'ID', node 'path', port 'name': problem (did you mean 'X'?)``.
"""

from .actions import FunctionAction, FunctionCondition
from .blackboard import Blackboard
from .errors import BTError
from .factory import TreeFactory, load_tree, validate
from .model_xml import tree_nodes_model_xml, tree_to_xml
from .node import TreeNode
from .node_kinds import (
    ConditionNode,
    ControlNode,
    DecoratorNode,
    StatefulActionNode,
    SyncActionNode,
)
from .observers import BtlogWriter, JsonLinesWriter, NodeCount, NodeCounters
from .ports import (
    BidirectionalPort,
    InputPort,
    OneOf,
    OutputPort,
    PortDirection,
    PortInfo,
    Range,
    convert_from_string,
    register_type,
)
from .registry import NodeModel, NodeRegistry, default_registry
from .render import render_tree, tree_graph
from .status import Status
from .tree import TransitionObserver, Tree

__all__ = [
    "BTError",
    "BtlogWriter",
    "JsonLinesWriter",
    "NodeCount",
    "NodeCounters",
    "BidirectionalPort",
    "Blackboard",
    "ConditionNode",
    "ControlNode",
    "DecoratorNode",
    "FunctionAction",
    "FunctionCondition",
    "InputPort",
    "NodeModel",
    "NodeRegistry",
    "OneOf",
    "OutputPort",
    "PortDirection",
    "PortInfo",
    "Range",
    "StatefulActionNode",
    "Status",
    "SyncActionNode",
    "TransitionObserver",
    "Tree",
    "TreeFactory",
    "TreeNode",
    "convert_from_string",
    "default_registry",
    "load_tree",
    "register_type",
    "render_tree",
    "tree_graph",
    "tree_nodes_model_xml",
    "tree_to_xml",
    "validate",
]
