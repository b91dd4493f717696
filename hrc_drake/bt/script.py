"""BehaviorTree.CPP's script language: a tokenizer, a precedence-climbing parser and
closures that evaluate against a blackboard.

Supported: ``:=`` (create), ``=``, ``+= -= *= /=``, ``+ - * /``, ``..`` (concatenation),
``== != < > <= >=`` (chainable), ``&& || !``, ``& | ^ ~``, ``cond ? a : b``, numbers,
'single' or "double" quoted strings, true/false, blackboard keys (``@key`` for the root)
and enum names, several statements separated by ``;``. A script's value is its last
statement's value.
"""

from __future__ import annotations

import functools
import operator
import re
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from .blackboard import UNSET, Blackboard
from .errors import BTError
from .ports import register_type, value_to_text

EPSILON = 1.1920929e-07  # float epsilon, BehaviorTree.CPP's tolerance for "=="


@dataclass
class ScriptEnv:
    """What a script sees: the node's blackboard and the registry's enum names."""

    blackboard: Blackboard
    enums: dict[str, int]


Evaluator = Callable[[ScriptEnv], Any]

_TOKEN = re.compile(
    r"""\s*(?:
    (?P<number>0[xX][0-9a-fA-F]+|(?:\d+\.\d*|\.\d+|\d+)(?:[eE][+-]?\d+)?)
  | (?P<string>'[^']*'|"[^"]*")
  | (?P<name>@?[A-Za-z_][A-Za-z0-9_]*)
  | (?P<op>:=|\+=|-=|\*=|/=|==|!=|<=|>=|&&|\|\||\.\.|[-+*/<>=!~&|^?:();])
    )""",
    re.VERBOSE,
)


ASSIGNMENTS = (":=", "=", "+=", "-=", "*=", "/=")


@dataclass(frozen=True)
class Token:
    kind: str
    text: str
    position: int


def tokenize(code: str) -> list[Token]:
    tokens, position = [], 0
    while True:
        while position < len(code) and code[position].isspace():
            position += 1
        if position >= len(code):
            return [*tokens, Token("end", "", position)]
        match = _TOKEN.match(code, position)
        if match is None or match.end() == position:
            raise BTError(
                f"script syntax error at column {position + 1}: unexpected "
                f"'{code[position]}' in '{code}'"
            )
        kind = match.lastgroup
        tokens.append(Token(kind, match.group(kind), match.start(kind)))
        position = match.end()


def _is_number(value: Any) -> bool:
    return isinstance(value, int | float)  # bools and IntEnums included


def _to_number(value: Any, env: ScriptEnv) -> float:
    """Numbers as they are; strings that name a number, a bool or an enum, converted."""
    if _is_number(value):
        return value
    if isinstance(value, str):
        if value in ("true", "false"):
            return value == "true"
        if value in env.enums:
            return env.enums[value]
        try:
            return float(value)
        except ValueError:
            pass
    raise BTError(f"script: cannot use {value!r} as a number")


def _truthy(value: Any) -> bool:
    if isinstance(value, str):
        return value != ""
    return bool(value)


def _arithmetic(symbol: str) -> Callable[[Any, Any, ScriptEnv], Any]:
    numeric = {"+": operator.add, "-": operator.sub, "*": operator.mul, "/": operator.truediv}[
        symbol
    ]

    def apply(left: Any, right: Any, env: ScriptEnv) -> Any:
        if _is_number(left) and _is_number(right):
            try:
                return numeric(left, right)
            except ZeroDivisionError:
                raise BTError("script: division by zero") from None
        if symbol == "+" and isinstance(left, str) and isinstance(right, str):
            return left + right
        raise BTError(f"script: operator '{symbol}' not permitted on {left!r} and {right!r}")

    return apply


def _concat(left: Any, right: Any, env: ScriptEnv) -> str:
    return value_to_text(left) + value_to_text(right)


