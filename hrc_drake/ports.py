"""Optional input ports: each actor runs with or without its neighbours, and an input that
nothing drives means "that part is not in this diagram"."""


def value_or_none(port, context):
    """The input's value, or None while nothing is connected to it (or fixed on it)."""
    return port.Eval(context) if port.HasValue(context) else None
