"""What a run recorded: `hrc_drake.runner.simulate` returns a `RunRecord`, and
`hrc_drake.evaluation.report` turns it into report.json's metrics and the run directory's
files. The record is data (arrays, final statuses, events); only the diagram (for
diagram.svg) and the Meshcat the replay was drawn in (for replay.html's scene) are Drake
objects.
"""

from dataclasses import dataclass, field

import numpy as np
from pydrake.geometry import Meshcat
from pydrake.systems.framework import Diagram

from hrc_drake.ergonomics.config import ErgonomicsOptions
from hrc_drake.evaluation.realism import AuditState
from hrc_drake.evaluation.recording import Recording
from hrc_drake.messages import TaskEvent
from hrc_drake.safety.config import SafetyConfig
from hrc_drake.safety.messages import SafetyStatus
from hrc_drake.workpieces.messages import HeldObject


@dataclass(frozen=True)
class RunSetup:
    """What the run was asked to be, as far as its evaluation needs it (the runner takes it
    from the scenario)."""

    scenario: str
    seed: int
    duration: float
    time_step: float
    robot_variant: str
    initial_positions: tuple[float, ...]
    """rad: the arm's joint positions at the start"""
    safety: SafetyConfig
    """the monitor's settings (whether or not the station has a monitor)"""
    command_latency: float
    """s: the robot's command update period, part of S_p's reaction time"""
    ergonomics: ErgonomicsOptions = field(default_factory=ErgonomicsOptions)


@dataclass(frozen=True, eq=False)
class PersonRecord:
    """The person's body over the run, for the ergonomic scores: their size, their joint
    positions (the kinematic plant's q, one column per time, every `ergonomics.period`)
    and from which times their hands held what."""

    height: float
    mass: float
    times: np.ndarray
    positions: np.ndarray
    holds: list[tuple[float, tuple[HeldObject, ...]]]
    """Known by identity (eq=False): its evaluation is computed once per record."""


@dataclass(frozen=True)
class Footprint:
    """A piece of the cell's furniture seen from above: its name and the corners of its
    floor outline (x, y in m), as the person's navigation map walks round it."""

    name: str
    outline: tuple[tuple[float, float], ...]


@dataclass(frozen=True)
class Fault:
    """A tree fault that stopped the run early: when, and the tree's own message (file,
    line, node and port)."""

    time: float
    error: str


@dataclass
class RunRecord:
    """Everything a run recorded (see the module docstring); None where the station had no
    such part (no monitor, no person, no replay recorder)."""

    setup: RunSetup
    versions: dict[str, str]
    """of the software that ran it: hrc_drake and drake"""
    robot_times: np.ndarray
    robot_states: np.ndarray
    """the arm's state (joint positions, then velocities) at each of `robot_times`"""
    signal_times: np.ndarray
    signals: np.ndarray | None
    """the monitor's `safety_signals` (hrc_drake.safety.messages.SIGNALS x samples)"""
    safety_parts: tuple[str, ...]
    """the robot parts the `part` safety signal numbers"""
    safety_status: SafetyStatus | None
    """the monitor's status at the end of the run (its totals)"""
    realism: AuditState | None
    """the realism audit at the end of the run (the objects' alone without a person; None
    with neither a person nor objects)"""
    events: list[TaskEvent]
    """every tree's task events, by time"""
    event_names: tuple[str, ...]
    """the task events the trees' Emit nodes name, counted even where none happened"""
    states: dict[str, list[tuple[float, str]]]
    """per actor (and tree), the (time, state) at which its state changed"""
    node_statistics: dict[str, dict]
    """per agent, per node path: ticks, successes, failures, time running, first failure"""
    recording: Recording | None
    """what replay.html animates"""
    furniture: tuple[Footprint, ...]
    """the cell's furniture the person walks round (none without a person)"""
    person: PersonRecord | None
    meshcat: Meshcat | None
    diagram: Diagram
    fault: Fault | None
    wall_time: float
    """s of wall-clock time the simulation took (never written to the report)"""
