"""Checks a YAML document against a dataclass schema before `yaml_load_typed` reads it.

Drake's `yaml_load_typed` reports a bad value without saying where it is. Users need the
file, the line and the field, so we walk PyYAML's node tree (which keeps line numbers)
alongside the schema and report the first mismatch as one line.
"""

import dataclasses
import difflib
import re
import types
import typing
from pathlib import Path

import numpy as np
import yaml

REQUIRED = {"required": True}
"""Field metadata: the file must give this field."""
NEW_ENTRIES = "new_entries"
"""Field metadata: `--set` may add entries to this mapping (not only change them)."""


class InputError(Exception):
    """A user's file is wrong; the message is one self-contained line."""


def located_error(filename, node, field: str, message: str) -> InputError:
    line = f":{node.start_mark.line + 1}" if node is not None else ""
    return InputError(f"{filename}{line}: {field}: {message}")


def read_text(filename: Path, what: str = "file") -> str:
    """The file's text; a file that cannot be read or is not UTF-8 text is an InputError."""
    try:
        data = Path(filename).read_bytes()
    except OSError as e:
        raise InputError(f"{filename}: cannot read the {what}: {e.strerror}") from None
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as e:
        line = data[: e.start].count(b"\n") + 1
        raise InputError(
            f"{filename}:{line}: the {what} is not UTF-8 text (byte 0x{data[e.start]:02x})"
        ) from None


MAX_VALUES = 100_000
"""The most values a YAML document may hold once its aliases are expanded: a scenario holds
a few hundred; a "billion laughs" (aliases of aliases of lists) would make every reader of
it (ours and Drake's) run out of time and memory."""


def compose(filename: Path, text: str) -> yaml.Node | None:
    """The YAML node tree of `text`; syntax errors, aliases that expand beyond MAX_VALUES or
    into themselves, and keys given twice in one mapping (PyYAML and Drake would silently
    keep the last) become an InputError with the line."""
    try:
        root = yaml.compose(text, Loader=yaml.SafeLoader)
    except yaml.YAMLError as e:
        mark = getattr(e, "problem_mark", None)
        line = f":{mark.line + 1}" if mark else ""
        problem = getattr(e, "problem", None) or str(e)
        raise InputError(f"{filename}{line}: malformed YAML: {problem}") from None
    except RecursionError:
        raise InputError(f"{filename}: malformed YAML: nested too deeply") from None
    _ExpandedSize(filename).of(root, ())
    _check_unique_keys(filename, root, ())
    return root


class _ExpandedSize:
    """How many values each node stands for with its aliases expanded, counted once per
    node (PyYAML shares an anchored node among its aliases), so a document that would
    expand exponentially is refused at the node where it passes MAX_VALUES."""

    def __init__(self, filename):
        self.filename = filename
        self.sizes: dict[int, int] = {}

    def of(self, node, path: tuple) -> int:
        known = self.sizes.get(id(node))
        if known == 0:
            raise located_error(
                self.filename, node, field_path(path) or "<document>", "an alias refers to itself"
            )
        if known is not None:
            return known
        self.sizes[id(node)] = 0  # being counted
        total = 1 + sum(self.of(child, (*path, name)) for name, child in _children(node))
        if total > MAX_VALUES:
            raise located_error(
                self.filename,
                node,
                field_path(path) or "<document>",
                f"its aliases expand it to more than {MAX_VALUES} values (an alias bomb?): "
                "write the values out or use fewer aliases",
            )
        self.sizes[id(node)] = total
        return total


def _children(node) -> list[tuple]:
    """(name, node) of a node's values: items by index, mapping values by key (the keys count
    as values too)."""
    if isinstance(node, yaml.SequenceNode):
        return list(enumerate(node.value))
    if isinstance(node, yaml.MappingNode):
        return [(_key_name(key), n) for key, value in node.value for n in (key, value)]
    return []


def _key_name(key) -> str:
    return key.value if isinstance(key, yaml.ScalarNode) else str(key.value)


