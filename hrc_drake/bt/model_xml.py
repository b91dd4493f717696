"""XML exports for Groot2: the TreeNodesModel of a registry, and a built tree with
every node's ``_uid`` (the header of a .btlog file)."""

from __future__ import annotations

import xml.etree.ElementTree as ElementTree

from .node import TreeNode
from .ports import type_name, value_to_text
from .registry import NodeModel, NodeRegistry
from .tree import Tree


def _add_model(parent: ElementTree.Element, model: NodeModel) -> None:
    element = ElementTree.SubElement(parent, model.kind, ID=model.id)
    for port in model.ports.values():
        port_element = ElementTree.SubElement(element, port.direction.value, name=port.name)
        if port.type is not None:
            port_element.set("type", type_name(port.type))
        if port.has_default and port.default is not None:
            port_element.set("default", value_to_text(port.default))
        if port.description:
            port_element.text = port.description


def _models_element(
    parent: ElementTree.Element, registry: NodeRegistry, include_builtin: bool
) -> None:
    models = ElementTree.SubElement(parent, "TreeNodesModel")
    for model in sorted(registry.models(), key=lambda model: model.id):
        if include_builtin or not model.builtin:
            _add_model(models, model)


def _to_text(root: ElementTree.Element) -> str:
    ElementTree.indent(root)
    return ElementTree.tostring(root, encoding="unicode") + "\n"


def tree_nodes_model_xml(registry: NodeRegistry, include_builtin: bool = False) -> str:
    """``<root><TreeNodesModel>`` listing node types with their ports, for Groot2."""
    root = ElementTree.Element("root", BTCPP_format="4")
    _models_element(root, registry, include_builtin)
    return _to_text(root)


_OWN = ("_uid", "_fullpath")
_SUBTREE_OWN = (*_OWN, "name", "_autoremap")
"""Attributes BT.CPP's WriteTreeToXML writes itself or leaves out (a SubTree's name is its
``_fullpath``)."""


_OWN = ("_uid", "_fullpath")
_SUBTREE_OWN = (*_OWN, "name", "_autoremap")
"""Attributes BT.CPP's WriteTreeToXML writes itself or leaves out (a SubTree's name is its
``_fullpath``)."""


def _add_node(parent: ElementTree.Element, node: TreeNode) -> None:
    element = ElementTree.SubElement(parent, node.registration_id)
    for attribute, value in node.config.attributes.items():
        if attribute not in (_SUBTREE_OWN if node.kind == "SubTree" else _OWN):
            element.set(attribute, value)
    if node.kind == "SubTree":
        element.set("_fullpath", node.path)
    else:
        element.set("name", node.name)
    element.set("_uid", str(node.uid))
    if node.kind != "SubTree":
        for child in node.children_nodes():
            _add_node(element, child)


def tree_to_xml(tree: Tree) -> str:
    """The tree as BehaviorTree.CPP's WriteTreeToXML(tree, true, true) writes it: one
    <BehaviorTree _fullpath> per SubTree instance, nodes carrying their ``_uid``."""
    root = ElementTree.Element("root", BTCPP_format="4")
    for instance in tree.subtrees:
        element = ElementTree.SubElement(
            root, "BehaviorTree", ID=instance.tree_id, _fullpath=instance.path
        )
        _add_node(element, instance.root)
    _models_element(root, tree.registry, include_builtin=True)
    return _to_text(root)
