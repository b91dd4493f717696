"""Vocabulary shared by every actor's command and status messages.

Commands flow down and carry a sequence number; every actor's status reports the results
of its recent commands by number (a ResultLog), so an asynchronous behavior tree node knows
when *its* command finished (docs/architecture.md).
"""

from dataclasses import dataclass

RUNNING = "running"
SUCCEEDED = "succeeded"
FAILED = "failed"
REJECTED = "rejected"
CANCELLED = "cancelled"

OUTCOMES = (RUNNING, SUCCEEDED, FAILED, REJECTED, CANCELLED)
FINISHED = (SUCCEEDED, FAILED, REJECTED, CANCELLED)
RECENT_COMMANDS = 16
"""One window for both ends: the commands a tree's command port carries (far more than one
tick sends to one actor) and the results an actor reports, so a node finds the result of
every command that is still on the port."""


@dataclass(frozen=True)
class CommandResult:
    """The outcome of one command, by sequence number; `object_id` names the object it
    concerned where there is one (for the workpieces' Spawn: the new object)."""

    seq: int
    outcome: str
    reason: str = ""
    object_id: int | None = None

    def __post_init__(self):
        if self.outcome not in OUTCOMES:
            raise ValueError(f"unknown outcome '{self.outcome}'")


@dataclass(frozen=True)
class ResultLog:
    """An actor's results of its recent commands, newest last: a node looks up its own
    command by number even after later commands (of its own or of another node)."""

    results: tuple[CommandResult, ...] = ()

    def recorded(self, result: CommandResult) -> "ResultLog":
        """This log with `result` as the newest, replacing an earlier one of the same seq."""
        kept = tuple(r for r in self.results if r.seq != result.seq)
        return ResultLog((*kept, result)[-RECENT_COMMANDS:])

    def result_of(self, seq: int) -> CommandResult | None:
        return next((r for r in reversed(self.results) if r.seq == seq), None)

    def outcome_of(self, seq: int) -> str | None:
        result = self.result_of(seq)
        return result.outcome if result is not None else None

    @property
    def last(self) -> CommandResult | None:
        return self.results[-1] if self.results else None

    def __iter__(self):
        return iter(self.results)


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