def _check_unique_keys(filename, node, path: tuple) -> None:
    if isinstance(node, yaml.SequenceNode):
        for i, item in enumerate(node.value):
            _check_unique_keys(filename, item, (*path, i))
    elif isinstance(node, yaml.MappingNode):
        first_line: dict[str, int] = {}
        for key, value in node.value:
            name = _key_name(key)
            if name in first_line:
                raise located_error(
                    filename,
                    key,
                    field_path((*path, name)),
                    f"given twice (first on line {first_line[name]})",
                )
            first_line[name] = key.start_mark.line + 1
            _check_unique_keys(filename, value, (*path, name))


def field_path(path: tuple) -> str:
    return ".".join(str(p) if not isinstance(p, int) else f"[{p}]" for p in path).replace(".[", "[")


def node_at(root: yaml.Node | None, path: tuple) -> yaml.Node | None:
    """The deepest node on `path` that exists (for pointing at a semantic error)."""
    node = root
    for key in path:
        child = _child(node, key)
        if child is None:
            return node
        node = child
    return node


def _child(node, key):
    if isinstance(node, yaml.MappingNode):
        return next((v for k, v in node.value if k.value == key), None)
    if isinstance(node, yaml.SequenceNode) and isinstance(key, int) and key < len(node.value):
        return node.value[key]
    return None


def schema_fields(schema) -> dict[str, typing.Any] | None:
    """Field name -> type for our dataclasses and Drake's bound schema classes."""
    if dataclasses.is_dataclass(schema):
        hints = typing.get_type_hints(schema)
        return {f.name: hints[f.name] for f in dataclasses.fields(schema)}
    if hasattr(schema, "__fields__"):
        return {f.name: f.type for f in schema.__fields__}
    return None


def check_node(filename, node, schema, path: tuple = ()) -> None:
    """Raises InputError at the first place where `node` does not fit `schema`."""
    origin = typing.get_origin(schema)
    if origin in (typing.Union, types.UnionType):
        _check_union(filename, node, schema, path)
    elif origin in (list, typing.List, typing.Sequence):  # noqa: UP006
        for i, item in enumerate(_expect(filename, node, yaml.SequenceNode, path, "a list")):
            check_node(filename, item, typing.get_args(schema)[0], (*path, i))
    elif origin in (dict, typing.Dict, typing.Mapping):  # noqa: UP006
        for key, value in _expect(filename, node, yaml.MappingNode, path, "a mapping"):
            check_node(filename, value, typing.get_args(schema)[1], (*path, key.value))
    elif schema is np.ndarray:
        _check_vector(filename, node, path, size=None)
    elif schema in (float, int, bool, str):
        _check_scalar(filename, node, schema, path)
    elif (fields := schema_fields(schema)) is not None:
        _check_mapping(filename, node, schema, fields, path)


def _check_union(filename, node, schema, path):
    options = [t for t in typing.get_args(schema) if t is not type(None)]
    if _is_null(node):
        return
    if len(options) == 1:
        check_node(filename, node, options[0], path)
    elif all(option in (float, int, bool, str) for option in options):
        _check_any_scalar(filename, node, options, path)
    else:
        _check_variant(filename, node, options, path)


_VECTOR_SIZE = re.compile(r"Vector\D*(\d+)\D*$")
"""Drake names its fixed-size vector variants e.g. `DeterministicVector𝓣3𝓤`."""


def _check_variant(filename, node, options, path):
    """Drake's tagged variants (`!Rpy {deg: [...]}`): the tag names the option; no tag is
    the first option. A vector option's siblings tell its size."""
    tagged = {_VECTOR_SIZE.sub("Vector", t.__name__): t for t in options}
    tag = node.tag if node.tag.startswith("!") and not node.tag.startswith("!!") else ""
    if tag and (tag[1:] not in tagged or tag[1:].startswith("_")):
        known = ", ".join(f"!{name}" for name in list(tagged)[1:] if not name.startswith("_"))
        raise located_error(filename, node, field_path(path), f"unknown tag '{tag}' ({known})")
    chosen = tagged[tag[1:]] if tag else options[0]
    sizes = {int(m.group(1)) for t in options if (m := _VECTOR_SIZE.search(t.__name__))}
    size = sizes.pop() if len(sizes) == 1 else None
    if chosen is np.ndarray:
        _check_vector(filename, node, path, size)
        return
    check_node(filename, node, chosen, path)
    fields = schema_fields(chosen) or {}
    for key, value in node.value if size is not None else ():  # e.g. !UniformVector min, max
        if fields[key.value] is np.ndarray:
            _check_vector(filename, value, (*path, key.value), size)


