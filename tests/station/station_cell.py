"""The small test cell (`cell.yaml`) with trees from `trees/` for its agents, and its
station simulated step by step: what the whole-station tests build on."""

import dataclasses
from pathlib import Path

from pydrake.systems.analysis import Simulator

from hrc_drake.agent_trees import AgentTree
from hrc_drake.builder import build_diagram
from hrc_drake.scenario import load_scenario

HERE = Path(__file__).resolve().parent


def cell(robot: str | None = None, human: str | None = None, person: bool = True):
    """The test cell with the given tree files (names in trees/) for its agents."""
    scenario = load_scenario(HERE / "cell.yaml")
    trees = {"robot": robot, "human": human}
    scenario.trees = {agent: AgentTree(str(HERE / "trees" / f)) for agent, f in trees.items() if f}
    return scenario if person else dataclasses.replace(scenario, human=None)


class Simulation:
    """A scenario's station simulated step by step, with its outputs at hand."""

    def __init__(self, scenario):
        parts = []
        self.diagram = build_diagram(scenario, attach=lambda _, station: parts.append(station))
        self.station = parts[0]  # its parts (hrc_drake.builder.Station)
        self.simulator = Simulator(self.diagram)
        self.simulator.Initialize()

    def advance(self, t: float) -> "Simulation":
        self.simulator.AdvanceTo(t)
        return self

    def __getitem__(self, port: str):
        return self.diagram.GetOutputPort(port).Eval(self.simulator.get_context())

    def events(self, agent: str) -> list[str]:
        return [e.name for e in self[f"{agent}_task_events"]]

    def tree(self, agent: str):
        return self.station.trees[agent].tree
