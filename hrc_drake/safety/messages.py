"""What the SafetyMonitor reports: an abstract `safety_status` for behavior trees and
reports, and the vector `safety_signals` that loggers record for timelines, heat maps and
the run's safety log (safety.npz).

The status carries the current measurement and the run's running totals, so the status at
the end of a run is enough for its safety metrics.
"""

import dataclasses
import math
from dataclasses import dataclass

from hrc_drake.human.skeleton import REGIONS
from hrc_drake.safety.pfl import ContactAssessment
from hrc_drake.safety.sensors_reading import CLEAR
from hrc_drake.safety.sensors_view import SensorView
from hrc_drake.safety.ssm import FREE, NO_TERMS, ZONES, SsmTerms

NO_PART = ""


CARRIED = "carried object"
"""How reports name the robot part that is the object in its gripper."""


@dataclass(frozen=True)
class ViolationEpisode:
    """A stretch of updates in which the robot moved while closer than S_p; the pair,
    separation and S_p are those of its largest deficit."""

    start: float
    end: float
    region: str
    part: str
    separation: float
    protective: float

    @property
    def deficit(self) -> float:
        return self.protective - self.separation


@dataclass(frozen=True)
class ContactRecord:
    """One body region touching one robot part, from its first update to its last; the
    assessment is that of its worst update, `robot_moving` that of its first (who came
    into whom)."""

    start: float
    end: float
    worst: ContactAssessment
    robot_moving: bool
    violation: bool
    """over a limit at any update"""


@dataclass(frozen=True)
class SafetyTotals:
    """Running totals since the start of the run (times in seconds)."""

    min_separation: float = float("inf")
    min_separation_region: str = NO_PART
    min_separation_link: str = NO_PART
    min_separation_time: float = 0.0
    reduced_time: float = 0.0
    """the robot ran at a reduced SSM scale"""
    stopped_time: float = 0.0
    """the robot stood still in a monitored stop (braking into it not included)"""
    stops: int = 0
    violation_time: float = 0.0
    violation_episodes: tuple[ViolationEpisode, ...] = ()
    contact_time: float = 0.0
    contact_records: tuple[ContactRecord, ...] = ()

    @property
    def violations(self) -> int:
        return len(self.violation_episodes)

    @property
    def worst_deficit(self) -> float:
        """largest S_p minus separation while the robot moved (m)"""
        return max((e.deficit for e in self.violation_episodes), default=0.0)

    @property
    def contacts(self) -> int:
        return len(self.contact_records)

    @property
    def robot_contacts(self) -> int:
        """contacts that began while the robot moved"""
        return sum(r.robot_moving for r in self.contact_records)

    @property
    def contact_violations(self) -> int:
        return sum(r.violation for r in self.contact_records)

    @property
    def worst_contact(self) -> ContactRecord | None:
        return max(self.contact_records, key=lambda r: r.worst.severity, default=None)