def _check_any_scalar(filename, node, options, path):
    for option in options:
        try:
            return _check_scalar(filename, node, option, path)
        except InputError as error:
            problem = error
    raise problem


def _check_vector(filename, node, path, size: int | None):
    items = _expect(filename, node, yaml.SequenceNode, path, "a list")
    if size is not None and len(items) != size:
        raise located_error(
            filename, node, field_path(path), f"needs {size} numbers, got {len(items)}"
        )
    for i, item in enumerate(items):
        _check_scalar(filename, item, float, (*path, i))


def _check_mapping(filename, node, schema, fields, path):
    items = _expect(filename, node, yaml.MappingNode, path, "a mapping")
    for key, value in items:
        if key.value not in fields:
            hint = did_you_mean(key.value, fields) or f" (known: {', '.join(sorted(fields))})"
            raise located_error(
                filename, key, field_path((*path, key.value)), f"unknown field{hint}"
            )
        check_node(filename, value, fields[key.value], (*path, key.value))
    present = {key.value for key, _ in items}
    for f in dataclasses.fields(schema) if dataclasses.is_dataclass(schema) else ():
        if f.metadata.get("required") and f.name not in present:
            raise located_error(
                filename, node, field_path((*path, f.name)), "required field is missing"
            )


def _expect(filename, node, node_type, path, what):
    if not isinstance(node, node_type):
        raise located_error(filename, node, field_path(path) or "<document>", f"expected {what}")
    return node.value


def _is_null(node) -> bool:
    return isinstance(node, yaml.ScalarNode) and node.tag.endswith(":null")


_BOOL_WORDS = {"true", "false", "yes", "no", "on", "off"}


def _check_scalar(filename, node, schema, path):
    name = field_path(path)
    if not isinstance(node, yaml.ScalarNode):
        raise located_error(filename, node, name, f"expected a single {schema.__name__} value")
    value = node.value
    if schema is str and not node.tag.endswith(":str"):
        raise located_error(filename, node, name, f"'{value}' is not text: put it in quotes")
    try:
        if schema is bool and value.lower() not in _BOOL_WORDS:
            raise ValueError
        if schema is int:
            int(value)
        if schema is float and value.lower().lstrip("+-") not in (".inf", ".nan"):
            float(value)  # YAML's .inf and .nan are floats: the value checks refuse them
    except ValueError:
        raise located_error(filename, node, name, f"'{value}' is not {a_kind(schema)}") from None


def a_kind(schema) -> str:
    """`a float`, `an int`: how messages name a scalar type."""
    return f"{'an' if schema.__name__[0] in 'aeiou' else 'a'} {schema.__name__}"


def first_line(error: Exception) -> str:
    """What Drake says, on one line: its first line, and what it was called with when
    that line only announces a list of signatures (pybind's "incompatible arguments")."""
    lines = [line.strip() for line in str(error).splitlines() if line.strip()] or [repr(error)]
    invoked = next((line for line in lines if line.startswith("Invoked with")), "")
    return f"{lines[0]} {invoked}" if lines[0].endswith(":") and invoked else lines[0]


def did_you_mean(name: str, known) -> str:
    """` (did you mean '<the closest known name>'?)`, or "" when none is close."""
    close = difflib.get_close_matches(name, list(known), n=1)
    return f" (did you mean '{close[0]}'?)" if close else ""


def unknown(what: str, name: str, known) -> str:
    """`unknown <what> '<name>' (did you mean ...?); known: ...`"""
    return f"unknown {what} '{name}'{did_you_mean(name, known)}; known: {', '.join(sorted(known))}"
