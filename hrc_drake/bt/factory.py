"""Loading BehaviorTree.CPP v4 XML (files, strings, their <include>s) into tree definitions,
choosing the main tree, and building a tree from them (the building itself is
:mod:`.tree_builder`) or only validating it."""

from __future__ import annotations

import os
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import numpy as np

from .blackboard import Blackboard
from .errors import BTError, closest
from .registry import NodeRegistry, default_registry
from .tree import Tree
from .tree_builder import TreeBuilder, TreeDefinition
from .xmlparse import XmlElement, parse_xml


class TreeFactory:
    """Reads XML files or strings (with <include>s) and builds trees from them."""

    def __init__(self, registry: NodeRegistry | None = None):
        self.registry = registry if registry is not None else default_registry()
        self.definitions: dict[str, TreeDefinition] = {}
        self.main_tree_id: str | None = None
        self.declared_models: dict[str, str] = {}
        self.main_source: tuple[str, int] | None = None
        """File and line of the first <root>: where a wrong main tree is reported."""
        self._loaded_files: set[str] = set()

    def load_file(self, path: str | os.PathLike) -> None:
        resolved = str(Path(path).resolve())
        if resolved in self._loaded_files:
            return
        self._loaded_files.add(resolved)
        try:
            text = Path(resolved).read_bytes().decode("utf-8")
        except OSError as error:
            raise BTError(f"cannot read the tree file: {error.strerror}", file=str(path)) from None
        except UnicodeDecodeError:
            raise BTError("the tree file is not UTF-8 text", file=str(path)) from None
        self.load_string(text, file=str(path), base_dir=Path(resolved).parent)

    def load_string(
        self, xml: str, file: str = "<string>", base_dir: str | os.PathLike | None = None
    ) -> None:
        root = parse_xml(xml, file)
        if root.tag != "root":
            raise BTError(
                f"the top element must be <root>, not <{root.tag}>", file=file, line=root.line
            )
        if self.main_source is None:
            self.main_source = (file, root.line)
            self.main_tree_id = root.attributes.get("main_tree_to_execute")
        base = Path(base_dir) if base_dir is not None else Path.cwd()
        for element in root.children:
            if element.tag == "include":
                self._include(element, base)
            elif element.tag == "BehaviorTree":
                self._add_definition(element)
            elif element.tag == "TreeNodesModel":
                for model in element.children:
                    self.declared_models[model.attributes.get("ID", "")] = model.tag

    def _include(self, element: XmlElement, base: Path) -> None:
        relative = element.attributes.get("path", "")
        target = base / relative
        if not target.is_file():
            raise BTError(
                f"included file '{relative}' not found (looked in {base})",
                file=element.file,
                line=element.line,
            )
        self.load_file(target)

    def _add_definition(self, element: XmlElement) -> None:
        tree_id = element.attributes.get("ID")
        if not tree_id:
            raise BTError("<BehaviorTree> without an ID", file=element.file, line=element.line)
        if tree_id in self.definitions:
            other = self.definitions[tree_id]
            raise BTError(
                f"BehaviorTree '{tree_id}' is already defined in {other.file}:{other.element.line}",
                file=element.file,
                line=element.line,
                tree=tree_id,
            )
        self.definitions[tree_id] = TreeDefinition(tree_id, element)

    def _main_id(self, tree_id: str | None) -> str:
        chosen = tree_id or self.main_tree_id
        file, line = self.main_source or (None, None)
        if chosen is None:
            if len(self.definitions) == 1:
                return next(iter(self.definitions))
            raise BTError(
                f"{'several BehaviorTrees' if self.definitions else 'no BehaviorTree'} and "
                f"no main_tree_to_execute: choose one of {', '.join(self.definitions) or 'none'}",
                file=file,
                line=line,
            )
        if chosen not in self.definitions:
            raise BTError(
                f"no BehaviorTree with ID '{chosen}' (trees: {', '.join(self.definitions)})",
                file=file,
                line=line,
                tree=chosen,
                suggestion=closest(chosen, list(self.definitions)),
            )
        return chosen

    def create_tree(
        self,
        tree_id: str | None = None,
        *,
        rng: np.random.Generator | None = None,
        seed: int = 0,
        agent: Any = None,
        port_values: Mapping[str, Mapping[str, str]] | None = None,
    ) -> Tree:
        """Build the tree ``tree_id`` (default: the main tree); randomness comes from
        ``rng`` or else from a Generator seeded with ``seed``. ``port_values`` replace port
        attributes of the XML: {node name: {port: text}}."""
        main_id = self._main_id(tree_id)
        tree = Tree(
            main_id, self.registry, rng if rng is not None else np.random.default_rng(seed), agent
        )
        builder = TreeBuilder(
            self.registry, self.definitions, tree, collect=False, port_values=port_values or {}
        )
        builder.build_instance(main_id, Blackboard(), "", ())
        for instance in tree.subtrees:
            instance.blackboard.remember_initial_state()
        return tree

    def validate(self, tree_id: str | None = None) -> list[BTError]:
        """Every error in the main tree and in the trees it does not reach, unrun."""
        try:
            main_id = self._main_id(tree_id)
        except BTError as error:
            if tree_id is not None or self.main_tree_id is not None or not self.definitions:
                return [error]
            main_id = next(iter(self.definitions))  # a library of trees: check them all
        errors: list[BTError] = []
        reached: set[str] = set()
        for root_id in [main_id, *self.definitions]:
            if root_id in reached:
                continue
            tree = Tree(root_id, self.registry, np.random.default_rng(0))
            builder = TreeBuilder(self.registry, self.definitions, tree, collect=True)
            builder.build_instance(root_id, Blackboard(), "", ())
            reached.update(instance.tree_id for instance in tree.subtrees if instance)
            reached.add(root_id)
            errors.extend(builder.errors)
        return _once_per_place(errors)


def _once_per_place(errors: list[BTError]) -> list[BTError]:
    """One error per place in the XML: a mistake in a SubTree used several times is
    reported once (for its first instance), not once per instance."""
    seen = set()
    kept = []
    for error in errors:
        place = (error.file, error.line, error.port, error.problem)
        if place not in seen:
            seen.add(place)
            kept.append(error)
    return kept


def _factory_for(source: str | os.PathLike, registry: NodeRegistry | None) -> TreeFactory:
    factory = TreeFactory(registry)
    if isinstance(source, str) and source.lstrip().startswith("<"):
        factory.load_string(source)
    else:
        factory.load_file(source)
    return factory


def load_tree(
    source: str | os.PathLike,
    registry: NodeRegistry | None = None,
    *,
    tree_id: str | None = None,
    rng: np.random.Generator | None = None,
    seed: int = 0,
    agent: Any = None,
    port_values: Mapping[str, Mapping[str, str]] | None = None,
) -> Tree:
    """Build a tree from an XML file path or an XML string (``port_values``: see
    `TreeFactory.create_tree`)."""
    factory = _factory_for(source, registry)
    return factory.create_tree(tree_id, rng=rng, seed=seed, agent=agent, port_values=port_values)


def validate(
    source: str | os.PathLike, registry: NodeRegistry | None = None, tree_id: str | None = None
) -> list[BTError]:
    """All errors of a file or XML string, without running it (empty list: valid)."""
    try:
        factory = _factory_for(source, registry)
    except BTError as error:
        return [error]
    except OSError as error:
        return [BTError(f"cannot read: {error.strerror}", file=str(source))]
    return factory.validate(tree_id)
