"""Random trees run by hrc_drake.bt and by BehaviorTree.CPP (behaviortreepy), compared tick by
tick: the root's result, every node's status (BT.CPP's through its Groot2Publisher's status
reply) and the root blackboard.

Leaves behave identically in both engines: ``Run<S|F><n>`` is an asynchronous action that
runs n ticks then succeeds or fails, ``Cond<pattern>`` a condition whose results cycle
through its pattern (per node), scripts and SetBlackboard work on integer counters. With
``subtrees``, the main tree also calls a second tree through SubTree nodes whose ports
remap the counters (``{=}``, ``{other}``) or autoremap them.
"""

from __future__ import annotations

import dataclasses
import random
import struct
from dataclasses import dataclass, field

import behaviortreepy as btcpp
import zmq

from hrc_drake.bt import (
    BTError,
    ConditionNode,
    StatefulActionNode,
    Status,
    default_registry,
    load_tree,
)

RUN_LEAVES = [f"Run{result}{ticks}" for result in "SF" for ticks in (0, 1, 2)]
CONDITION_PATTERNS = ["S", "F", "SF", "FS", "SSF", "FFS"]
COUNTERS = ("a", "b", "c")
COMPARISONS = ("<", ">=", "==", "!=")
HEADER = struct.Struct("<BBI")


# --- the same leaves in both engines ------------------------------------------------------
class RunFor(StatefulActionNode):
    def __init__(self, config, ticks: int, result: Status):
        super().__init__(config)
        self.ticks, self.result, self.left = ticks, result, 0

    def on_start(self):
        self.left = self.ticks
        return self.on_running()

    def on_running(self):
        if self.left == 0:
            return self.result
        self.left -= 1
        return Status.RUNNING


class Cycle(ConditionNode):
    def __init__(self, config, pattern: str):
        super().__init__(config)
        self.pattern, self.calls = pattern, 0

    def tick(self):
        self.calls += 1
        return (
            Status.SUCCESS
            if self.pattern[(self.calls - 1) % len(self.pattern)] == "S"
            else (Status.FAILURE)
        )


def our_registry():
    registry = default_registry()
    for name in RUN_LEAVES:
        result = Status.SUCCESS if name[3] == "S" else Status.FAILURE
        registry.register(RunFor, name, ticks=int(name[4:]), result=result)
    for pattern in CONDITION_PATTERNS:
        registry.register(Cycle, f"Cond{pattern}", pattern=pattern)
    return registry


def btcpp_factory():
    factory = btcpp.BehaviorTreeFactory()
    left: dict[int, int] = {}
    calls: dict[int, int] = {}
    for name in RUN_LEAVES:
        ticks, result = (
            int(name[4:]),
            getattr(btcpp.NodeStatus, "SUCCESS" if name[3] == "S" else "FAILURE"),
        )

        def running(node, result=result):
            if left[node.uid()] == 0:
                return result
            left[node.uid()] -= 1
            return btcpp.NodeStatus.RUNNING

        def start(node, ticks=ticks, running=running):
            left[node.uid()] = ticks
            return running(node)

        factory.register_simple_stateful_action(name, start, running)
    for pattern in CONDITION_PATTERNS:

        def cycle(node, pattern=pattern):
            calls[node.uid()] = calls.get(node.uid(), 0) + 1
            letter = pattern[(calls[node.uid()] - 1) % len(pattern)]
            return btcpp.NodeStatus.SUCCESS if letter == "S" else btcpp.NodeStatus.FAILURE

        factory.register_simple_condition(f"Cond{pattern}", cycle)
    return factory, (left, calls)


# --- random trees -----------------------------------------------------------------------
@dataclass
class Vocabulary:
    """What the generator may use; ``full`` adds decorators with ports, Parallel,
    scripts with operators, SetBlackboard and pre/post-conditions; ``precedence`` leaves out
    the parentheses that make scripts read alike whatever the operators' precedence;
    ``subtrees`` adds SubTree calls of a second tree, ``Sub``, remapping the counters."""

    full: bool = True
    precedence: bool = False
    subtrees: bool = False
    controls: list[str] = field(default_factory=list)
    decorators: list[str] = field(default_factory=list)

    def __post_init__(self):
        self.controls = [
            "Sequence",
            "Fallback",
            "ReactiveSequence",
            "ReactiveFallback",
            "SequenceWithMemory",
            "IfThenElse",
            "WhileDoElse",
        ]
        self.decorators = ["Inverter", "ForceSuccess", "ForceFailure", "KeepRunningUntilFailure"]
        if self.full:
            self.controls += ["AsyncSequence", "AsyncFallback", "Parallel", "ParallelAll"]
            self.decorators += ["Repeat", "RetryUntilSuccessful", "RunOnce", "Precondition"]


