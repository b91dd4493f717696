"""Building a tree from parsed BehaviorTree.CPP v4 XML: each element becomes a node of a
registered type with its ports bound (literals converted, ``{key}`` entries declared on the
blackboard), its pre/post-condition scripts compiled, and each SubTree an instance with a
blackboard of its own. In collecting mode every error is recorded and building carries on
(validation); otherwise the first error is raised."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

from .blackboard import Blackboard
from .decorators import SubTreeNode
from .errors import BTError, closest
from .node import POSTCONDITIONS, PRECONDITIONS, EntryRef, Literal, NodeConfig, TreeNode
from .ports import (
    PortDirection,
    PortInfo,
    convert_from_string,
    literal_value,
    port_key,
    subtree_key,
)
from .registry import NodeModel, NodeRegistry
from .script import ScriptCode, compile_script
from .tree import SubtreeInstance, Tree
from .xmlparse import XmlElement

GENERIC_TAGS = ("Action", "Condition", "Control", "Decorator")
IGNORED_ATTRIBUTES = frozenset(("ID", "name", "_description", "_uid", "_fullpath"))


@dataclass(frozen=True)
class TreeDefinition:
    """One <BehaviorTree> element and the file it came from."""

    id: str
    element: XmlElement

    @property
    def file(self) -> str:
        return self.element.file


@dataclass
class _Scope:
    """Where the builder is: which definition, which blackboard, which path prefix."""

    definition: TreeDefinition
    blackboard: Blackboard
    prefix: str
    stack: tuple[str, ...]

    def where(self, element: XmlElement, **more: Any) -> dict[str, Any]:
        return {"file": element.file, "line": element.line, "tree": self.definition.id, **more}


@dataclass
class TreeBuilder:
    """Instantiates nodes; in collecting mode it records errors and carries on."""

    registry: NodeRegistry
    definitions: dict[str, TreeDefinition]
    tree: Tree
    collect: bool
    errors: list[BTError] = field(default_factory=list)
    next_uid: int = 1
    port_values: Mapping[str, Mapping[str, str]] = field(default_factory=dict)
    """Port attributes that replace the XML's, by node name (every node of that name)."""

    def report(self, error: BTError) -> None:
        if not self.collect:
            raise error
        self.errors.append(error)

    def build_instance(
        self, tree_id: str, blackboard: Blackboard, path: str, stack: tuple[str, ...]
    ) -> TreeNode | None:
        definition = self.definitions[tree_id]
        roots = definition.element.children
        if len(roots) != 1:
            self.report(
                BTError(
                    f"a BehaviorTree must have exactly one root node, has {len(roots)}",
                    file=definition.file,
                    line=definition.element.line,
                    tree=tree_id,
                )
            )
            return None
        instance_index = len(self.tree.subtrees)
        scope = _Scope(definition, blackboard, f"{path}/" if path else "", (*stack, tree_id))
        self.tree.subtrees.append(None)
        root = self.build_node(roots[0], scope)
        self.tree.subtrees[instance_index] = SubtreeInstance(tree_id, path, root, blackboard)
        return root

    def build_node(self, element: XmlElement, scope: _Scope) -> TreeNode | None:
        uid = self.next_uid
        self.next_uid += 1
        type_id = element.attributes.get("ID", "") if element.tag in GENERIC_TAGS else element.tag
        name = element.attributes.get("name") or type_id
        path = scope.prefix + (name if name != type_id else f"{type_id}::{uid}")
        if type_id not in self.registry:
            self.report(
                BTError(
                    f"unknown node type '{type_id}'",
                    node=path,
                    suggestion=closest(type_id, self.registry.ids()),
                    **scope.where(element),
                )
            )
            return None
        model = self.registry[type_id]
        if not self._check_children(model, element, scope, path):
            return None
        if model.cls is SubTreeNode:
            return self._build_subtree(element, scope, uid)
        config = self._config(model, element, scope, uid, name, path)
        node = self._create(model, config, element, scope)
        if node is None:
            return None
        children = [self.build_node(child, scope) for child in element.children]
        if None not in children:
            self._attach(node, children)
            self._check_literals(node, element, scope)
        return node

    def _check_literals(self, node: TreeNode, element: XmlElement, scope: _Scope) -> None:
        """Literal inputs the node does not accept (a velocity of 100 for a fraction, two
        weights for three children), known once its children are attached."""
        for port, binding in node.config.inputs.items():
            if isinstance(binding, Literal) and (
                problem := node.input_problem(port, binding.value)
            ):
                self.report(BTError(problem, node=node.path, port=port, **scope.where(element)))

    def _check_children(
        self, model: NodeModel, element: XmlElement, scope: _Scope, path: str
    ) -> bool:
        least, most = model.children_range
        count = len(element.children)
        if least <= count and (most is None or count <= most):
            return self._check_async_children(model, element, scope, path)
        expected = (
            f"exactly {least}"
            if least == most
            else f"at least {least}"
            if most is None
            else f"{least} to {most}"
        )
        self.report(
            BTError(
                f"'{model.id}' needs {expected} children, has {count}",
                node=path,
                **scope.where(element),
            )
        )
        return False

    def _check_async_children(
        self, model: NodeModel, element: XmlElement, scope: _Scope, path: str
    ) -> bool:
        """BT.CPP's loader refuses a ReactiveSequence with two AsyncSequence children (it
        counts children by tag, so only these): a tree it cannot load must not run here."""
        tags = [child.tag for child in element.children]
        if model.id != "ReactiveSequence" or tags.count("AsyncSequence") < 2:
            return True
        self.report(
            BTError(
                "a ReactiveSequence cannot have more than one AsyncSequence child "
                "(BehaviorTree.CPP refuses to load it)",
                node=path,
                **scope.where(element),
            )
        )
        return False

    @staticmethod
    def _attach(node: TreeNode, children: list[TreeNode]) -> None:
        if hasattr(node, "children"):
            node.children.extend(children)
        elif children:
            node.child = children[0]

    def _create(
        self, model: NodeModel, config: NodeConfig, element: XmlElement, scope: _Scope
    ) -> TreeNode | None:
        try:
            node = model.create(config)
        except (BTError, ValueError) as error:
            problem = error.problem if isinstance(error, BTError) else str(error)
            self.report(BTError(problem, node=config.path, **scope.where(element)))
            return None
        self.tree.node_list.append(node)
        return node

    def _config(
        self, model: NodeModel, element: XmlElement, scope: _Scope, uid: int, name: str, path: str
    ) -> NodeConfig:
        attributes = {**element.attributes, **self.port_values.get(name, {})}
        config = NodeConfig(
            model.id,
            name,
            uid,
            path,
            self.tree,
            scope.blackboard,
            attributes=attributes,
            file=element.file,
            line=element.line,
            tree_id=scope.definition.id,
        )
        ports = model.ports
        config.accepts = {name: port.accepts for name, port in ports.items() if port.accepts}
        for attribute, text in attributes.items():
            if attribute in IGNORED_ATTRIBUTES:
                continue
            if attribute in PRECONDITIONS or attribute in POSTCONDITIONS:
                self._add_condition(config, attribute, text, element, scope)
            elif attribute in ports:
                self._bind(config, ports[attribute], text, element, scope)
            else:
                self.report(
                    BTError(
                        f"port '{attribute}' is not declared by '{model.id}'",
                        node=path,
                        port=attribute,
                        suggestion=closest(attribute, list(ports)),
                        **scope.where(element),
                    )
                )
        for port in ports.values():
            if port.name in attributes:
                continue
            if port.has_default:
                self._bind_default(config, port, element, scope)
            elif port.required:
                self.report(
                    BTError(
                        f"missing required port of '{model.id}'",
                        node=path,
                        port=port.name,
                        **scope.where(element),
                    )
                )
        return config

    def _add_condition(
        self, config: NodeConfig, attribute: str, text: str, element: XmlElement, scope: _Scope
    ) -> None:
        script = self._compile(text, element, scope, config.path, attribute)
        if script is None:
            return
        if attribute in PRECONDITIONS:
            config.preconditions.append((attribute, script))
            config.preconditions.sort(key=lambda item: PRECONDITIONS.index(item[0]))
        else:
            config.postconditions[attribute] = script

    def _compile(self, code: str, element: XmlElement, scope: _Scope, path: str, port: str):
        try:
            return compile_script(code)
        except BTError as error:
            self.report(error.located(node=path, port=port, **scope.where(element)))
            return None

    def _bind(
        self, config: NodeConfig, port: PortInfo, text: str, element: XmlElement, scope: _Scope
    ) -> None:
        key = port_key(port.name, text)
        if key is not None:
            self._bind_entry(config, port, key, element, scope)
            return
        if port.direction is PortDirection.OUTPUT:
            self.report(
                BTError(
                    f"output port needs a blackboard entry like '{{{text}}}', "
                    f"not the literal '{text}'",
                    node=config.path,
                    port=port.name,
                    **scope.where(element),
                )
            )
            return
        try:
            value = convert_from_string(text, port.type)
        except ValueError as error:
            self.report(
                BTError(str(error), node=config.path, port=port.name, **scope.where(element))
            )
            return
        if (
            port.type is ScriptCode
            and self._compile(value, element, scope, config.path, port.name) is None
        ):
            return
        config.inputs[port.name] = Literal(value)

    def _bind_default(
        self, config: NodeConfig, port: PortInfo, element: XmlElement, scope: _Scope
    ) -> None:
        key = port_key(port.name, port.default) if isinstance(port.default, str) else None
        if key is not None:
            self._bind_entry(config, port, key, element, scope)
        else:
            config.inputs[port.name] = Literal(port.default)

    def _bind_entry(
        self, config: NodeConfig, port: PortInfo, key: str, element: XmlElement, scope: _Scope
    ) -> None:
        try:
            entry = scope.blackboard.declare(key, port.type)
        except BTError as error:
            self.report(error.located(node=config.path, port=port.name, **scope.where(element)))
            return
        reference = EntryRef(key, entry)
        if port.is_input:
            config.inputs[port.name] = reference
        if port.direction is not PortDirection.INPUT:
            config.outputs[port.name] = reference

    def _build_subtree(self, element: XmlElement, scope: _Scope, uid: int) -> TreeNode | None:
        attributes = element.attributes
        subtree_id = attributes.get("ID", "")
        path = scope.prefix + (attributes.get("name") or f"{subtree_id}::{uid}")
        where = scope.where(element, node=path)
        if subtree_id not in self.definitions:
            self.report(
                BTError(
                    f"unknown SubTree ID '{subtree_id}'",
                    suggestion=closest(subtree_id, list(self.definitions)),
                    **where,
                )
            )
            return None
        if subtree_id in scope.stack:
            cycle = " -> ".join((*scope.stack, subtree_id))
            self.report(BTError(f"SubTree cycle: {cycle}", **where))
            return None
        remap, literals, autoremap = self._subtree_ports(attributes, element, scope, path)
        blackboard = Blackboard(scope.blackboard, remap, autoremap)
        for key, text in literals.items():
            blackboard.set_local(key, literal_value(text))
        config = NodeConfig(
            "SubTree",
            attributes.get("name") or subtree_id,
            uid,
            path,
            self.tree,
            scope.blackboard,
            attributes=attributes,
            inputs={"_autoremap": Literal(autoremap)},
            file=element.file,
            line=element.line,
            tree_id=scope.definition.id,
        )
        for attribute in PRECONDITIONS + POSTCONDITIONS:
            if attribute in attributes:
                self._add_condition(config, attribute, attributes[attribute], element, scope)
        node = self._create(self.registry["SubTree"], config, element, scope)
        child = self.build_instance(subtree_id, blackboard, path, scope.stack)
        if node is not None and child is not None:
            node.child = child
        return node

    def _subtree_ports(
        self, attributes: dict[str, str], element: XmlElement, scope: _Scope, path: str
    ) -> tuple[dict[str, str], dict[str, str], bool]:
        remap, literals, autoremap = {}, {}, False
        for attribute, text in attributes.items():
            if attribute in IGNORED_ATTRIBUTES or attribute in PRECONDITIONS + POSTCONDITIONS:
                continue
            if attribute == "_autoremap":
                try:
                    autoremap = convert_from_string(text, bool)
                except ValueError as error:
                    self.report(
                        BTError(str(error), port=attribute, **scope.where(element, node=path))
                    )
                continue
            key = subtree_key(attribute, text)
            if key is None:
                literals[attribute] = text
            else:
                remap[attribute] = key
        return remap, literals, autoremap
