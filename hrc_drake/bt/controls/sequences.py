"""Sequence and Fallback with their asynchronous, memory and reactive variants, and
TryCatch (a Sequence with a catch branch), following BehaviorTree.CPP 4.x.

A tick here is BehaviorTree.CPP's ``tickExactlyOnce``: where BT.CPP emits a wake-up
signal (AsyncSequence, SequenceWithMemory after a child completed synchronously), the
node returns RUNNING and continues at the next tick.
"""

from __future__ import annotations

from ..node import NodeConfig
from ..node_kinds import ControlNode, halt_and_reset
from ..ports import InputPort
from ..status import FAILURE, IDLE, RUNNING, SKIPPED, SUCCESS, Status


def _opposite(status: Status) -> Status:
    return SUCCESS if status is FAILURE else FAILURE


class SequentialControl(ControlNode):
    """Sequence (``stops_on=FAILURE``) and Fallback (``stops_on=SUCCESS``): tick the
    children in order, resuming at the RUNNING one, until one returns ``stops_on``.

    ``yields``: return RUNNING after a child completed synchronously (Async variants).
    ``memory``: on ``stops_on`` keep the position (SequenceWithMemory), also when halted.
    """

    def __init__(self, config: NodeConfig, stops_on: Status, yields=False, memory=False):
        super().__init__(config)
        self.stops_on = stops_on
        self.passes_on = _opposite(stops_on)
        self.yields = yields
        self.memory = memory
        self.current = 0
        self.skipped = 0

    def tick(self) -> Status:
        children = self.children
        count = len(children)
        if self.status is IDLE:
            self.skipped = 0
        self.set_status(RUNNING)
        while self.current < count:
            child = children[self.current]
            previous = child.status
            status = child.execute_tick()
            if status is RUNNING:
                return RUNNING
            if status is self.stops_on:
                self._stop()
                return status
            self.current += 1
            if status is SKIPPED:
                self.skipped += 1
            elif self.yields and previous is IDLE and self.current < count:
                return RUNNING
        all_skipped = self.skipped == count
        self.reset_children()
        self.current = self.skipped = 0
        return SKIPPED if all_skipped else self.passes_on

    def _stop(self) -> None:
        if self.memory:
            for index in range(self.current, len(self.children)):
                self.halt_child(index)
        else:
            self.reset_children()
            self.current = 0

    def halt(self) -> None:
        if not self.memory:
            self.current = 0
        self.skipped = 0
        super().halt()

    def on_tree_reset(self) -> None:
        self.current = self.skipped = 0


class ReactiveControl(ControlNode):
    """ReactiveSequence (``stops_on=FAILURE``) and ReactiveFallback (``SUCCESS``): tick
    from the first child at every tick; when one is RUNNING, halt all the others."""

    def __init__(self, config: NodeConfig, stops_on: Status):
        super().__init__(config)
        self.stops_on = stops_on
        self.passes_on = _opposite(stops_on)

    def tick(self) -> Status:
        all_skipped = True
        self.set_status(RUNNING)
        children = self.children
        for index, child in enumerate(children):
            status = child.execute_tick()
            if status is RUNNING:
                for other in children:
                    if other is not child and other.status is not IDLE:
                        halt_and_reset(other)
                return RUNNING
            if status is self.stops_on:
                self.reset_children()
                return status
            if status is SKIPPED:
                self.halt_child(index)
            else:
                all_skipped = False
        self.reset_children()
        return SKIPPED if all_skipped else self.passes_on


class TryCatch(ControlNode):
    """Tick the first children as a Sequence; if one fails, tick the last child (the
    catch branch) to completion and return FAILURE."""

    ports = (InputPort("catch_on_halt", bool, False, "run the catch branch when halted"),)
    children_range = (2, None)

    def __init__(self, config: NodeConfig):
        super().__init__(config)
        self.current = 0
        self.skipped = 0
        self.in_catch = False

    def tick(self) -> Status:
        if self.status is IDLE:
            self.skipped = 0
            self.in_catch = False
        self.set_status(RUNNING)
        if self.in_catch:
            return self._tick_catch()
        attempts = len(self.children) - 1
        while self.current < attempts:
            status = self.children[self.current].execute_tick()
            if status is RUNNING:
                return RUNNING
            if status is FAILURE:
                self.reset_children()
                self.current = 0
                self.in_catch = True
                return self._tick_catch()
            self.current += 1
            self.skipped += status is SKIPPED
        all_skipped = self.skipped == attempts
        self.reset_children()
        self.current = self.skipped = 0
        return SKIPPED if all_skipped else SUCCESS

    def _tick_catch(self) -> Status:
        if self.children[-1].execute_tick() is RUNNING:
            return RUNNING
        self.reset_children()
        self.current = 0
        self.in_catch = False
        return FAILURE

    def halt(self) -> None:
        if self.get_input("catch_on_halt") and not self.in_catch and self.status is RUNNING:
            last = len(self.children) - 1
            for index in range(last):
                self.halt_child(index)
            if self.children[last].execute_tick() is RUNNING:
                self.halt_child(last)
        self.current = self.skipped = 0
        self.in_catch = False
        super().halt()
