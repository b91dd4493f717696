"""The revised NIOSH lifting equation (Waters, Putz-Anderson, Garg & Fine, Ergonomics 36,
1993, 749-776; the NIOSH Applications Manual, DHHS (NIOSH) Publication 94-110, 1994):
the recommended weight limit RWL = LC x HM x VM x DM x AM x FM x CM of a lift at its origin
or destination, with the manual's frequency (Table 5) and coupling (Table 7) multipliers
and its rules for values out of range, and the lifting index LI = load / RWL.

The equation comes in metric and US customary units with their own constants (`METRIC`,
`US`); the manual's worked examples are in inches and pounds.
"""

import bisect
import math
from dataclasses import dataclass

from hrc_drake.workpieces.messages import COUPLINGS


@dataclass(frozen=True)
class Units:
    """The equation's constants in one system of units (lengths, then mass)."""

    load_constant: float
    horizontal: tuple[float, float]
    """H below the first counts as the first (HM = 1); beyond the second HM = 0"""
    vertical_optimum: float
    vertical_factor: float
    vertical_limit: float
    """V above it: VM = 0"""
    distance_factor: float
    distance: tuple[float, float]
    """D below the first counts as the first (DM = 1); beyond the second DM = 0"""
    frequency_split: float
    """The frequency table's and the coupling table's V < 75 cm (30 in) column"""
    length_per_metre: float


METRIC = Units(23.0, (25.0, 63.0), 75.0, 0.003, 175.0, 4.5, (25.0, 175.0), 75.0, 100.0)
"""kg and cm"""
US = Units(51.0, (10.0, 25.0), 30.0, 0.0075, 70.0, 1.8, (10.0, 70.0), 30.0, 100.0 / 2.54)
"""lb and in"""

ASYMMETRY_LIMIT = 135.0
"""degrees: beyond it AM = 0"""
LOWEST_FREQUENCY = 0.2
"""lifts/min: less often than once in 5 minutes counts as 0.2"""

SHORT, MODERATE, LONG = "short", "moderate", "long"
DURATIONS = (SHORT, MODERATE, LONG)
"""Work duration: up to 1 h, 1-2 h, 2-8 h (each followed by enough recovery time)."""

FREQUENCIES = (0.2, 0.5, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15)
# Table 5 of the Applications Manual: per frequency, (V < 30 in, V >= 30 in) for short,
# moderate and long work durations.
FREQUENCY_TABLE = (
    ((1.00, 1.00), (0.95, 0.95), (0.85, 0.85)),
    ((0.97, 0.97), (0.92, 0.92), (0.81, 0.81)),
    ((0.94, 0.94), (0.88, 0.88), (0.75, 0.75)),
    ((0.91, 0.91), (0.84, 0.84), (0.65, 0.65)),
    ((0.88, 0.88), (0.79, 0.79), (0.55, 0.55)),
    ((0.84, 0.84), (0.72, 0.72), (0.45, 0.45)),
    ((0.80, 0.80), (0.60, 0.60), (0.35, 0.35)),
    ((0.75, 0.75), (0.50, 0.50), (0.27, 0.27)),
    ((0.70, 0.70), (0.42, 0.42), (0.22, 0.22)),
    ((0.60, 0.60), (0.35, 0.35), (0.18, 0.18)),
    ((0.52, 0.52), (0.30, 0.30), (0.00, 0.15)),
    ((0.45, 0.45), (0.26, 0.26), (0.00, 0.13)),
    ((0.41, 0.41), (0.00, 0.23), (0.00, 0.00)),
    ((0.37, 0.37), (0.00, 0.21), (0.00, 0.00)),
    ((0.00, 0.34), (0.00, 0.00), (0.00, 0.00)),
    ((0.00, 0.31), (0.00, 0.00), (0.00, 0.00)),
    ((0.00, 0.28), (0.00, 0.00), (0.00, 0.00)),
)
# Table 7: per coupling (good, fair, poor), (V < 30 in, V >= 30 in).
COUPLING_TABLE = ((1.00, 1.00), (0.95, 1.00), (0.90, 0.90))


def duration_category(hours: float) -> str:
    return SHORT if hours <= 1.0 else MODERATE if hours <= 2.0 else LONG


