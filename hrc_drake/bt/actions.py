"""Built-in actions, following BehaviorTree.CPP 4.x (src/actions), with Sleep on
simulation time."""

from __future__ import annotations

import functools
from collections.abc import Callable

from .decorators import ENTRY_PORT, EntryWatch
from .node import EntryRef, NodeConfig
from .node_kinds import ConditionNode, StatefulActionNode, SyncActionNode
from .ports import BidirectionalPort, InputPort, PortInfo, Range, literal_value
from .script import ScriptCode, compile_script
from .status import FAILURE, RUNNING, SUCCESS, Status
from .timing import has_elapsed


class ConstantAction(SyncActionNode):
    """AlwaysSuccess / AlwaysFailure."""

    def __init__(self, config: NodeConfig, result: Status):
        super().__init__(config)
        self.result = result

    def tick(self) -> Status:
        return self.result


class ScriptAction(SyncActionNode):
    """Script: run ``code`` against the blackboard; always SUCCESS."""

    ports = (InputPort("code", ScriptCode, description="script to run"),)

    def tick(self) -> Status:
        compile_script(self.get_input("code"))(self.script_env)
        return SUCCESS


class ScriptCondition(ConditionNode):
    """ScriptCondition: SUCCESS if ``code`` evaluates to true, else FAILURE."""

    ports = (InputPort("code", ScriptCode, description="script that returns true or false"),)

    def tick(self) -> Status:
        return (
            SUCCESS if compile_script(self.get_input("code")).is_true(self.script_env) else FAILURE
        )


class SetBlackboard(SyncActionNode):
    """Write ``value`` (a literal or ``{other_key}``'s value) into entry ``output_key``."""

    ports = (
        InputPort("value", description="value to write, or {key} to copy an entry"),
        BidirectionalPort("output_key", str, description="name of the entry to write"),
    )

    def tick(self) -> Status:
        key_binding = self._inputs["output_key"]
        key = key_binding.key if isinstance(key_binding, EntryRef) else key_binding.value
        destination = self.blackboard.entry(key, create=True)
        source = self._inputs["value"]
        value = self.get_input("value")
        if isinstance(source, EntryRef):
            if destination.type is None:
                destination.type = source.entry.type
        elif destination.type is None and isinstance(destination.value, int | float):
            value = self._as_number(value, key)
        destination.assign(value)
        return SUCCESS

    def _as_number(self, text: str, key: str) -> int | float:
        """A literal written into an untyped entry that holds a number or a truth value
        (both numbers in BT.CPP's scripts) stays a number, as BT.CPP converts it for a
        typed entry (BT.CPP itself empties such an entry: see docs/bt-conformance.md)."""
        number = literal_value(text)
        if isinstance(number, str):
            raise self.error(f"cannot write '{text}' into '{key}', which holds a number", "value")
        return number


class UnsetBlackboard(SyncActionNode):
    """Remove the value of entry ``key``."""

    ports = (InputPort("key", str, description="name of the entry to unset"),)

    def tick(self) -> Status:
        self.blackboard.unset(self.get_input("key"))
        return SUCCESS


class Sleep(StatefulActionNode):
    """RUNNING for ``msec`` of simulation time, then SUCCESS."""

    ports = (InputPort("msec", int, description="duration in milliseconds", accepts=Range(0)),)

    def on_start(self) -> Status:
        self.started_at = self.now
        return RUNNING if self.get_input("msec") > 0 else SUCCESS

    def on_running(self) -> Status:
        return (
            SUCCESS if has_elapsed(self.started_at, self.now, self.get_input("msec")) else RUNNING
        )


class WasEntryUpdated(SyncActionNode):
    """SUCCESS if the entry changed since this node last looked, else FAILURE."""

    ports = (ENTRY_PORT,)

    def __init__(self, config: NodeConfig):
        super().__init__(config)
        self.watch = EntryWatch(config)

    def tick(self) -> Status:
        return SUCCESS if self.watch.updated(self.blackboard) else FAILURE

    def on_tree_reset(self) -> None:
        self.watch.seen = 0


TickFunction = Callable[[SyncActionNode], Status]


class FunctionTick:
    """Mixin for nodes registered from a plain function ``function(node) -> Status``."""

    def __init__(self, config: NodeConfig, function: TickFunction, ports=()):
        super().__init__(config)
        self.function = function
        self.tick = functools.partial(function, self)  # one call less per tick

    def tick(self) -> Status:  # the instance's partial above replaces it
        return self.function(self)

    @classmethod
    def provided_ports(cls, function: TickFunction, ports: tuple[PortInfo, ...] = ()):
        return tuple(ports)


class FunctionAction(FunctionTick, SyncActionNode):
    """A synchronous action given as a function."""


class FunctionCondition(FunctionTick, ConditionNode):
    """A condition given as a function."""
