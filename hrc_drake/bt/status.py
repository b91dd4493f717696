"""Node statuses, numbered as in BehaviorTree.CPP so that .btlog files stay compatible."""

from enum import IntEnum


class Status(IntEnum):
    """What a node reports after a tick; IDLE means "not started or reset"."""

    IDLE = 0
    RUNNING = 1
    SUCCESS = 2
    FAILURE = 3
    SKIPPED = 4

    @property
    def is_completed(self) -> bool:
        return self is Status.SUCCESS or self is Status.FAILURE


IDLE = Status.IDLE
RUNNING = Status.RUNNING
SUCCESS = Status.SUCCESS
FAILURE = Status.FAILURE
SKIPPED = Status.SKIPPED
COMPLETED = frozenset((SUCCESS, FAILURE))