def _bitwise(function: Callable[[int, int], int]) -> Callable[[Any, Any, ScriptEnv], int]:
    def apply(left: Any, right: Any, env: ScriptEnv) -> int:
        left_number, right_number = _to_number(left, env), _to_number(right, env)
        if int(left_number) != left_number or int(right_number) != right_number:
            raise BTError("script: bitwise operators need integers")
        return function(int(left_number), int(right_number))

    return apply


def _logic(function: Callable[[bool, bool], bool]) -> Callable[[Any, Any, ScriptEnv], bool]:
    return lambda left, right, env: function(_truthy(left), _truthy(right))


_BINARY = {
    "+": _arithmetic("+"),
    "-": _arithmetic("-"),
    "*": _arithmetic("*"),
    "/": _arithmetic("/"),
    "..": _concat,
    "&": _bitwise(operator.and_),
    "|": _bitwise(operator.or_),
    "^": _bitwise(operator.xor),
    "&&": _logic(lambda a, b: a and b),
    "||": _logic(lambda a, b: a or b),
}

_COMPARISONS: dict[str, Callable[[Any, Any], bool]] = {
    "==": lambda a, b: a == b,
    "!=": lambda a, b: a != b,
    "<": operator.lt,
    ">": operator.gt,
    "<=": operator.le,
    ">=": operator.ge,
}

# Binary operators from the loosest to the tightest binding, each level left-associative,
# as BehaviorTree.CPP 4.9's Pratt parser (4.8's grammar got `a - b + c` and the logical
# operators wrong; see docs/bt-conformance.md). Comparisons bind looser than bitwise ones.
_PRECEDENCE = [
    ("||",),
    ("&&",),
    ("==", "!=", "<", ">", "<=", ">="),
    ("|", "^"),
    ("&",),
    ("+", "-", ".."),
    ("*", "/"),
]
_COMPARISON_LEVEL = 2


def _compare(left: Any, right: Any, symbol: str, env: ScriptEnv) -> bool:
    """Compare like BehaviorTree.CPP: numbers with a tolerance, strings as text, and a
    string against a number by reading the string as a number (or enum)."""
    if isinstance(left, str) and isinstance(right, str):
        return _COMPARISONS[symbol](left, right)
    left_number, right_number = _to_number(left, env), _to_number(right, env)
    if symbol in ("==", "!="):
        same = abs(left_number - right_number) <= EPSILON
        return same if symbol == "==" else not same
    return _COMPARISONS[symbol](left_number, right_number)


class _Parser:
    def __init__(self, code: str):
        self.code = code
        self.tokens = tokenize(code)
        self.index = 0

    @property
    def current(self) -> Token:
        return self.tokens[self.index]

    def error(self, what: str) -> BTError:
        token = self.current
        found = f"'{token.text}'" if token.kind != "end" else "end of script"
        return BTError(
            f"script syntax error at column {token.position + 1}: {what}, "
            f"found {found} in '{self.code}'"
        )

    def accept(self, *texts: str) -> str | None:
        token = self.current
        if token.kind in ("op", "name") and token.text in texts:
            self.index += 1
            return token.text
        return None

    def expect(self, text: str) -> None:
        if self.accept(text) is None:
            raise self.error(f"expected '{text}'")

    def statements(self) -> list[Evaluator]:
        result = []
        while self.current.kind != "end":
            if self.accept(";"):
                continue
            result.append(self.statement())
            if self.current.kind != "end":
                self.expect(";")
        if not result:
            raise self.error("expected a statement")
        return result

    def statement(self) -> Evaluator:
        token, following = self.current, self.tokens[self.index + 1]
        if token.kind == "name" and following.text in ASSIGNMENTS:
            self.index += 2
            return _assignment(token.text, following.text, self.expression())
        return self.expression()

    def expression(self) -> Evaluator:
        condition = self.binary(0)
        if not self.accept("?"):
            return condition
        when_true = self.expression()
        self.expect(":")
        when_false = self.expression()
        return lambda env: when_true(env) if _truthy(condition(env)) else when_false(env)

    def binary(self, level: int) -> Evaluator:
        if level == len(_PRECEDENCE):
            return self.unary()
        if level == _COMPARISON_LEVEL:
            return self.comparison()
        left = self.binary(level + 1)
        while symbol := self.accept(*_PRECEDENCE[level]):
            left = _binary(_BINARY[symbol], left, self.binary(level + 1))
        return left

    def comparison(self) -> Evaluator:
        operands = [self.binary(_COMPARISON_LEVEL + 1)]
        symbols = []
        while symbol := self.accept(*_PRECEDENCE[_COMPARISON_LEVEL]):
            symbols.append(symbol)
            operands.append(self.binary(_COMPARISON_LEVEL + 1))
        return operands[0] if not symbols else _comparison_chain(operands, symbols)

    def unary(self) -> Evaluator:
        symbol = self.accept("!", "-", "~")
        if symbol is None:
            return self.primary()
        operand = self.unary()
        if symbol == "!":
            return lambda env: not _truthy(operand(env))
        if symbol == "-":
            return lambda env: -_to_number(operand(env), env)
        return lambda env: ~int(_to_number(operand(env), env))

    def primary(self) -> Evaluator:
        token = self.current
        if self.accept("("):
            inner = self.expression()
            self.expect(")")
            return inner
        if token.kind == "number":
            self.index += 1
            return _constant(_number_literal(token.text))
        if token.kind == "string":
            self.index += 1
            return _constant(token.text[1:-1])
        if token.kind == "name" and token.text in ("true", "false"):
            self.index += 1
            return _constant(token.text == "true")
        if token.kind == "name":
            self.index += 1
            return _variable(token.text)
        raise self.error("expected a value")


