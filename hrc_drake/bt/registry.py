"""The registry of node types (ID -> class + parameters + ports) and the built-ins."""

from __future__ import annotations

import enum
from collections.abc import Iterator
from dataclasses import dataclass, field
from typing import Any

from .actions import (
    ConstantAction,
    FunctionAction,
    FunctionCondition,
    ScriptAction,
    ScriptCondition,
    SetBlackboard,
    Sleep,
    UnsetBlackboard,
    WasEntryUpdated,
)
from .controls.branches import IfThenElse, Switch, WhileDoElse
from .controls.parallel import Parallel, ParallelAll
from .controls.sequences import ReactiveControl, SequentialControl, TryCatch
from .decorators import (
    Delay,
    EntryUpdated,
    ForceStatus,
    Inverter,
    KeepRunningUntilFailure,
    Loop,
    Precondition,
    RepeatUntil,
    RunOnce,
    SubTreeNode,
    Timeout,
)
from .errors import BTError
from .node import TreeNode
from .ports import PortInfo
from .status import FAILURE, RUNNING, SKIPPED, SUCCESS


@dataclass(frozen=True)
class NodeModel:
    """A registered node type: what the XML calls it and how to build it."""

    id: str
    cls: type[TreeNode]
    params: dict[str, Any] = field(default_factory=dict)
    description: str = ""
    builtin: bool = False

    @property
    def kind(self) -> str:
        return self.cls.kind

    @property
    def ports(self) -> dict[str, PortInfo]:
        return {port.name: port for port in self.cls.provided_ports(**self.params)}

    @property
    def children_range(self) -> tuple[int, int | None]:
        return self.cls.allowed_children(**self.params)

    def create(self, config) -> TreeNode:
        return self.cls(config, **self.params)


class NodeRegistry:
    """Node types known to a factory, plus the enum names scripts may use."""

    def __init__(self) -> None:
        self._models: dict[str, NodeModel] = {}
        self.enums: dict[str, int] = {}

    def register(
        self,
        cls: type[TreeNode],
        id: str | None = None,
        *,
        description: str = "",
        builtin: bool = False,
        **params: Any,
    ) -> NodeModel:
        """Register ``cls`` under ``id`` (default: the class name). ``params`` are
        passed to the constructor and to ``provided_ports``."""
        model = NodeModel(
            id or cls.__name__,
            cls,
            params,
            description or " ".join((cls.__doc__ or "").strip().split("\n\n")[0].split()),
            builtin,
        )
        if model.id in self._models:
            raise BTError(f"node type '{model.id}' is already registered")
        self._models[model.id] = model
        return model

    def register_function(
        self,
        id: str,
        function,
        *,
        kind: str = "Action",
        ports: tuple[PortInfo, ...] = (),
        description: str = "",
    ) -> NodeModel:
        """Register ``function(node) -> Status`` as a synchronous Action or Condition."""
        cls = FunctionCondition if kind == "Condition" else FunctionAction
        return self.register(
            cls, id, description=description, function=function, ports=tuple(ports)
        )

    def register_enum(self, enum_type: type[enum.Enum]) -> None:
        """Make the members' names usable in scripts and Switch cases (as their values)."""
        for member in enum_type:
            self.enums[member.name] = int(member.value)

    def __contains__(self, id: str) -> bool:
        return id in self._models

    def __getitem__(self, id: str) -> NodeModel:
        return self._models[id]

    def ids(self) -> list[str]:
        return list(self._models)

    def models(self) -> Iterator[NodeModel]:
        return iter(self._models.values())


def _register_builtins(registry: NodeRegistry) -> None:
    def add(cls, id, **params):
        registry.register(cls, id, builtin=True, **params)

    seq = SequentialControl
    add(seq, "Sequence", stops_on=FAILURE)
    add(seq, "AsyncSequence", stops_on=FAILURE, yields=True)
    add(seq, "SequenceWithMemory", stops_on=FAILURE, yields=True, memory=True)
    add(seq, "SequenceStar", stops_on=FAILURE, yields=True, memory=True)
    add(seq, "Fallback", stops_on=SUCCESS)
    add(seq, "AsyncFallback", stops_on=SUCCESS, yields=True)
    add(ReactiveControl, "ReactiveSequence", stops_on=FAILURE)
    add(ReactiveControl, "ReactiveFallback", stops_on=SUCCESS)
    for cls in (Parallel, ParallelAll, IfThenElse, WhileDoElse, TryCatch):
        add(cls, cls.__name__)
    for cases in range(2, 7):
        add(Switch, f"Switch{cases}", cases=cases)

    add(Inverter, "Inverter")
    add(ForceStatus, "ForceSuccess", forced=SUCCESS)
    add(ForceStatus, "ForceFailure", forced=FAILURE)
    add(RepeatUntil, "Repeat", count_port="num_cycles", repeat_on=SUCCESS)
    add(RepeatUntil, "RetryUntilSuccessful", count_port="num_attempts", repeat_on=FAILURE)
    for cls in (KeepRunningUntilFailure, Timeout, Delay, RunOnce, Precondition):
        add(cls, cls.__name__)
    add(SubTreeNode, "SubTree")
    for suffix, item_type in (("Int", int), ("Double", float), ("Bool", bool), ("String", str)):
        add(Loop, f"Loop{suffix}", item_type=item_type)
    add(EntryUpdated, "SkipUnlessUpdated", if_not_updated=SKIPPED)
    add(EntryUpdated, "WaitValueUpdate", if_not_updated=RUNNING)

    add(ConstantAction, "AlwaysSuccess", result=SUCCESS)
    add(ConstantAction, "AlwaysFailure", result=FAILURE)
    add(ScriptAction, "Script")
    add(ScriptCondition, "ScriptCondition")
    for cls in (SetBlackboard, UnsetBlackboard, Sleep, WasEntryUpdated):
        add(cls, cls.__name__)


def default_registry() -> NodeRegistry:
    """A fresh registry holding every built-in node; register yours on top of it."""
    registry = NodeRegistry()
    _register_builtins(registry)
    return registry
