"""Port declarations, the values a port accepts, the string-to-type conversions used for
XML literals, and how a port's text names a blackboard entry (``{key}``, ``{=}``).

Applications register their own port types (poses, areas, ...) with :func:`register_type`;
conversions are global, as in BehaviorTree.CPP where they are template specialisations.
"""

from __future__ import annotations

import enum
import re
import typing
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from .errors import closest
from .status import Status


class PortDirection(enum.Enum):
    INPUT = "input_port"
    OUTPUT = "output_port"
    INOUT = "inout_port"


_NO_DEFAULT = object()


@dataclass(frozen=True)
class Range:
    """The numbers an input port accepts (each item of a list port): at least `low` (above it
    with `above`), at most `high`; None leaves a side open. Checked on literals when a tree
    is built, on known blackboard values when a scenario is validated, and on every read."""

    low: float | None = None
    high: float | None = None
    above: bool = False
    why: str = ""
    """Said after a value it refuses, where the numbers are a convention to recall."""

    def problem(self, value: Any) -> str:
        items = value if isinstance(value, list) else [value]
        if all(self._holds(item) for item in items):
            return ""
        got = f"must be {self}, got {value_to_text(value)}"
        if self.why:
            return f"{got} ({self.why})"
        if (self.low, self.high) == (0, 1) and not isinstance(value, list) and 5 <= value <= 100:
            return f"{got} (a percentage? {value_to_text(value / 100)} is the fraction)"
        return got

    def _holds(self, item) -> bool:
        low = self.low is None or (item > self.low if self.above else item >= self.low)
        return low and (self.high is None or item <= self.high)

    def __str__(self) -> str:
        if self.low is not None and self.high is not None:
            return f"within {value_to_text(self.low)}..{value_to_text(self.high)}"
        if self.high is not None:
            return f"at most {value_to_text(self.high)}"
        return f"{'above' if self.above else 'at least'} {value_to_text(self.low)}"


@dataclass(frozen=True)
class OneOf:
    """The words a text input port accepts."""

    words: tuple[str, ...]

    def problem(self, value: Any) -> str:
        if value in self.words:
            return ""
        close = closest(str(value), self.words)
        hint = f" (did you mean '{close}'?)" if close else ""
        return f"unknown value '{value}'{hint}; known: {', '.join(self.words)}"

    def __str__(self) -> str:
        return f"one of {', '.join(self.words)}"


Accepts = Range | OneOf


@dataclass(frozen=True)
class PortInfo:
    """One port of a node type: its direction, value type (None = any), default, help, and
    the values it accepts (None: any its type reads)."""

    name: str
    direction: PortDirection
    type: Any = None
    default: Any = _NO_DEFAULT
    description: str = ""
    accepts: Accepts | None = None

    @property
    def has_default(self) -> bool:
        return self.default is not _NO_DEFAULT

    @property
    def required(self) -> bool:
        """Inputs without a default must be given in the XML; outputs are optional."""
        return self.direction is not PortDirection.OUTPUT and not self.has_default

    @property
    def is_input(self) -> bool:
        return self.direction is not PortDirection.OUTPUT


def InputPort(  # noqa: N802
    name: str,
    type: Any = None,
    default: Any = _NO_DEFAULT,
    description: str = "",
    accepts: Accepts | None = None,
):
    return PortInfo(name, PortDirection.INPUT, type, default, description, accepts)


def OutputPort(name: str, type: Any = None, description: str = ""):  # noqa: N802
    return PortInfo(name, PortDirection.OUTPUT, type, _NO_DEFAULT, description)


def BidirectionalPort(  # noqa: N802
    name: str,
    type: Any = None,
    default: Any = _NO_DEFAULT,
    description: str = "",
    accepts: Accepts | None = None,
):
    return PortInfo(name, PortDirection.INOUT, type, default, description, accepts)


@dataclass(frozen=True)
class _TypeConversion:
    from_string: Callable[[str], Any]
    name: str


_CONVERSIONS: dict[Any, _TypeConversion] = {}


def register_type(py_type: Any, from_string: Callable[[str], Any], name: str | None = None):
    """Teach the engine to read ``py_type`` from an XML literal or a string entry.

    ``from_string`` raises ValueError for text it cannot read; ``name`` is the type name
    shown in the TreeNodesModel (default: the class name).
    """
    _CONVERSIONS[py_type] = _TypeConversion(from_string, name or getattr(py_type, "__name__", ""))


def _parse_bool(text: str) -> bool:
    lowered = text.strip().lower()
    if lowered in ("true", "1"):
        return True
    if lowered in ("false", "0"):
        return False
    raise ValueError(f"'{text}' is not a bool (true/false)")