def _script(rng: random.Random, vocabulary: Vocabulary) -> str:
    counter, other = rng.choice(COUNTERS), rng.choice(COUNTERS)
    left, right = ("", "") if vocabulary.precedence else ("(", ")")
    return rng.choice(
        [
            f"{counter} += 1",
            f"{counter} = {left}{other} - {rng.randint(0, 2)}{right} + {rng.randint(0, 2)}",
            f"{counter} = {left}{other} > 1 || {counter} < 1{right} && {other} != 2",
            f"{counter} = {rng.randint(0, 3)}",
        ]
    )


def _condition_code(rng: random.Random, vocabulary: Vocabulary) -> str:
    if rng.random() < 0.7:
        return f"{rng.choice(COUNTERS)} {rng.choice(COMPARISONS)} {rng.randint(0, 3)}"
    left, right = ("", "") if vocabulary.precedence else ("(", ")")
    return (
        f"{left}{rng.choice(COUNTERS)} > 0 || {rng.choice(COUNTERS)} > 1{right} && "
        f"{rng.choice(COUNTERS)} < 2"
    )


def _attributes(rng: random.Random, vocabulary: Vocabulary) -> str:
    if not vocabulary.full or rng.random() > 0.15:
        return ""
    kind = rng.choice(
        ["_skipIf", "_successIf", "_failureIf", "_while", "_onSuccess", "_onFailure", "_post"]
    )
    code = (
        _script(rng, vocabulary)
        if kind.startswith("_on") or kind == "_post"
        else _condition_code(rng, vocabulary)
    )
    return f' {kind}="{_escape(code)}"'


def _escape(code: str) -> str:
    return code.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")


def _subtree_call(rng: random.Random) -> str:
    """A SubTree of ``Sub`` whose ports reach the caller's counters: each port the entry of
    its own name (``{=}``) or another counter, or every one by ``_autoremap``."""
    if rng.random() < 0.2:
        return '<SubTree ID="Sub" _autoremap="true"/>'
    ports = "".join(
        f' {counter}="{rng.choice(["{=}", "{=}", *(f"{{{c}}}" for c in COUNTERS)])}"'
        for counter in COUNTERS
    )
    return f'<SubTree ID="Sub"{ports}/>'


def _leaf(rng: random.Random, vocabulary: Vocabulary) -> str:
    choices = ["run", "run", "cond", "cond", "const"]
    if vocabulary.full:
        choices += ["script", "script_condition", "set"]
    if vocabulary.subtrees:
        choices += ["subtree", "subtree"]
    kind = rng.choice(choices)
    if kind == "subtree":
        return _subtree_call(rng)
    extra = _attributes(rng, vocabulary)
    if kind == "run":
        return f"<{rng.choice(RUN_LEAVES)}{extra}/>"
    if kind == "cond":
        return f"<Cond{rng.choice(CONDITION_PATTERNS)}{extra}/>"
    if kind == "const":
        return f"<{rng.choice(['AlwaysSuccess', 'AlwaysFailure'])}{extra}/>"
    if kind == "script":
        return f'<Script code="{_escape(_script(rng, vocabulary))}"{extra}/>'
    if kind == "script_condition":
        return f'<ScriptCondition code="{_escape(_condition_code(rng, vocabulary))}"{extra}/>'
    return (
        f'<SetBlackboard output_key="{rng.choice(COUNTERS)}" value="{rng.randint(0, 3)}"{extra}/>'
    )


def _node(rng: random.Random, vocabulary: Vocabulary, depth: int) -> str:
    if depth == 0 or rng.random() < 0.3:
        return _leaf(rng, vocabulary)
    extra = _attributes(rng, vocabulary)
    if rng.random() < 0.3:
        name = rng.choice(vocabulary.decorators)
        ports = {
            "Repeat": f' num_cycles="{rng.randint(1, 3)}"',
            "RetryUntilSuccessful": f' num_attempts="{rng.randint(1, 3)}"',
            "Precondition": f' if="{_escape(_condition_code(rng, vocabulary))}" '
            f'else="{rng.choice(["FAILURE", "SUCCESS", "SKIPPED"])}"',
        }.get(name, "")
        return f"<{name}{ports}{extra}>{_node(rng, vocabulary, depth - 1)}</{name}>"
    name = rng.choice(vocabulary.controls)
    count = {"IfThenElse": rng.randint(2, 3), "WhileDoElse": rng.randint(2, 3)}.get(
        name, rng.randint(1, 4)
    )
    ports = ""
    if name == "Parallel":
        ports = f' success_count="{rng.randint(1, count)}" failure_count="{rng.randint(1, count)}"'
    elif name == "ParallelAll":
        ports = f' max_failures="{rng.randint(1, count)}"'
    children = "".join(_node(rng, vocabulary, depth - 1) for _ in range(count))
    return f"<{name}{ports}{extra}>{children}</{name}>"


