"""What every tree node is: its configuration from the XML, its ports, BehaviorTree.CPP's
tick with pre/post-conditions and hooks, its status and halting.

The kinds authors subclass (actions, conditions, controls, decorators) are in
:mod:`.node_kinds`. A node sees the tree that holds it only as a :class:`HostTree`, so this
module does not import the tree module (which imports it).
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any, ClassVar, Protocol

import numpy as np

from .blackboard import UNSET, Blackboard, Entry
from .errors import BTError
from .ports import Accepts, PortInfo
from .script import Script, ScriptEnv
from .status import FAILURE, IDLE, RUNNING, SKIPPED, SUCCESS, Status

PRECONDITIONS = ("_failureIf", "_successIf", "_skipIf", "_while")
POSTCONDITIONS = ("_onSuccess", "_onFailure", "_onHalted", "_post")

PreTickHook = Callable[["TreeNode"], Status]
PostTickHook = Callable[["TreeNode", Status], Status]


class HostTree(Protocol):
    """What a node uses of the tree that holds it (``bt.tree.Tree`` is one): the time of
    the tick, the random generator, the application's agent, the enums scripts know and
    the observers it notifies of its transitions."""

    now: float
    rng: np.random.Generator
    agent: Any
    enums: dict[str, int]
    observers: list[Any]

    def notify(self, node: TreeNode, previous: Status, new: Status) -> None: ...


class Literal:
    """A port given as a constant in the XML, already converted to the port's type."""

    __slots__ = ("value",)

    def __init__(self, value: Any):
        self.value = value

    def read(self) -> Any:
        return self.value


class EntryRef:
    """A port bound to a blackboard entry (``{key}``), resolved once at construction."""

    __slots__ = ("key", "entry")

    def __init__(self, key: str, entry: Entry):
        self.key = key
        self.entry = entry

    def read(self) -> Any:
        return self.entry.value


@dataclass
class NodeConfig:
    """Everything the factory knows about one node instance."""

    registration_id: str
    name: str
    uid: int
    path: str
    tree: HostTree
    blackboard: Blackboard
    inputs: dict[str, Literal | EntryRef] = field(default_factory=dict)
    outputs: dict[str, EntryRef] = field(default_factory=dict)
    attributes: dict[str, str] = field(default_factory=dict)
    file: str | None = None
    line: int | None = None
    tree_id: str | None = None
    preconditions: list[tuple[str, Script]] = field(default_factory=list)
    postconditions: dict[str, Script] = field(default_factory=dict)
    accepts: dict[str, Accepts] = field(default_factory=dict)
    """The values each input port with a declared range or words accepts."""