def _parse_enum(enum_type: type[enum.Enum], text: str) -> enum.Enum:
    key = text.strip()
    if key in enum_type.__members__:
        return enum_type[key]
    try:
        return enum_type(int(key))
    except ValueError:
        names = ", ".join(enum_type.__members__)
        raise ValueError(f"'{text}' is not one of {names}") from None


register_type(str, str, "std::string")
register_type(int, int, "int")
register_type(float, float, "double")
register_type(bool, _parse_bool, "bool")


def _runtime_class(py_type: Any) -> Any:
    return typing.get_origin(py_type) or py_type


def _is_enum(py_type: Any) -> bool:
    return isinstance(py_type, type) and issubclass(py_type, enum.Enum)


def convert_from_string(text: str, py_type: Any) -> Any:
    """Read ``text`` as ``py_type``; raises ValueError saying why it cannot."""
    if py_type is None:
        return text
    conversion = _CONVERSIONS.get(py_type)
    if conversion is not None:
        try:
            return conversion.from_string(text)
        except (ValueError, TypeError) as error:
            raise ValueError(f"cannot convert '{text}' to {type_name(py_type)}: {error}") from None
    if _is_enum(py_type):
        return _parse_enum(py_type, text)
    if _runtime_class(py_type) is list:
        (item_type,) = typing.get_args(py_type) or (str,)
        return [convert_from_string(part, item_type) for part in text.split(";") if part != ""]
    raise ValueError(f"no conversion from string registered for type {type_name(py_type)}")


def coerce(value: Any, py_type: Any) -> Any:
    """Make ``value`` fit an entry of ``py_type``, converting strings and numbers."""
    if py_type is None:
        return value
    cls = _runtime_class(py_type)
    if isinstance(value, cls) and not (cls is int and isinstance(value, bool)):
        return value
    if isinstance(value, str):
        return convert_from_string(value, py_type)
    if cls is float and isinstance(value, int):
        return float(value)
    if cls is int and isinstance(value, float) and value.is_integer():
        return int(value)
    if cls is bool and isinstance(value, int | float) and value in (0, 1):
        return bool(value)
    if cls is str and isinstance(value, int | float | enum.Enum):
        return value_to_text(value)
    raise ValueError(f"a {type(value).__name__} value {value!r} is not a {type_name(py_type)}")


SAME_NAME = "{=}"
"""BehaviorTree.CPP's shorthand for the entry named like the port (``x="{=}"`` is
``x="{x}"``), on a node's port and on a SubTree's; a node's port also takes a bare ``=``
(BT.CPP's TreeNode::getRemappedKey and the SubTree branch of its XML parser)."""


def blackboard_key(text: str) -> str | None:
    """``key`` for ``{key}`` (``@key`` for ``{@key}``), None for a literal."""
    text = text.strip()
    if len(text) >= 3 and text[0] == "{" and text[-1] == "}":
        return text[1:-1].strip()
    return None


def port_key(port: str, text: str) -> str | None:
    """The blackboard key a node's port ``port`` given ``text`` reads or writes, None for a
    literal: ``{key}``, or the port's own name for ``{=}`` and ``=``."""
    if text.strip() in (SAME_NAME, "="):
        return port
    return blackboard_key(text)


def subtree_key(port: str, text: str) -> str | None:
    """The parent's key a SubTree port given ``text`` is remapped to (None: a literal):
    ``{key}``, or the port's own name for ``{=}`` (a bare ``=`` stays a literal there, as in
    BT.CPP)."""
    return port if text.strip() == SAME_NAME else blackboard_key(text)


_INTEGER = re.compile(r"-?\d+")
_REAL = re.compile(r"-?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")


def literal_value(text: str) -> int | float | str:
    """A number if the whole text is one, else the text: how BehaviorTree.CPP (4.9.1 on)
    stores a SubTree's literal port, so that scripts can compute with it."""
    if _INTEGER.fullmatch(text):
        return int(text)
    if _REAL.fullmatch(text):
        return float(text)
    return text


def value_to_text(value: Any) -> str:
    """Text of a value as BehaviorTree.CPP would write it (true/false, enum names)."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, enum.Enum):
        return value.name
    if isinstance(value, float) and value.is_integer():
        return str(int(value))
    if isinstance(value, list):
        return ";".join(value_to_text(item) for item in value)
    return str(value)


def type_name(py_type: Any) -> str:
    """Name of a port type as shown to Groot2 users."""
    if py_type is None:
        return ""
    conversion = _CONVERSIONS.get(py_type)
    if conversion is not None:
        return conversion.name
    if _runtime_class(py_type) is list:
        args = typing.get_args(py_type)
        return f"std::vector<{type_name(args[0]) if args else 'std::string'}>"
    return getattr(py_type, "__name__", str(py_type))


register_type(Status, lambda text: _parse_enum(Status, text), "BT::NodeStatus")
