"""BehaviorTreeSystem: one agent's behavior tree, ticked on simulation time inside the Diagram.

Each period an unrestricted update reads the actors' status ports, ticks the tree with the
simulation time as its clock, and stores the commands the nodes sent. The command outputs
are computed from that state only (no feedthrough), so a command sent at tick k reaches its
actor at the actor's next update.

A command port carries the recent commands of this tree (`RECENT_COMMANDS`), oldest first,
each with its sequence number: an actor acts on every command newer than the last one it saw, so two
commands sent to one actor in the same tick (SetRobotVelocity, then RobotMove) both arrive.

The tree object lives in the system, not in the Context: the initialization event resets
it (blackboard and node memory) and gives it a fresh Generator from the run's seed, so
every simulation started from a new Context replays identically.
"""

from dataclasses import dataclass

import numpy as np
from pydrake.common.value import AbstractValue
from pydrake.systems.framework import LeafSystem

from hrc_drake.bt import NodeCounters, Status, Tree
from hrc_drake.messages import RECENT_COMMANDS, TaskEvent
from hrc_drake.nodes.agent import Agent
from hrc_drake.ports import message_value, value_or_none
from hrc_drake.wiring import STATUS_SOURCES, command_output, status_port


@dataclass(frozen=True)
class TreeStatus:
    """What the agent is doing: the root's status and the deepest running node."""

    agent: str
    time: float
    root_status: str
    running_path: str
    ticks: int


@dataclass(frozen=True)
class TreeOutputs:
    """The system's state: what its output ports publish."""

    commands: dict[str, tuple]
    status: TreeStatus
    events: tuple[TaskEvent, ...]

    def __deepcopy__(self, memo):
        return self  # immutable: Drake's state copies may share it


class BehaviorTreeSystem(LeafSystem):
    """Ticks `tree` every `period` seconds (see module docstring).

    Inputs (abstract, each optional): `<source>_status` for every status source (robot,
    human, workpieces, safety). Outputs (abstract): `<actor>_command` for every actor the
    agent may command (tuples of recent commands), tree_status (TreeStatus), task_events
    (all TaskEvents).
    """

    def __init__(self, tree: Tree, agent: Agent, seed: np.random.SeedSequence, period: float):
        super().__init__()
        self.tree = tree
        self.agent = agent
        self.tree.agent = agent
        self.seed = seed
        self.counters = NodeCounters()
        self.tree.add_observer(self.counters)
        self._inputs = {
            source: self.DeclareAbstractInputPort(status_port(source), message_value())
            for source in STATUS_SOURCES
        }
        self._state = self.DeclareAbstractState(AbstractValue.Make(self._initial_outputs()))
        for actor in agent.commands:
            self._declare_state_view(
                command_output(actor), (), lambda out, a=actor: out.commands[a]
            )
        initial_status = self._initial_outputs().status
        self._declare_state_view("tree_status", initial_status, lambda out: out.status)
        self._declare_state_view("task_events", (), lambda out: out.events)
        self.DeclareInitializationUnrestrictedUpdateEvent(self._initialize)
        self.DeclarePeriodicUnrestrictedUpdateEvent(period, 0.0, self._tick)

    def _initial_outputs(self) -> TreeOutputs:
        status = TreeStatus(self.agent.name, 0.0, Status.IDLE.name, "", 0)
        return TreeOutputs({actor: () for actor in self.agent.commands}, status, ())

    def _initialize(self, context, state) -> None:
        self.tree.reset(rng=np.random.default_rng(self.seed))
        self.agent.reset()
        self.counters.reset()
        state.get_mutable_abstract_state(self._state).set_value(self._initial_outputs())

    def _tick(self, context, state) -> None:
        agent = self.agent
        for source, port in self._inputs.items():
            agent.statuses[source] = value_or_none(port, context)
        agent.now = context.get_time()
        previous = context.get_abstract_state(self._state).get_value()
        root_status = self.tree.tick(agent.now)
        state.get_mutable_abstract_state(self._state).set_value(
            TreeOutputs(
                commands=self._updated_commands(previous.commands, agent.take_outbox()),
                status=TreeStatus(
                    agent.name,
                    agent.now,
                    root_status.name,
                    self._running_path(),
                    previous.status.ticks + 1,
                ),
                events=tuple(agent.events),
            )
        )

    @staticmethod
    def _updated_commands(previous: dict[str, tuple], sent: dict[str, list]) -> dict:
        return {
            actor: (previous[actor] + tuple(sent[actor]))[-RECENT_COMMANDS:]
            if sent[actor]
            else previous[actor]
            for actor in previous
        }

    def _running_path(self) -> str:
        """The last running node in pre-order: the leaf the agent is busy with."""
        running = (node for node in reversed(self.tree.node_list) if node.status is Status.RUNNING)
        return next((node.path for node in running), "")

    def _declare_state_view(self, name: str, model, extract) -> None:
        """An output port publishing one part of the state (never the inputs)."""
        self.DeclareAbstractOutputPort(
            name,
            lambda: AbstractValue.Make(model),
            lambda context, output: output.set_value(
                extract(context.get_abstract_state(self._state).get_value())
            ),
            prerequisites_of_calc={self.abstract_state_ticket(self._state)},
        )