def horizontal_multiplier(h: float, units: Units = METRIC) -> float:
    low, high = units.horizontal
    return 0.0 if h > high else low / max(h, low)


def vertical_multiplier(v: float, units: Units = METRIC) -> float:
    if v > units.vertical_limit or v < 0:
        return 0.0
    return 1.0 - units.vertical_factor * abs(v - units.vertical_optimum)


def distance_multiplier(d: float, units: Units = METRIC) -> float:
    low, high = units.distance
    return 0.0 if d > high else 0.82 + units.distance_factor / max(d, low)


def asymmetry_multiplier(a: float) -> float:
    """`a` in degrees."""
    return 0.0 if abs(a) > ASYMMETRY_LIMIT else 1.0 - 0.0032 * abs(a)


def frequency_multiplier(frequency: float, duration: str, v: float, units: Units = METRIC):
    """Table 5, interpolated linearly between the frequencies it lists; above 15 lifts/min
    FM = 0."""
    column = DURATIONS.index(duration)
    high_v = int(v >= units.frequency_split)
    f = max(frequency, LOWEST_FREQUENCY)
    if f > FREQUENCIES[-1]:
        return 0.0
    i = bisect.bisect_left(FREQUENCIES, f)
    upper = FREQUENCY_TABLE[i][column][high_v]
    if FREQUENCIES[i] == f:
        return upper
    lower = FREQUENCY_TABLE[i - 1][column][high_v]
    share = (f - FREQUENCIES[i - 1]) / (FREQUENCIES[i] - FREQUENCIES[i - 1])
    return lower + share * (upper - lower)


def coupling_multiplier(coupling: str, v: float, units: Units = METRIC) -> float:
    """Table 7 for a good, fair or poor coupling (REBA's `unacceptable` counts as poor)."""
    row = COUPLINGS.index(coupling) if coupling in COUPLINGS else len(COUPLINGS) - 1
    return COUPLING_TABLE[row][int(v >= units.frequency_split)]


@dataclass(frozen=True)
class LiftPoint:
    """Where the hands are at a lift's origin or destination: H (horizontal distance from
    the midpoint between the ankles), V (height above the floor), in the units' lengths,
    and A the asymmetry angle in degrees."""

    h: float
    v: float
    a: float


@dataclass(frozen=True)
class Multipliers:
    hm: float
    vm: float
    dm: float
    am: float
    fm: float
    cm: float

    @property
    def product(self) -> float:
        return self.hm * self.vm * self.dm * self.am * self.fm * self.cm


def multipliers(
    point: LiftPoint,
    distance: float,
    frequency: float,
    duration: str,
    coupling: str,
    units: Units = METRIC,
) -> Multipliers:
    """The six multipliers at one end of a lift of vertical travel `distance`."""
    return Multipliers(
        hm=horizontal_multiplier(point.h, units),
        vm=vertical_multiplier(point.v, units),
        dm=distance_multiplier(distance, units),
        am=asymmetry_multiplier(point.a),
        fm=frequency_multiplier(frequency, duration, point.v, units),
        cm=coupling_multiplier(coupling, point.v, units),
    )


def recommended_weight_limit(factors: Multipliers, units: Units = METRIC) -> float:
    return units.load_constant * factors.product


def lifting_index(load: float, rwl: float) -> float:
    """load / RWL; infinite where a multiplier is 0 (the lift is out of the equation's
    range: no load is recommended)."""
    return load / rwl if rwl > 0 else math.inf


def out_of_range(
    point: LiftPoint, distance: float, frequency: float, units: Units = METRIC
) -> list[str]:
    """What of a lift's end lies beyond the equation's range (a multiplier is 0 there)."""
    notes = []
    if point.h > units.horizontal[1]:
        notes.append("H beyond the reach limit")
    if point.v > units.vertical_limit or point.v < 0:
        notes.append("V out of range")
    if distance > units.distance[1]:
        notes.append("D beyond range")
    if abs(point.a) > ASYMMETRY_LIMIT:
        notes.append("A beyond 135 degrees")
    if frequency > FREQUENCIES[-1]:
        notes.append("more than 15 lifts a minute")
    return notes
