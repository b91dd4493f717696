"""Built-in decorators, following BehaviorTree.CPP 4.x (src/decorators), with Delay and
Timeout on simulation time."""

from __future__ import annotations

from .blackboard import Blackboard
from .node import EntryRef, NodeConfig
from .node_kinds import DecoratorNode
from .ports import BidirectionalPort, InputPort, OutputPort, Range, convert_from_string
from .script import ScriptCode, compile_script
from .status import COMPLETED, FAILURE, IDLE, RUNNING, SKIPPED, SUCCESS, Status
from .timing import has_elapsed


class Inverter(DecoratorNode):
    """SUCCESS becomes FAILURE and FAILURE becomes SUCCESS."""

    def tick(self) -> Status:
        self.set_status(RUNNING)
        status = self.child.execute_tick()
        if status is SUCCESS or status is FAILURE:
            self.reset_child()
            return FAILURE if status is SUCCESS else SUCCESS
        return status


class ForceStatus(DecoratorNode):
    """ForceSuccess / ForceFailure: a completed child reports ``forced`` instead."""

    def __init__(self, config: NodeConfig, forced: Status):
        super().__init__(config)
        self.forced = forced

    def tick(self) -> Status:
        self.set_status(RUNNING)
        status = self.child.execute_tick()
        if status in COMPLETED:
            self.reset_child()
            return self.forced
        return status


class KeepRunningUntilFailure(DecoratorNode):
    """A succeeding child is restarted and RUNNING reported, until it fails."""

    def tick(self) -> Status:
        self.set_status(RUNNING)
        status = self.child.execute_tick()
        if status is FAILURE:
            self.reset_child()
            return FAILURE
        if status is SUCCESS:
            self.reset_child()
        return RUNNING


class RepeatUntil(DecoratorNode):
    """Repeat (``repeat_on=SUCCESS``, port num_cycles) and RetryUntilSuccessful
    (``repeat_on=FAILURE``, port num_attempts): restart the child while it returns
    ``repeat_on``, at most ``count_port`` times (-1: forever). A child that completed
    within one tick is restarted at the next tick, so sync children cannot hang a tick.
    """

    def __init__(self, config: NodeConfig, count_port: str, repeat_on: Status):
        super().__init__(config)
        self.count_port = count_port
        self.repeat_on = repeat_on
        self.done = 0

    @classmethod
    def provided_ports(cls, count_port: str, repeat_on: Status) -> tuple:
        what = "repetitions" if repeat_on is SUCCESS else "attempts"
        return (InputPort(count_port, int, description=f"number of {what} (-1 = forever)"),)

    def tick(self) -> Status:
        limit = self.get_input(self.count_port)
        self.set_status(RUNNING)
        while self.done < limit or limit == -1:
            previous = self.child.status
            status = self.child.execute_tick()
            if status is RUNNING:
                return RUNNING
            self.reset_child()
            if status is not self.repeat_on:
                if status is not SKIPPED:
                    self.done = 0
                return status
            self.done += 1
            if previous is IDLE and (self.done < limit or limit == -1):
                return RUNNING
        self.done = 0
        return self.repeat_on

    def halt(self) -> None:
        self.done = 0
        super().halt()


class TimedDecorator(DecoratorNode):
    """Shared clock handling of Timeout and Delay: started at the first tick, cleared
    when the child completes or the node is halted."""

    def __init__(self, config: NodeConfig):
        super().__init__(config)
        self.started_at: float | None = None

    def start_if_idle(self) -> bool:
        """Start the clock on the first tick; True if it was already running."""
        if self.started_at is not None:
            return True
        self.started_at = self.now
        self.set_status(RUNNING)
        return False

    def tick_child(self) -> Status:
        status = self.child.execute_tick()
        if status in COMPLETED:
            self.started_at = None
            self.reset_child()
        return status

    def halt(self) -> None:
        self.started_at = None
        super().halt()


class Timeout(TimedDecorator):
    """Halt the child and return FAILURE if it is still RUNNING ``msec`` after start."""

    ports = (
        InputPort(
            "msec", int, description="time limit in milliseconds (0: none)", accepts=Range(0)
        ),
    )

    def tick(self) -> Status:
        msec = self.get_input("msec")
        if self.start_if_idle() and msec > 0 and has_elapsed(self.started_at, self.now, msec):
            self.started_at = None
            self.reset_child()
            return FAILURE
        return self.tick_child()


class Delay(TimedDecorator):
    """Return RUNNING for ``delay_msec`` of simulation time, then tick the child."""

    ports = (InputPort("delay_msec", int, description="delay in milliseconds", accepts=Range(0)),)

    def tick(self) -> Status:
        self.start_if_idle()
        if not has_elapsed(self.started_at, self.now, self.get_input("delay_msec")):
            return RUNNING
        return self.tick_child()


