"""Overrides: dotted scenario fields set from outside the file, the one way the command line
(`--set path=value[,value…]`, `--seed`, `--duration`), sweeps, searches and notebooks change
a scenario.

Paths are checked against the Scenario schema and values converted to the field's type, so
a typo is one clear line (InputError) before any run starts. Several values make a grid
axis; several `--set` options make the Cartesian product. `overridden` layers the values
over a loaded scenario through Drake's `yaml_load_typed`, the reader of scenario files, so a
value given here is read exactly like one in the file.
"""

import contextlib
import dataclasses
import itertools
import types
import typing

import numpy as np
import yaml
from pydrake.common.yaml import yaml_load_typed

from hrc_drake.yaml_check import NEW_ENTRIES, InputError, a_kind, did_you_mean, schema_fields

SCALARS = (bool, int, float, str)
Overrides = tuple[tuple[str, typing.Any], ...]
"""((dotted path, value), …) in the order given; hashable, so it names a grid point."""


def parse_sets(texts: list[str], schema) -> list[tuple[str, list]]:
    """`["a.b=1,2", "c=x"]` → `[("a.b", [1.0, 2.0]), ("c", ["x"])]`, typed by `schema`."""
    axes = []
    for text in texts:
        path, sep, values = text.partition("=")
        path = path.strip()
        if not sep or not path or not values.strip():
            raise InputError(f"--set {text}: expected PATH=VALUE[,VALUE...]")
        kind = field_type(schema, path)
        axes.append((path, [convert(path, kind, v.strip()) for v in values.split(",")]))
    return axes


def grid(axes: list[tuple[str, list]]) -> list[Overrides]:
    """Every combination of the axes' values (one empty grid point without axes)."""
    paths = [path for path, _ in axes]
    return [
        tuple(zip(paths, combo, strict=True)) for combo in itertools.product(*(v for _, v in axes))
    ]


def field_type(schema, path: str):
    """The type of the scalar field at dotted `path` (a mapping's entry is named by its
    key, e.g. `parameters.robot_speed`); InputError naming the bad part."""
    kind = field_kind(schema, path)
    if isinstance(kind, str):
        raise InputError(f"--set {kind}")
    return kind


def field_kind(schema, path: str):
    """The type of the scalar field at dotted `path`, or why `--set` cannot change it (a
    str that names the path)."""
    kind = _field_type(schema, path)
    return f"{path}: {kind}" if isinstance(kind, str) else kind


def _field_type(schema, path: str):
    """The scalar field's type, or what is wrong with `path` (a str)."""
    kind = schema
    for depth, name in enumerate(path.split(".")):
        if _mapping(kind):
            kind = typing.get_args(_options(kind)[0])[1]
            continue
        fields = schema_fields(_options(kind)[0])
        if fields is None:
            done = ".".join(path.split(".")[:depth])
            if _a_list(kind):
                return f"'{done}' is a list: {LIST_ITEMS} (change it in the scenario file)"
            return f"'{done}' has no fields"
        if name not in fields:
            return f"unknown field '{name}'{did_you_mean(name, fields)}"
        kind = fields[name]
    if scalar_of(kind) is None:
        listed = " (a list: change it in the scenario file)" if _a_list(kind) else ""
        return f"only number, boolean and text fields can be set{listed}"
    return kind


def convert(path: str, kind, text: str):
    """`text` as a value of the scalar (or optional scalar) type `kind`."""
    if text in ("null", "~") and _optional(kind):
        return None
    scalar = scalar_of(kind)
    value = yaml.safe_load(text) if scalar is not str else text
    if scalar is float and isinstance(value, str):
        with contextlib.suppress(ValueError):  # 1e3 is text to YAML 1.1, a number to people
            value = float(value)
    if scalar is float and isinstance(value, int) and not isinstance(value, bool):
        value = float(value)
    if not isinstance(value, scalar) or (scalar is int and isinstance(value, bool)):
        raise InputError(f"--set {path}: '{text}' is not {a_kind(scalar)}")
    return value


def overridden(scenario, overrides: Overrides):
    """A copy of the scenario with the dotted fields set (typed values, as `parse_sets` and
    `convert` give them), layered over it by `yaml_load_typed`: mapping entries not named
    keep their values, and `new_entries` mappings take new keys."""
    if not overrides:
        return scenario
    layer: dict = {}
    for path, value in overrides:
        names = path.split(".")
        _check_settable(scenario, names, path)
        node = layer
        for name in names[:-1]:
            node = node.setdefault(name, {})
        node[names[-1]] = value
    return yaml_load_typed(
        schema=type(scenario),
        data=yaml.safe_dump(layer),
        defaults=scenario,
        retain_map_defaults=True,
    )


def label(overrides: Overrides) -> str:
    """`a.b=1.6 c=x` (empty for the scenario as written)."""
    return " ".join(f"{path}={value}" for path, value in overrides)


def _check_settable(obj, names: list[str], path: str, new_entries: bool = False) -> None:
    """The entries and sections the path goes through exist in the scenario (a mapping
    marked `new_entries` may gain keys): a path the schema knows can still name an entry
    or an optional section this scenario does not have."""
    head, rest = names[0], names[1:]
    if isinstance(obj, dict):
        if head not in obj and not new_entries:
            done = path.split(".")[: -len(names)]
            raise InputError(
                f"--set {path}: '{'.'.join(done)}' has no entry '{head}'"
                f"{did_you_mean(head, obj)} (it has: {', '.join(obj) or 'none'})"
            )
        if rest:
            _check_settable(obj.get(head, {}), rest, path, new_entries)
        return
    if rest and getattr(obj, head) is None:
        raise InputError(f"--set {path}: the scenario has no '{head}' section to change")
    fields = dataclasses.fields(obj) if dataclasses.is_dataclass(obj) else ()  # Drake's structs
    opens = any(f.name == head and f.metadata.get(NEW_ENTRIES) for f in fields)
    if rest:
        _check_settable(getattr(obj, head), rest, path, opens)


def _mapping(kind) -> bool:
    return typing.get_origin(_options(kind)[0]) is dict


def _a_list(kind) -> bool:
    """Whether `kind` is a list or vector field (--set reaches no item of one)."""
    option = _options(kind)[0]
    return typing.get_origin(option) in (list, tuple) or option is np.ndarray


LIST_ITEMS = "--set reaches fields and mapping entries, not a list's items"


def scalar_of(kind):
    """bool, int, float or str for a (possibly optional) scalar field type, else None."""
    options = _options(kind)
    return options[0] if len(options) == 1 and options[0] in SCALARS else None


def _optional(kind) -> bool:
    return type(None) in typing.get_args(kind)


def _options(kind) -> list:
    if typing.get_origin(kind) in (typing.Union, types.UnionType):
        return [t for t in typing.get_args(kind) if t is not type(None)]
    return [kind]
