"""Checks a scenario's `cell:` model directives before Drake processes them.

Drake's `ProcessModelDirectives` answers a weld to an unknown model or a name used twice
with a long exception, a missing `add_directives` file likewise, and a directives file
that includes itself with a segmentation fault. We walk the directives (and the files
they include) first, tracking the model names each one adds, and report the first
problem as (field names, message) so the scenario loader can name the file and line.
"""

from collections.abc import Iterator
from pathlib import Path

from pydrake.common.yaml import yaml_load_typed
from pydrake.multibody.parsing import ModelDirective, ModelDirectives, PackageMap

from hrc_drake.yaml_check import (
    InputError,
    check_node,
    compose,
    field_path,
    located_error,
    node_at,
    read_text,
)

WORLD = "world"
SCOPE = "::"
Problem = tuple[tuple | None, str]


def directive_problems(
    directives: list[ModelDirective],
    package_map: PackageMap,
    reserved=(),
    directory: Path | None = None,
) -> Iterator[Problem]:
    """Problems of `directives` (field names relative to the list); model names in
    `reserved` are taken already (the station's own models); `directory`: the scenario's,
    where a file named by a plain path is looked for to say how to name it."""
    yield from _Walk(package_map, set(reserved), directory).directives(directives, "", ())


URL_FORMS = "package://hrc_drake_models/cell/NAME.sdf or file:///ABSOLUTE/PATH"
"""How Drake's model directives name a file: a URL, never a path relative to the scenario."""


class _Walk:
    def __init__(self, package_map: PackageMap, models: set[str], directory: Path | None):
        self.package_map = package_map
        self.models = models
        self.directory = directory

    def directives(self, directives, namespace: str, including: tuple) -> Iterator[Problem]:
        for i, directive in enumerate(directives):
            for names, message in self.directive(directive, namespace, including):
                yield (None if names is None else (i, *names)), message

    def directive(self, d: ModelDirective, namespace: str, including: tuple) -> Iterator[Problem]:
        if d.add_model is not None:
            yield from self._file(("add_model", "file"), d.add_model.file, "model file")
            yield from self._new_model(("add_model", "name"), d.add_model.name, namespace)
        if d.add_model_instance is not None:
            yield from self._new_model(
                ("add_model_instance", "name"), d.add_model_instance.name, namespace
            )
        if d.add_frame is not None:
            yield from self._scoped(("add_frame", "name"), d.add_frame.name, namespace)
            base = d.add_frame.X_PF.base_frame
            if base is not None:
                yield from self._frame(("add_frame", "X_PF", "base_frame"), base, namespace)
        if d.add_weld is not None:
            yield from self._frame(("add_weld", "parent"), d.add_weld.parent, namespace)
            yield from self._frame(("add_weld", "child"), d.add_weld.child, namespace)
        if d.add_directives is not None:
            yield from self._include(d.add_directives, namespace, including)

    def _file(self, names: tuple, url: str, what: str) -> Iterator[Problem]:
        if self.resolve(url) is None:
            yield names, f"{what} '{url}' not found{self._how_to_name(url)}"

    def _how_to_name(self, url: str) -> str:
        """For a plain path (no URL scheme), how to name a file instead, and the URL of the
        file it names beside the scenario when there is one ("" for a URL)."""
        if "://" in url:
            return ""
        hint = f": a model file is a URL, {URL_FORMS}"
        beside = (self.directory / url).resolve() if self.directory is not None else None
        if beside is not None and beside.is_file():
            hint += f"; {beside.as_uri()} exists"
        return hint

    def resolve(self, url: str) -> Path | None:
        try:
            path = Path(self.package_map.ResolveUrl(url))
        except Exception:  # Drake raises for an unknown package or a malformed URL
            return None
        return path if path.is_file() else None

    def _new_model(self, names: tuple, name: str, namespace: str) -> Iterator[Problem]:
        if not name:
            yield names, "a model needs a name"
            return
        full = _scoped_name(namespace, name)
        if full in self.models:
            yield names, f"model name '{full}' is used twice (names must be unique)"
        self.models.add(full)

    def _scoped(self, names: tuple, scoped: str, namespace: str) -> Iterator[Problem]:
        model, sep, frame = scoped.rpartition(SCOPE)
        if not sep or not model or not frame:
            yield names, f"'{scoped}' is not a scoped frame name like 'model::frame'"
        elif _scoped_name(namespace, model) not in self.models:
            yield names, self._unknown_model(_scoped_name(namespace, model))

    def _frame(self, names: tuple, frame: str, namespace: str) -> Iterator[Problem]:
        if frame != WORLD:
            yield from self._scoped(names, frame, namespace)

    def _unknown_model(self, model: str) -> str:
        known = ", ".join(sorted(self.models)) or "none"
        return f"unknown model '{model}' (models added before this directive: {known})"

    def _include(self, add_directives, namespace: str, including: tuple) -> Iterator[Problem]:
        names = ("add_directives", "file")
        path = self.resolve(add_directives.file)
        if path is None:
            yield names, f"directives file '{add_directives.file}' not found"
            return
        if path.resolve() in including:
            chain = " -> ".join(p.name for p in (*including, path.resolve()))
            yield names, f"directives files include each other in a loop: {chain}"
            return
        try:
            root, included = _read_directives(path)
        except InputError as error:
            yield None, str(error)
            return
        inner = _scoped_name(namespace, add_directives.model_namespace or "")
        if add_directives.model_namespace:
            self.models.add(inner)
        for names, message in self.directives(included, inner, (*including, path.resolve())):
            if names is not None:  # located in the included file
                names = ("directives", *names)
                message = str(located_error(path, node_at(root, names), field_path(names), message))
            yield None, message


def _read_directives(path: Path) -> tuple:
    """The YAML root of a directives file and its directives."""
    text = read_text(path, "directives file")
    root = compose(path, text)
    if root is None:
        raise InputError(f"{path}: the file is empty")
    check_node(path, root, ModelDirectives)
    try:
        return root, yaml_load_typed(schema=ModelDirectives, data=text).directives
    except Exception as e:  # Drake's reader: check_node catches the common cases first
        raise located_error(path, root, "directives", str(e).splitlines()[0]) from None


def _scoped_name(namespace: str, name: str) -> str:
    return f"{namespace}{SCOPE}{name}" if namespace and name else namespace or name