def random_tree(seed: int, vocabulary: Vocabulary, depth: int = 3) -> str:
    rng = random.Random(seed)
    body = _node(rng, vocabulary, depth)
    sub = ""
    if vocabulary.subtrees:
        called = _node(rng, dataclasses.replace(vocabulary, subtrees=False), depth - 1)
        sub = f'<BehaviorTree ID="Sub">{called}</BehaviorTree>'
    return (
        f'<root BTCPP_format="4" main_tree_to_execute="Main">'
        f'<BehaviorTree ID="Main">{body}</BehaviorTree>{sub}</root>'
    )


# --- running both -----------------------------------------------------------------------
@dataclass
class Tick:
    """What one tick did: root result (or the error), node statuses, counters."""

    root: str
    statuses: tuple[int, ...]
    counters: tuple[float, ...]


def _numbers(values) -> tuple[float, ...]:
    return tuple(float(v) for v in values)


LOAD_ERROR = [Tick("LOAD ERROR", (), ())]


def run_ours(xml: str, ticks: int, changes: dict | None = None) -> list[Tick]:
    """``changes``: counters set before a tick, by tick index."""
    try:
        tree = load_tree(xml, our_registry())
    except BTError:
        return LOAD_ERROR
    for counter in COUNTERS:
        tree.root_blackboard.set(counter, 0)
    nodes = [node for _, nodes in tree.instance_nodes() for node in nodes]
    result = []
    for index in range(ticks):
        for key, value in (changes or {}).get(index, {}).items():
            tree.root_blackboard.set(key, value)
        try:
            root = tree.tick(0.1 * index).name
        except BTError:
            root = "ERROR"
        result.append(
            Tick(
                root,
                tuple(int(node.status) for node in nodes),
                _numbers(tree.root_blackboard.get(c) for c in COUNTERS),
            )
        )
        if root == "ERROR":
            break
    return result


class BtcppRunner:
    """BT.CPP trees on one port pair, their statuses read as Groot2 reads them."""

    def __init__(self, port: int):
        self.port = port
        self.factory, self.memory = btcpp_factory()
        self.context = zmq.Context()
        self.socket = None

    def _request(self, kind: str, *frames: bytes) -> list[bytes]:
        self.socket.send_multipart([HEADER.pack(2, ord(kind), 1), *frames])
        return self.socket.recv_multipart()

    def run(self, xml: str, ticks: int, changes: dict | None = None) -> list[Tick]:
        for memory in self.memory:
            memory.clear()
        blackboard = btcpp.Blackboard.create()
        for counter in COUNTERS:
            blackboard.set_int(counter, 0)
        try:
            self.factory.register_behavior_tree_from_text(xml)
            tree = self.factory.create_tree("Main", blackboard)
        except RuntimeError:
            return LOAD_ERROR
        publisher = btcpp.Groot2Publisher(tree, self.port)
        self.socket = self.context.socket(zmq.REQ)
        self.socket.setsockopt(zmq.LINGER, 0)
        self.socket.setsockopt(zmq.RCVTIMEO, 5000)
        self.socket.connect(f"tcp://127.0.0.1:{self.port}")
        result = []
        try:
            for index in range(ticks):
                for key, value in (changes or {}).get(index, {}).items():
                    blackboard.set_int(key, value)
                try:
                    root = str(tree.tick_exactly_once()).rsplit(".", 1)[-1]
                except RuntimeError:
                    root = "ERROR"
                buffer = self._request("S")[1]
                codes = tuple(code if code < 10 else 0 for code in buffer[2::3])
                result.append(
                    Tick(
                        root,
                        codes,
                        _numbers(_btcpp_get(blackboard, c) for c in COUNTERS),
                    )
                )
                if root == "ERROR":
                    break
        finally:
            self.socket.close()
            del publisher
        return result

    def close(self):
        self.context.destroy(linger=0)


def _btcpp_get(blackboard, key: str) -> float:
    for getter in (blackboard.get_double, blackboard.get_int, blackboard.get_string):
        try:
            return float(getter(key))
        except (RuntimeError, ValueError, TypeError):
            continue
    return float("nan")


def first_difference(ours: list[Tick], theirs: list[Tick]) -> int | None:
    """The first tick at which the engines disagree (both failing with an error counts as
    agreeing: statuses are then half-way through a tick), or None."""
    for index, (mine, other) in enumerate(zip(ours, theirs, strict=False)):
        if mine != other and not mine.root == other.root == "ERROR":
            return index
    return None if len(ours) == len(theirs) else min(len(ours), len(theirs))
