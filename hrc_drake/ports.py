"""Abstract ports that carry our messages, and optional inputs.

Each actor runs with or without its neighbours: an input that nothing drives means "that
part is not in this diagram".
"""

from pydrake.common.value import AbstractValue


def message_value() -> AbstractValue:
    """The model value of a port that carries any Python message (a frozen dataclass, a
    tuple, a command or None at run time).

    Every Python object travels as Drake's `Value[object]`, so one model serves all message
    types. It holds a plain `object()`: `AbstractValue.Make(None)` stopped constructing in
    newer Drake releases (`Value[object](None)` raises there), and this form works on all of
    them.
    """
    return AbstractValue.Make(object())


def value_or_none(port, context):
    """The input's value, or None while nothing is connected to it (or fixed on it)."""
    return port.Eval(context) if port.HasValue(context) else None
