"""Watch a simulation's behavior trees live in Groot2 (or btview): one Groot2 server per
BehaviorTreeSystem of a Diagram, the robot's first.

    servers = serve_groot(diagram)          # robot on 127.0.0.1:1667, the person on 1669
    print(servers)                          # which tree is on which port
    simulator.set_target_realtime_rate(1.0)
    simulator.AdvanceTo(60.0)
    servers.close()

``hrc-drake run SCENARIO --groot`` does the same for a run. Each server takes two ports
(requests on PORT, breakpoint notifications on PORT + 1); the robot's tree gets PORT, every
other tree the next free pair after it.
"""

from __future__ import annotations

from pydrake.systems.analysis import Simulator
from pydrake.systems.framework import Diagram, EventStatus

from hrc_drake.bt.groot2 import DEFAULT_PORT, Groot2Server, ServeError
from hrc_drake.systems.behavior_tree import BehaviorTreeSystem
from hrc_drake.wiring import ROBOT

LOCALHOST = "127.0.0.1"
PAIRS_TRIED = 16
"""Port pairs tried after the robot's for each further tree before giving up."""


class GrootServers:
    """The servers of one Diagram's trees, by agent; close them when the run ends."""

    def __init__(self, servers: dict[str, Groot2Server]):
        self.servers = servers

    def __str__(self) -> str:
        return "\n".join(
            f"Groot2: {agent} tree '{server.tree.id}' on {server.address} "
            f"(breakpoints published on {server.port + 1})"
            for agent, server in self.servers.items()
        )

    def keep_pace(self, simulator: Simulator) -> None:
        """After a breakpoint held a paced simulation, pace it anew from where it stands
        (else Drake's real-time pacing would run flat out to make up the pause). Call it
        after ``set_target_realtime_rate``; it takes the simulator's monitor. An unpaced
        simulator is left alone."""
        if simulator.get_target_realtime_rate() <= 0:
            return

        def resume_after_pause(context):
            paused = [server for server in self.servers.values() if server.paused]
            if paused:
                for server in paused:
                    server.paused = False
                simulator.ResetStatistics()
            return EventStatus.DidNothing()

        simulator.set_monitor(resume_after_pause)

    def close(self) -> None:
        for server in self.servers.values():
            server.close()

    def __enter__(self) -> GrootServers:
        return self

    def __exit__(self, *exc) -> None:
        self.close()


def tree_systems(diagram: Diagram) -> dict[str, BehaviorTreeSystem]:
    """Every BehaviorTreeSystem in the diagram (nested diagrams too), the robot's first."""
    found: dict[str, BehaviorTreeSystem] = {}
    pending = [diagram]
    while pending:
        for system in pending.pop().GetSystems():
            if isinstance(system, BehaviorTreeSystem):
                found[system.agent.name] = system
            elif isinstance(system, Diagram):
                pending.append(system)
    return dict(sorted(found.items(), key=lambda item: item[0] != ROBOT))


def serve_groot(diagram: Diagram, port: int = DEFAULT_PORT, host: str = LOCALHOST) -> GrootServers:
    """Start a Groot2 server for each tree of ``diagram`` (see the module docstring).
    Raises ServeError, with nothing left open, if the robot's port pair is taken or out of
    range, or no free pair follows it for another tree."""
    servers: dict[str, Groot2Server] = {}
    try:
        for agent, system in tree_systems(diagram).items():
            servers[agent] = _serve_next(system, port if not servers else None, servers, host)
    except ServeError:
        GrootServers(servers).close()
        raise
    return GrootServers(servers)


def _serve_next(system, port: int | None, servers: dict, host: str) -> Groot2Server:
    """On ``port``, or on the first free pair after the last server's."""
    if port is not None:
        return Groot2Server(system.tree, port, host)
    after = max(server.port for server in servers.values())
    for candidate in range(after + 2, after + 2 + 2 * PAIRS_TRIED, 2):
        try:
            return Groot2Server(system.tree, candidate, host)
        except ServeError as error:
            last = error
    raise last