class TreeNode(ABC):
    """A node of an instantiated tree. ``status`` is read by parents; ``tick`` is the
    node's own logic; ``execute_tick`` wraps it with pre/post-conditions."""

    kind: ClassVar[str] = "Action"
    ports: ClassVar[tuple[PortInfo, ...]] = ()
    children_range: ClassVar[tuple[int, int | None]] = (0, 0)
    synchronous: ClassVar[bool] = False
    _pre_tick: PreTickHook | None = None
    _post_tick: PostTickHook | None = None

    def __init__(self, config: NodeConfig):
        self.config = config
        self.uid = config.uid
        self.name = config.name
        self.path = config.path
        self.tree = config.tree
        self.blackboard = config.blackboard
        self.status = IDLE
        self.tick_counts: list[int] | None = None  # results by status, once NodeCounters attach
        self.failure_reason = ""
        """Why the node last returned FAILURE, when it knows (e.g. the actor's answer)."""
        self._observers = config.tree.observers  # the tree's list, shared
        self._inputs = config.inputs
        self._outputs = config.outputs
        self._refresh_guards()
        self._script_env: ScriptEnv | None = None

    @classmethod
    def provided_ports(cls, **params: Any) -> tuple[PortInfo, ...]:
        """Ports of this node type; parameterised types (Switch3, LoopInt) override."""
        return cls.ports

    @classmethod
    def allowed_children(cls, **params: Any) -> tuple[int, int | None]:
        """Least and most children in the XML (None: no limit)."""
        return cls.children_range

    @property
    def registration_id(self) -> str:
        return self.config.registration_id

    @property
    def now(self) -> float:
        """Simulation time of the current tick, in seconds."""
        return self.tree.now

    @property
    def rng(self):
        """The tree's numpy Generator: the only source of randomness for nodes."""
        return self.tree.rng

    @property
    def agent(self) -> Any:
        """The application's object set on the tree (e.g. robot status, command outbox)."""
        return self.tree.agent

    @property
    def script_env(self) -> ScriptEnv:
        if self._script_env is None:
            self._script_env = ScriptEnv(self.blackboard, self.tree.enums)
        return self._script_env

    def children_nodes(self) -> list[TreeNode]:
        return []

    # ports -------------------------------------------------------------------------
    def constant_input(self, name: str) -> Any:
        """The value the XML gives port ``name`` as a constant (None: it names a blackboard
        entry or is unset): what is known of the node before it runs."""
        binding = self._inputs.get(name)
        return binding.value if isinstance(binding, Literal) else None

    def get_input(self, name: str, default: Any = UNSET) -> Any:
        """Value of input port ``name``; ``default`` if its entry is unset (else error)."""
        binding = self._inputs.get(name)
        value = binding.read() if binding is not None else UNSET
        if value is UNSET:
            if default is not UNSET:
                return default
            raise self.error(
                "no value: "
                + (
                    f"blackboard entry '{binding.key}' is not set"
                    if binding is not None
                    else "port is not connected"
                ),
                port=name,
            )
        if name in self.config.accepts and isinstance(binding, EntryRef):
            problem = self.input_problem(name, value)  # literals were checked when built
            if problem:
                raise self.error(problem, port=name)
        return value

    def input_problem(self, port: str, value: Any) -> str:
        """What is wrong with `value` as input `port` ("" when nothing): outside the port's
        declared range or words; a node type adds rules of its own (e.g. one weight per
        child). The tree builder asks it of literals, `validate` of values known before a
        run, `get_input` of every value read from the blackboard. None is a port left out
        whose default is None (an ActorReach squaring up no object): nothing to judge."""
        accepts = self.config.accepts.get(port)
        return accepts.problem(value) if accepts is not None and value is not None else ""

    def set_output(self, name: str, value: Any) -> bool:
        """Write output port ``name``; False when the XML leaves the port unconnected."""
        binding = self._outputs.get(name)
        if binding is None:
            return False
        try:
            binding.entry.assign(value)
        except BTError as error:
            raise self.error(error.problem, port=name) from None
        return True

    def error(self, problem: str, port: str | None = None) -> BTError:
        """A BTError located at this node (file, line, tree, path)."""
        config = self.config
        return BTError(
            problem,
            file=config.file,
            line=config.line,
            tree=config.tree_id,
            node=self.path,
            port=port,
        )

    # ticking -----------------------------------------------------------------------
    @abstractmethod
    def tick(self) -> Status:
        """The node's own logic for one tick."""

    def execute_tick(self) -> Status:
        try:
            if self._preconditions is None:
                status = self.tick()
            else:
                forced = self._check_preconditions()
                status = self.tick() if forced is None else forced
            if self._postconditions is not None:
                status = self._after_tick(status)
        except BTError as error:
            if error.node is not None:
                raise
            raise self.error(error.problem, port=error.port) from None
        previous = self.status
        if status is not previous and status is not SKIPPED:  # SKIPPED keeps IDLE
            if status is RUNNING and self.synchronous:
                raise self.error(
                    f"{type(self).__name__} is synchronous and must not return RUNNING"
                )
            self.status = status  # set_status, inlined: this is the hottest line
            if self._observers:
                self.tree.notify(self, previous, status)
        if self.tick_counts is not None:
            self.tick_counts[status] += 1
        return status

    def _check_preconditions(self) -> Status | None:
        env = self.script_env
        for kind, script in self._preconditions:
            if self.status is IDLE:
                holds = script.is_true(env)
                if kind == "_while":
                    if not holds:
                        return SKIPPED
                elif holds:
                    return {"_failureIf": FAILURE, "_successIf": SUCCESS, "_skipIf": SKIPPED}[kind]
            elif self.status is RUNNING and kind == "_while" and not script.is_true(env):
                self.halt_node()
                return SKIPPED
        if self._pre_tick is not None and not self.status.is_completed:
            override = self._pre_tick(self)
            if override is SUCCESS or override is FAILURE:
                return override
        return None

    def _after_tick(self, status: Status) -> Status:
        """Post-condition scripts of a completed tick, then the post-tick hook, which may
        replace the result (as BehaviorTree.CPP's executeTick)."""
        if status is SUCCESS or status is FAILURE:
            scripts = self._postconditions
            specific = scripts.get("_onSuccess" if status is SUCCESS else "_onFailure")
            if specific is not None:
                specific(self.script_env)
            always = scripts.get("_post")
            if always is not None:
                always(self.script_env)
        if self._post_tick is not None:
            override = self._post_tick(self, status)
            if override is SUCCESS or override is FAILURE:
                return override
        return status

    # hooks --------------------------------------------------------------------------
    def set_pre_tick(self, hook: PreTickHook | None) -> None:
        """Call ``hook(node)`` before each tick of a node that has not completed; a
        SUCCESS or FAILURE it returns replaces the tick (BT.CPP's setPreTickFunction)."""
        self._pre_tick = hook
        self._refresh_guards()

    def set_post_tick(self, hook: PostTickHook | None) -> None:
        """Call ``hook(node, status)`` after each tick; a SUCCESS or FAILURE it returns
        replaces the result (BT.CPP's setPostTickFunction)."""
        self._post_tick = hook
        self._refresh_guards()

    def _refresh_guards(self) -> None:
        """Take the slow path of execute_tick only for nodes with scripts or hooks."""
        config = self.config
        self._preconditions = (
            config.preconditions if config.preconditions or self._pre_tick else None
        )
        self._postconditions = (
            config.postconditions if config.postconditions or self._post_tick else None
        )

    def set_status(self, new_status: Status) -> None:
        previous = self.status
        if previous is not new_status:
            self.status = new_status
            if self._observers:
                self.tree.notify(self, previous, new_status)

    def reset_status(self) -> None:
        if self.status is not IDLE:
            self.set_status(IDLE)

    # halting ------------------------------------------------------------------------
    def halt(self) -> None:  # noqa: B027  (a hook: most leaves have nothing to stop)
        """Stop the node's own activity; leaves and composites override this."""

    def halt_node(self) -> None:
        """Halt, then run the ``_onHalted`` script (as BehaviorTree.CPP's haltNode)."""
        self.halt()
        if self._postconditions is not None:
            on_halted = self._postconditions.get("_onHalted")
            if on_halted is not None:
                on_halted(self.script_env)

    def on_tree_reset(self) -> None:  # noqa: B027  (a hook: most nodes keep no memory)
        """Forget memory that survives a halt (Tree.reset calls this on every node)."""
