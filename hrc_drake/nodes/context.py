"""What a behavior tree node sees of the simulation: statuses in, commands out.

The BehaviorTreeSystem puts one AgentContext on its tree (`tree.context`). Before each
tick it stores the latest status messages of the actors it is wired to; nodes read them
and send commands, which get the system's next sequence number. After the tick the system
publishes the commands on its output ports. Named places of the scenario (locations and
areas) are resolved here, so trees can name them.
"""

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from pydrake.math import RigidTransform

from hrc_drake.areas import Area
from hrc_drake.messages import TaskEvent
from hrc_drake.tree_types import AreaRef, Pose

ROBOT = "robot"
HUMAN = "human"
WORKPIECES = "workpieces"
SAFETY = "safety"
ACTORS = (ROBOT, HUMAN, WORKPIECES)
"""Actors a tree commands; each has a command output and a status input."""
STATUS_INPUTS = (ROBOT, HUMAN, WORKPIECES, SAFETY)


@dataclass
class Places:
    """The scenario's named locations and areas."""

    locations: dict[str, Pose] = field(default_factory=dict)
    areas: dict[str, Area] = field(default_factory=dict)


class AgentContext:
    """The tree's handle on its agent's world (see module docstring)."""

    def __init__(self, agent: str, places: Places, seq_start: int = 1, seq_step: int = 1):
        self.agent = agent
        self.places = places
        self.seq_start = seq_start
        self.seq_step = seq_step
        self.statuses: dict[str, Any] = dict.fromkeys(STATUS_INPUTS)
        self.now = 0.0
        self.reset()

    def reset(self) -> None:
        self.next_seq = self.seq_start
        self.outbox: dict[str, list] = {actor: [] for actor in ACTORS}
        self.events: list[TaskEvent] = []

    # statuses ------------------------------------------------------------------------
    @property
    def robot(self):
        return self.statuses[ROBOT]

    @property
    def human(self):
        return self.statuses[HUMAN]

    @property
    def workpieces(self):
        return self.statuses[WORKPIECES]

    @property
    def safety(self):
        return self.statuses[SAFETY]

    @property
    def workpieces_issuer(self) -> str:
        """This agent's name towards the Workpieces system, which answers per issuer."""
        return f"{self.agent}_tree"

    # commands ------------------------------------------------------------------------
    def send(self, actor: str, make_command: Callable[[int], Any]) -> int:
        """Queue `make_command(seq)` for `actor`; returns its sequence number."""
        seq = self.next_seq
        self.next_seq += self.seq_step
        self.outbox[actor].append(make_command(seq))
        return seq

    def take_outbox(self) -> dict[str, list]:
        sent, self.outbox = self.outbox, {actor: [] for actor in ACTORS}
        return sent

    def emit(self, event: str, value: str = "") -> None:
        self.events.append(TaskEvent(self.now, event, self.agent, value))

    # places --------------------------------------------------------------------------
    def resolve_pose(self, pose: Pose) -> Pose:
        """The pose with a location name replaced by the scenario's location."""
        if not pose.name:
            return pose
        if pose.name not in self.places.locations:
            raise KeyError(f"unknown location '{pose.name}'")
        return self.places.locations[pose.name]

    def transform(self, pose: Pose) -> RigidTransform:
        """A pose port's value in the world (identity rotation when it has none)."""
        return self.resolve_pose(pose).to_transform()

    def area(self, area: Area | AreaRef) -> Area:
        if isinstance(area, AreaRef):
            if area.name not in self.places.areas:
                raise KeyError(f"unknown area '{area.name}'")
            return self.places.areas[area.name]
        return area

    def in_area(self, xy, area: Area | AreaRef) -> bool:
        return self.area(area).contains(np.asarray(xy)[:2])
