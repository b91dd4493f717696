"""What a behavior tree node sees of the simulation: its agent, with statuses in and
commands out.

The BehaviorTreeSystem gives its tree one Agent (`tree.agent`). Before each tick it stores
the latest status of every source (hrc_drake.wiring.STATUS_SOURCES); nodes read them and
send commands to the actors the agent may command, numbered in the agent's own steps. After
the tick the system publishes the commands on its output ports. Named places of the
scenario (locations and areas) are resolved here, so trees can name them.
"""

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from pydrake.math import RigidTransform

from hrc_drake.areas import Area
from hrc_drake.messages import TaskEvent
from hrc_drake.tree_types import AreaRef, Pose
from hrc_drake.wiring import (
    COMMANDED_BY,
    HUMAN,
    ROBOT,
    SAFETY,
    SEQ_STEP,
    STATUS_SOURCES,
    WORKPIECES,
    first_seq,
    tree_issuer,
)


@dataclass
class Places:
    """The scenario's named locations and areas."""

    locations: dict[str, Pose] = field(default_factory=dict)
    areas: dict[str, Area] = field(default_factory=dict)


class Agent:
    """The tree's handle on its agent's world (see module docstring)."""

    def __init__(self, name: str, places: Places | None = None):
        self.name = name
        self.places = places or Places()
        self.commands = COMMANDED_BY[name]
        """The actors this agent may command, one outbox each."""
        self.statuses: dict[str, Any] = dict.fromkeys(STATUS_SOURCES)
        self.now = 0.0
        self.reset()

    def reset(self) -> None:
        self.next_seq = first_seq(self.name)
        self.outbox: dict[str, list] = {actor: [] for actor in self.commands}
        self.events: list[TaskEvent] = []
        self.called_sent: tuple[int, bool, float] | None = None
        """This tree's last SetCalledTo: its seq, the flag and when it was sent (IsCalled
        reads it until the person has taken it)."""

    @property
    def issuer(self) -> str:
        """How the actors name this agent's commands."""
        return tree_issuer(self.name)

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

    # commands ------------------------------------------------------------------------
    def send(self, actor: str, make_command: Callable[[int], Any]) -> int:
        """Queue `make_command(seq)` for `actor`; returns its sequence number. Trees are
        checked when they are loaded (hrc_drake.agent_trees), so an actor the agent may not
        command is a programming error here."""
        seq = self.next_seq
        self.next_seq += SEQ_STEP
        self.outbox[actor].append(make_command(seq))
        return seq

    def take_outbox(self) -> dict[str, list]:
        sent, self.outbox = self.outbox, {actor: [] for actor in self.commands}
        return sent

    def emit(self, event: str, value: str = "") -> None:
        self.events.append(TaskEvent(self.now, event, self.name, value))

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