def _number_literal(text: str) -> int | float:
    if text.lower().startswith("0x"):
        return int(text, 16)
    return float(text) if any(c in text for c in ".eE") else int(text)


def _constant(value: Any) -> Evaluator:
    return lambda env: value


def _variable(name: str) -> Evaluator:
    def read(env: ScriptEnv) -> Any:
        if name in env.enums:
            return env.enums[name]
        entry = env.blackboard.entry(name)
        if entry is None or entry.value is UNSET:
            raise BTError(f"script: variable '{name}' is not set")
        return entry.value

    return read


def _binary(apply: Callable, left: Evaluator, right: Evaluator) -> Evaluator:
    return lambda env: apply(left(env), right(env), env)


def _comparison_chain(operands: list[Evaluator], symbols: list[str]) -> Evaluator:
    def evaluate(env: ScriptEnv) -> bool:
        left = operands[0](env)
        for symbol, operand in zip(symbols, operands[1:], strict=True):
            right = operand(env)
            if not _compare(left, right, symbol, env):
                return False
            left = right
        return True

    return evaluate


def _assignment(key: str, symbol: str, value: Evaluator) -> Evaluator:
    update = _BINARY[symbol[0]] if symbol not in (":=", "=") else None

    def assign(env: ScriptEnv) -> Any:
        entry = env.blackboard.entry(key, create=symbol == ":=")
        if entry is None:
            raise BTError(f"script: blackboard entry '{key}' does not exist; use ':=' to create it")
        new_value = value(env)
        if update is not None:
            if entry.value is UNSET:
                raise BTError(f"script: '{key}' is not set, cannot apply '{symbol}'")
            new_value = update(entry.value, new_value, env)
        entry.assign(new_value)
        return entry.value

    return assign


class ScriptCode(str):
    """Port type of script ports: the factory checks their syntax when it loads a tree."""


register_type(ScriptCode, ScriptCode, "std::string")


class Script:
    """A parsed script; calling it runs every statement and returns the last value."""

    __slots__ = ("code", "_statements")

    def __init__(self, code: str):
        self.code = code
        self._statements = _Parser(code).statements()

    def __call__(self, env: ScriptEnv) -> Any:
        result = None
        for statement in self._statements:
            result = statement(env)
        return result

    def is_true(self, env: ScriptEnv) -> bool:
        return _truthy(self(env))


@functools.lru_cache(maxsize=1024)
def compile_script(code: str) -> Script:
    """Parse ``code`` once; scripts are immutable, so trees may share them."""
    return Script(code)
