"""The asynchronous node that sends one command to an actor and follows its outcome.

Every actor reports the outcomes of its recent commands by sequence number, so a node
knows when *its* command finished even if other commands came after it. Halting the node
cancels the command where the actor has a cancel (Stop for the robot, Cancel for the
person)."""

from abc import abstractmethod
from typing import ClassVar

from hrc_drake.bt import StatefulActionNode, Status
from hrc_drake.messages import RUNNING, SUCCEEDED, CommandResult, ResultLog


class CommandNode(StatefulActionNode):
    """Sends `command(seq)` to `actor` on start; SUCCESS when it succeeded, FAILURE when it
    failed, was rejected or cancelled."""

    actor: ClassVar[str]
    commands: ClassVar[tuple[str, ...]]
    """Every actor the node sends commands to (`actor` and any other): a tree may hold the
    node only if its agent may command them all (hrc_drake.wiring.COMMANDED_BY)."""
    cancel_command: ClassVar[type | None] = None
    """Command class (built from a seq) sent when the node is halted; None: nothing."""

    @abstractmethod
    def command(self, seq: int):
        """The command to send, numbered `seq`."""

    def results(self, status) -> ResultLog:
        """Where the actor's `status` keeps the results of this agent's commands."""
        return status.results

    def result(self):
        """The actor's CommandResult for this node's command (None until it has one)."""
        status = self.agent.statuses[self.actor]
        return self.results(status).result_of(self.seq) if status is not None else None

    def outcome(self) -> str | None:
        result = self.result()
        return result.outcome if result is not None else None

    def succeeded(self) -> Status:
        """Called once the command succeeded; nodes with outputs write them here."""
        return Status.SUCCESS

    def on_start(self) -> Status:
        self.seq = self.agent.send(self.actor, self.command)
        return Status.RUNNING

    def on_running(self) -> Status:
        outcome = self.outcome()
        if outcome is None or outcome == RUNNING:
            return Status.RUNNING
        if outcome == SUCCEEDED:
            return self.succeeded()
        return self.failed(self.result())

    def failed(self, result: CommandResult) -> Status:
        """FAILURE, keeping why (the actor's outcome and reason) for the run's logs."""
        reason = f": {result.reason}" if result.reason else ""
        self.failure_reason = f"{result.outcome}{reason}"
        return Status.FAILURE

    def on_halted(self) -> None:
        if self.cancel_command is not None:
            self.agent.send(self.actor, self.cancel_command)
