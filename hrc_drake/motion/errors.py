"""Why a move cannot be planned."""


class PlanningFailed(Exception):
    """A move cannot be planned; the message is the reason reported in the status."""