class RunOnce(DecoratorNode):
    """Tick the child to completion once; afterwards SKIPPED (or its first result)."""

    ports = (
        InputPort(
            "then_skip", bool, True, "skip after the first run, else repeat the first result"
        ),
    )

    def __init__(self, config: NodeConfig):
        super().__init__(config)
        self.result: Status | None = None

    def tick(self) -> Status:
        if self.result is not None:
            return SKIPPED if self.get_input("then_skip") else self.result
        self.set_status(RUNNING)
        status = self.child.execute_tick()
        if status in COMPLETED:
            self.result = status
            self.reset_child()
        return status

    def on_tree_reset(self) -> None:
        self.result = None


class Precondition(DecoratorNode):
    """Tick the child only if the script ``if`` holds, else return ``else``; not
    re-checked while the child runs."""

    ports = (
        InputPort("if", ScriptCode, description="script that must be true to tick the child"),
        InputPort("else", Status, FAILURE, "status returned when the condition is false"),
    )

    def __init__(self, config: NodeConfig):
        super().__init__(config)
        self.child_running = False

    def tick(self) -> Status:
        if not self.child_running:
            if not compile_script(self.get_input("if")).is_true(self.script_env):
                return self.get_input("else")
            self.child_running = True
        status = self.child.execute_tick()
        if status in COMPLETED:
            self.reset_child()
            self.child_running = False
        return status

    def halt(self) -> None:
        self.child_running = False
        super().halt()


class SubTreeNode(DecoratorNode):
    """The root of a SubTree instance, with its own blackboard (see the factory)."""

    kind = "SubTree"
    ports = (InputPort("_autoremap", bool, False, "share every same-named entry"),)
    children_range = (0, 0)

    def tick(self) -> Status:
        if self.status is IDLE:
            self.set_status(RUNNING)
        status = self.child.execute_tick()
        if status in COMPLETED:
            self.reset_child()
        return status


class Loop(DecoratorNode):
    """LoopInt/LoopDouble/LoopBool/LoopString: pop one item of ``queue`` per cycle into
    ``value`` and tick the child, until the queue is empty (then ``if_empty``)."""

    def __init__(self, config: NodeConfig, item_type: type):
        super().__init__(config)
        self.item_type = item_type
        queue = config.inputs.get("queue")
        self.static_queue = (
            None
            if isinstance(queue, EntryRef)
            else convert_from_string(queue.value, list[item_type])
        )
        self.queue: list | None = None
        self.child_running = False

    @classmethod
    def provided_ports(cls, item_type: type) -> tuple:
        return (
            BidirectionalPort("queue", description="items separated by ';' or a list entry"),
            InputPort("if_empty", Status, SUCCESS, "status when the queue is empty"),
            OutputPort("value", item_type, "the current item"),
        )

    def tick(self) -> Status:
        if self.status is IDLE:
            self.child_running = False
            self.queue = list(self.static_queue) if self.static_queue is not None else None
        popped = False
        if not self.child_running:
            self._load_queue()
            if self.queue:
                self.set_output("value", self.queue.pop(0))
                popped = True
        if not popped and not self.child_running:
            return self.get_input("if_empty")
        self.set_status(RUNNING)
        status = self.child.execute_tick()
        self.child_running = status is RUNNING
        if status in COMPLETED:
            self.reset_child()
        return FAILURE if status is FAILURE else RUNNING

    def _load_queue(self) -> None:
        if self.static_queue is not None:
            return
        content = self.get_input("queue", None)
        if isinstance(content, list):
            self.queue = content
        elif isinstance(content, str) and self.queue is None:
            self.queue = convert_from_string(content, list[self.item_type])


class EntryWatch:
    """Remembers which version of a blackboard entry a node has seen last."""

    def __init__(self, config: NodeConfig):
        binding = config.inputs["entry"]
        self.key = binding.key if isinstance(binding, EntryRef) else binding.value
        self.seen = 0

    def updated(self, blackboard: Blackboard) -> bool:
        entry = blackboard.entry(self.key)
        if entry is None:
            return False
        previous, self.seen = self.seen, entry.sequence_id
        return previous != self.seen


ENTRY_PORT = InputPort("entry", description="blackboard entry to watch ({key} or key)")


class EntryUpdated(DecoratorNode):
    """SkipUnlessUpdated (``if_not_updated=SKIPPED``) / WaitValueUpdate (``RUNNING``):
    tick the child only if the entry changed since the last time it was checked."""

    ports = (ENTRY_PORT,)

    def __init__(self, config: NodeConfig, if_not_updated: Status):
        super().__init__(config)
        self.if_not_updated = if_not_updated
        self.watch = EntryWatch(config)
        self.child_running = False

    def tick(self) -> Status:
        if not self.child_running and not self.watch.updated(self.blackboard):
            return self.if_not_updated
        status = self.child.execute_tick()
        self.child_running = status is RUNNING
        return status

    def halt(self) -> None:
        self.child_running = False
        super().halt()

    def on_tree_reset(self) -> None:
        self.watch.seen = 0
