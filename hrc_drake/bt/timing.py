"""Simulated-time helper shared by Delay, Timeout and Sleep."""

TIME_TOLERANCE = 1e-9  # seconds; absorbs float rounding of tick times such as 0.1 + 0.2


def has_elapsed(start: float, now: float, msec: float) -> bool:
    """True once ``msec`` milliseconds of simulation time have passed since ``start``."""
    return now - start >= msec / 1000.0 - TIME_TOLERANCE
