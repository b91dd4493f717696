"""Vocabulary shared by every actor's command and status messages.

Commands flow down and carry a sequence number; every actor's status reports the last
sequence number it accepted and that command's outcome, so an asynchronous behavior tree
node knows when *its* command finished (README: "How a scenario becomes a Diagram").
"""

from dataclasses import dataclass

RUNNING = "running"
SUCCEEDED = "succeeded"
FAILED = "failed"
REJECTED = "rejected"
CANCELLED = "cancelled"

OUTCOMES = (RUNNING, SUCCEEDED, FAILED, REJECTED, CANCELLED)
FINISHED = (SUCCEEDED, FAILED, REJECTED, CANCELLED)
RESULTS_KEPT = 16
"""Recent command results an actor reports, so a node still finds its own after others."""


@dataclass(frozen=True)
class CommandResult:
    """The outcome of one command, by sequence number."""

    seq: int
    outcome: str
    reason: str = ""

    def __post_init__(self):
        if self.outcome not in OUTCOMES:
            raise ValueError(f"unknown outcome '{self.outcome}'")


def recorded(results: tuple, result) -> tuple:
    """`results` with `result` as the newest, replacing an earlier one of the same seq."""
    kept = tuple(r for r in results if r.seq != result.seq)
    return (*kept, result)[-RESULTS_KEPT:]


def result_of(results: tuple, seq: int):
    """The result of command `seq` among `results` (newest first), or None."""
    return next((r for r in reversed(results) if r.seq == seq), None)


NO_COMMANDS = ()
"""What a command port carries before its first command (ports cannot carry None)."""


def newer_commands(value, seen: int, cancels: tuple[type, ...] = ()) -> list:
    """The commands on a command port that are newer than sequence number `seen`, cancels
    first.

    A port carries one command or a tuple of recent commands oldest first (a behavior tree
    may send two commands to one actor in one tick; NO_COMMANDS before the first); every
    command has `seq`. An input that nothing drives reads as None.
    Commands of the `cancels` types are handled before the others: when a reactive node
    interrupts a running action, the new action is sent before the halted one's cancel,
    and the actor must be free before it can take the new one.
    """
    if value is None:
        return []
    commands = value if isinstance(value, tuple) else (value,)
    newer = [command for command in commands if command.seq > seen]
    return sorted(newer, key=lambda command: not isinstance(command, cancels))


@dataclass(frozen=True)
class TaskEvent:
    """Something a tree reports as done (its Emit node): `name` is e.g. part_finished,
    part_rejected, helped; reports count them per hour."""

    time: float
    name: str
    agent: str = ""
    value: str = ""