@dataclass(frozen=True)
class SafetyStatus:
    """The monitor's view at its last update.

    `separation` is the smallest signed distance between any body region of the person
    and any robot part (link, tool, carried object), at `region` and `link`; `ssm` holds
    S_p there and its terms; `scale` is the speed scale sent to the robot (1 with SSM
    disabled). `violation` says the robot moves closer than S_p now; `contact` lists the
    body regions touched now, assessed with the energy-transfer model.
    """

    time: float = 0.0
    separation: float = float("inf")
    region: str = NO_PART
    link: str = NO_PART
    ssm: SsmTerms = NO_TERMS
    scale: float = 1.0
    safe_scale: float = 1.0
    zone: str = FREE
    walking_speed: float = 0.0
    """the person's pelvis along the floor (m/s)"""
    robot_speed: float = 0.0
    """fastest point of the robot (m/s)"""
    path_rate: float = 0.0
    """fraction of full speed the robot moves along its path"""
    human_approach: float = 0.0
    """measured speed of the person's closest point towards the robot, moving with its
    body region (m/s; 0 moving away)"""
    violation: bool = False
    contact: tuple[ContactAssessment, ...] = ()
    ssm_enabled: bool = True
    totals: SafetyTotals = SafetyTotals()
    sensing: tuple[SensorView, ...] | None = None
    """each safety sensor's view of the person, which the scale follows (None: no sensors,
    the monitor knows the person's body)"""
    sensed_protective: float = math.nan
    """S_p at the nearest detection, with that sensor's response time, C and Z_d (m)"""
    robot_parts: tuple = dataclasses.field(default=(), compare=False)
    """the robot's parts (links, tool, what it holds) as the monitor bounds them: capsules'
    starts and spans (parts × 3, world) and radii (what a person keeps out of while the
    robot stands still)"""

    @property
    def protective(self) -> float:
        """S_p (m)"""
        return self.ssm.total

    @property
    def approach_speed(self) -> float:
        """v_r: the robot's closest point towards the person (m/s)"""
        return self.ssm.v_r

    @property
    def sensed_separation(self) -> float:
        """m from the nearest detection of the person to the robot (inf: not seen; NaN:
        no sensors)"""
        if self.sensing is None:
            return math.nan
        return min((v.separation for v in self.sensing), default=math.inf)

    @property
    def seen(self) -> bool:
        """The person is seen: by a sensor, or always without sensors."""
        return self.sensing is None or math.isfinite(self.sensed_separation)

    @property
    def field(self) -> int:
        """The most urgent state of the sensors' active fields (sensors_reading.FIELD_STATES)."""
        return max((v.field_state for v in self.sensing or ()), default=CLEAR)

    def __deepcopy__(self, memo):
        return self  # immutable: Drake's state copies may share it

    def signals(self, person_xy: tuple[float, float], part_index: int) -> list[float]:
        """The `safety_signals` vector (order of SIGNALS); `part_index` numbers `link`
        among the monitor's part names."""
        separation = self.separation if math.isfinite(self.separation) else math.nan
        terms = self.ssm
        return [
            separation,
            terms.total,
            self.scale,
            self.robot_speed,
            terms.v_r,
            self.walking_speed,
            ZONES.index(self.zone),
            float(self.violation),
            float(bool(self.contact)),
            *person_xy,
            REGIONS.index(self.region) if self.region else -1,
            part_index,
            terms.v_h,
            self.human_approach,
            terms.stopping_time,
            terms.s_h,
            terms.s_r,
            terms.s_s,
            terms.margins,
            self.path_rate,
            self.safe_scale,
            self.time,
            _finite_or_nan(self.sensed_separation),
            self.sensed_protective,
            float(self.seen) if self.sensing is not None else math.nan,
            float(self.field) if self.sensing is not None else math.nan,
        ]


def _finite_or_nan(value: float) -> float:
    return value if math.isfinite(value) else math.nan


SIGNALS = (
    "separation",
    "protective",
    "scale",
    "robot_speed",
    "approach_speed",
    "walking_speed",
    "zone",
    "violation",
    "contact",
    "person_x",
    "person_y",
    "region",
    "part",
    "v_h",
    "human_approach",
    "stopping_time",
    "s_h",
    "s_r",
    "s_s",
    "margins",
    "path_rate",
    "safe_scale",
    "time",
    "sensed_separation",
    "sensed_protective",
    "seen",
    "field",
)
"""Entries of the `safety_signals` vector; `zone` is the index in ZONES, `region` in
REGIONS and `part` in the monitor's part names (-1: no person), flags are 0/1, and an
infinite separation (no person) is logged as NaN. `approach_speed` is v_r; `protective`
is S_p = s_h + s_r + s_s + margins (or ISO 13855's least distance). The person's speeds:
`walking_speed` their pelvis's along the floor, `human_approach` their closest body
region's towards the robot (0 moving away; v_h under the `measured` rule), `v_h` the speed
S_p assumed; `person_x`, `person_y` are where the pelvis is. `time` is when the
update measured them: a logger publishing at the monitor's period records the previous
update's values. With safety sensors, `sensed_separation` is from the nearest detection of the
person to the robot on the floor (NaN: not seen), `sensed_protective` S_p there, `seen` 1
while a sensor reports the person, `field` the most urgent field state (index in
`sensors_reading.FIELD_STATES`); all NaN without sensors."""
