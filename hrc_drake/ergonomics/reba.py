"""REBA, the Rapid Entire Body Assessment (Hignett & McAtamney, Applied Ergonomics 31,
2000, 201-205): body-part scores from posture angles, Tables A, B and C of the paper, the
load, coupling and activity scores and the risk levels.

Angles are in degrees, read to the whole degree (`hrc_drake.ergonomics.rula.whole_degrees`).
"""

from dataclasses import dataclass

from hrc_drake.ergonomics.rula import lower_arm_position, upper_arm_position, whole_degrees

# Table A: trunk 1-5 (rows), neck 1-3 x legs 1-4 (columns).
TABLE_A = (
    (1, 2, 3, 4, 1, 2, 3, 4, 3, 3, 5, 6),
    (2, 3, 4, 5, 3, 4, 5, 6, 4, 5, 6, 7),
    (2, 4, 5, 6, 4, 5, 6, 7, 5, 6, 7, 8),
    (3, 5, 6, 7, 5, 6, 7, 8, 6, 7, 8, 9),
    (4, 6, 7, 8, 6, 7, 8, 9, 7, 8, 9, 9),
)
# Table B: upper arm 1-6 (rows), lower arm 1-2 x wrist 1-3 (columns).
TABLE_B = (
    (1, 2, 2, 1, 2, 3),
    (1, 2, 3, 2, 3, 4),
    (3, 4, 5, 4, 5, 5),
    (4, 5, 5, 5, 6, 7),
    (6, 7, 8, 7, 8, 8),
    (7, 8, 8, 8, 9, 9),
)
# Table C: score A 1-12 (rows), score B 1-12 (columns).
TABLE_C = (
    (1, 1, 1, 2, 3, 3, 4, 5, 6, 7, 7, 7),
    (1, 2, 2, 3, 4, 4, 5, 6, 6, 7, 7, 8),
    (2, 3, 3, 3, 4, 5, 6, 7, 7, 8, 8, 8),
    (3, 4, 4, 4, 5, 6, 7, 8, 8, 9, 9, 9),
    (4, 4, 4, 5, 6, 7, 8, 8, 9, 9, 9, 9),
    (6, 6, 6, 7, 8, 8, 9, 9, 10, 10, 10, 10),
    (7, 7, 7, 8, 9, 9, 9, 10, 10, 11, 11, 11),
    (8, 8, 8, 9, 10, 10, 10, 10, 10, 11, 11, 11),
    (9, 9, 9, 10, 10, 10, 11, 11, 11, 12, 12, 12),
    (10, 10, 10, 11, 11, 11, 11, 12, 12, 12, 12, 12),
    (11, 11, 11, 11, 12, 12, 12, 12, 12, 12, 12, 12),
    (12, 12, 12, 12, 12, 12, 12, 12, 12, 12, 12, 12),
)

LOAD_LIMITS = (5.0, 10.0)
"""kg: the load/force score's bands (below 5 kg, 5-10 kg, above 10 kg)."""
COUPLINGS = ("good", "fair", "poor", "unacceptable")
"""The coupling score is the index in this tuple."""


def trunk_score(flexion: float, twisted: bool = False, side_bent: bool = False) -> int:
    """`flexion` from upright (negative: extension)."""
    a = whole_degrees(flexion)
    if a == 0:
        base = 1
    elif -20 <= a <= 20:
        base = 2
    elif a < -20 or a <= 60:
        base = 3
    else:
        base = 4
    return base + (twisted or side_bent)


def neck_score(flexion: float, twisted: bool = False, side_bent: bool = False) -> int:
    """`flexion` from the trunk (negative: extension, which scores 2)."""
    a = whole_degrees(flexion)
    return (1 if 0 <= a <= 20 else 2) + (twisted or side_bent)


def legs_score(bilateral: bool, knee_flexion: float) -> int:
    """1 for bilateral weight bearing (standing, walking, sitting), 2 on one leg or an
    unstable posture; +1 with the knees flexed 30-60 degrees, +2 beyond 60."""
    knee = whole_degrees(knee_flexion)
    return (1 if bilateral else 2) + (2 if knee > 60 else 1 if knee >= 30 else 0)


def upper_arm_score(
    flexion: float, abducted_or_rotated: bool = False, raised: bool = False, supported: bool = False
) -> int:
    """`flexion` forward of the trunk (negative: extension); supported or gravity-assisted
    -1."""
    return max(1, upper_arm_position(flexion) + abducted_or_rotated + raised - supported)


def lower_arm_score(flexion: float) -> int:
    return lower_arm_position(flexion)


def wrist_score(flexion: float, deviated_or_twisted: bool = False) -> int:
    a = abs(whole_degrees(flexion))
    return (1 if a <= 15 else 2) + deviated_or_twisted


def load_score(load: float, shock: bool = False) -> int:
    """`load` in kg; +1 for a shock or a rapid build-up of force."""
    low, high = LOAD_LIMITS
    return (0 if load < low else 1 if load <= high else 2) + shock


def coupling_score(coupling: str) -> int:
    return COUPLINGS.index(coupling)


def activity_score(static: bool, repeated: bool, rapid_change: bool) -> int:
    """+1 each: a body part held static longer than a minute; small-range actions repeated
    more than 4 times a minute; rapid large changes of posture or an unstable base."""
    return int(static) + int(repeated) + int(rapid_change)


@dataclass(frozen=True)
class RebaParts:
    """The body-part, load, coupling and activity scores of one side."""

    trunk: int
    neck: int
    legs: int
    upper_arm: int
    lower_arm: int
    wrist: int
    load: int = 0
    coupling: int = 0
    activity: int = 0


def score_a(trunk: int, neck: int, legs: int) -> int:
    return TABLE_A[min(trunk, 5) - 1][4 * (min(neck, 3) - 1) + min(legs, 4) - 1]


def score_b(upper_arm: int, lower_arm: int, wrist: int) -> int:
    return TABLE_B[min(upper_arm, 6) - 1][3 * (min(lower_arm, 2) - 1) + min(wrist, 3) - 1]


def reba_score(parts: RebaParts) -> int:
    """Table C of score A (Table A + load) and score B (Table B + coupling), plus the
    activity score."""
    a = score_a(parts.trunk, parts.neck, parts.legs) + parts.load
    b = score_b(parts.upper_arm, parts.lower_arm, parts.wrist) + parts.coupling
    return TABLE_C[min(a, 12) - 1][min(b, 12) - 1] + parts.activity


RISK_LEVELS = ("negligible", "low", "medium", "high", "very high")


def risk_level(score: int) -> str:
    """Negligible (1), low (2-3), medium (4-7), high (8-10), very high (11-15)."""
    if score <= 1:
        return RISK_LEVELS[0]
    if score <= 3:
        return RISK_LEVELS[1]
    if score <= 7:
        return RISK_LEVELS[2]
    return RISK_LEVELS[3] if score <= 10 else RISK_LEVELS[4]
