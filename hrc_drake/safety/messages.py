"""What the SafetyMonitor reports: an abstract `safety_status` for behavior trees and
reports, and the vector `safety_signals` that loggers record for timelines and heat maps.

The status carries the current measurement and the run's running totals, so the status at
the end of a run is enough for its safety metrics.
"""

import math
from dataclasses import dataclass

from hrc_drake.safety.pfl import ContactAssessment
from hrc_drake.safety.ssm import FREE, ZONES

NO_PART = ""


CARRIED = "carried object"
"""How reports name the robot part that is the object in its gripper."""


@dataclass(frozen=True)
class SafetyTotals:
    """Running totals since the start of the run (times in seconds)."""

    min_separation: float = float("inf")
    min_separation_region: str = NO_PART
    min_separation_link: str = NO_PART
    min_separation_time: float = 0.0
    reduced_time: float = 0.0
    stopped_time: float = 0.0
    stops: int = 0
    violations: int = 0
    violation_time: float = 0.0
    worst_deficit: float = 0.0
    """largest S_p minus separation while the robot moved (m)"""
    contacts: int = 0
    contact_time: float = 0.0
    contact_violations: int = 0
    worst_contact: ContactAssessment | None = None


@dataclass(frozen=True)
class SafetyStatus:
    """The monitor's view at its last update.

    `separation` is the smallest signed distance between any body region of the person
    and any robot part (link, tool, carried object), at `region` and `link`; `protective`
    is S_p there; `scale` is the speed scale sent to the robot (1 with SSM disabled).
    `violation` says the robot moves closer than S_p now; `contact` lists the body regions
    touched now, assessed with the energy-transfer model.
    """

    time: float = 0.0
    separation: float = float("inf")
    region: str = NO_PART
    link: str = NO_PART
    protective: float = 0.0
    scale: float = 1.0
    safe_scale: float = 1.0
    zone: str = FREE
    human_speed: float = 0.0
    robot_speed: float = 0.0
    """fastest point of the robot (m/s)"""
    approach_speed: float = 0.0
    """speed of the robot's closest point towards the person (m/s)"""
    violation: bool = False
    contact: tuple[ContactAssessment, ...] = ()
    ssm_enabled: bool = True
    totals: SafetyTotals = SafetyTotals()

    def __deepcopy__(self, memo):
        return self  # immutable: Drake's state copies may share it

    def signals(self, person_xy: tuple[float, float]) -> list[float]:
        """The `safety_signals` vector (order of SIGNALS)."""
        separation = self.separation if math.isfinite(self.separation) else math.nan
        return [
            separation,
            self.protective,
            self.scale,
            self.robot_speed,
            self.approach_speed,
            self.human_speed,
            ZONES.index(self.zone),
            float(self.violation),
            float(bool(self.contact)),
            *person_xy,
        ]


SIGNALS = (
    "separation",
    "protective",
    "scale",
    "robot_speed",
    "approach_speed",
    "human_speed",
    "zone",
    "violation",
    "contact",
    "person_x",
    "person_y",
)
"""Entries of the `safety_signals` vector; `zone` is the index in ZONES, flags are 0/1, and
an infinite separation (no person) is logged as NaN."""
