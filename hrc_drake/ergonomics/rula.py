"""RULA, the Rapid Upper Limb Assessment (McAtamney & Corlett, Applied Ergonomics 24(2),
1993, 91-99): body-part scores from posture angles, Tables A, B and C of the paper, and the
action levels. docs/ergonomics.md says which printing of Table A this is and why.

Angles are in degrees, read to the whole degree as an observer's goniometer would
(`whole_degrees`), so a posture exactly at a band's edge scores as the paper's figures show.
"""

from dataclasses import dataclass

# Table A: upper arm 1-6 x lower arm 1-3 (rows), wrist 1-4 x wrist twist 1-2 (columns).
TABLE_A = (
    (1, 2, 2, 2, 2, 3, 3, 3),
    (2, 2, 2, 2, 3, 3, 3, 3),
    (2, 3, 3, 3, 3, 3, 4, 4),
    (2, 3, 3, 3, 3, 4, 4, 4),
    (3, 3, 3, 3, 3, 4, 4, 4),
    (3, 4, 4, 4, 4, 4, 5, 5),
    (3, 3, 4, 4, 4, 4, 5, 5),
    (3, 4, 4, 4, 4, 4, 5, 5),
    (4, 4, 4, 4, 4, 5, 5, 5),
    (4, 4, 4, 4, 4, 5, 5, 5),
    (4, 4, 4, 4, 4, 5, 5, 5),
    (4, 4, 4, 5, 5, 5, 6, 6),
    (5, 5, 5, 5, 5, 6, 6, 7),
    (5, 6, 6, 6, 6, 7, 7, 7),
    (6, 6, 6, 7, 7, 7, 7, 8),
    (7, 7, 7, 7, 7, 8, 8, 9),
    (8, 8, 8, 8, 8, 9, 9, 9),
    (9, 9, 9, 9, 9, 9, 9, 9),
)
# Table B: neck 1-6 (rows), trunk 1-6 x legs 1-2 (columns).
TABLE_B = (
    (1, 3, 2, 3, 3, 4, 5, 5, 6, 6, 7, 7),
    (2, 3, 2, 3, 4, 5, 5, 5, 6, 7, 7, 7),
    (3, 3, 3, 4, 4, 5, 5, 6, 6, 7, 7, 7),
    (5, 5, 5, 6, 6, 7, 7, 7, 7, 7, 8, 8),
    (7, 7, 7, 7, 7, 8, 8, 8, 8, 8, 8, 8),
    (8, 8, 8, 8, 8, 8, 8, 9, 9, 9, 9, 9),
)
# Table C (the grand score): score C 1-8+ (rows), score D 1-7+ (columns).
TABLE_C = (
    (1, 2, 3, 3, 4, 5, 5),
    (2, 2, 3, 4, 4, 5, 5),
    (3, 3, 3, 4, 4, 5, 6),
    (3, 3, 3, 4, 5, 6, 6),
    (4, 4, 4, 5, 6, 7, 7),
    (4, 4, 5, 6, 6, 7, 7),
    (5, 5, 6, 6, 7, 7, 7),
    (5, 5, 6, 7, 7, 7, 7),
)

INTERMITTENT_LOAD_LIMITS = (2.0, 10.0)
"""kg: the force/load score's bands (below 2 kg, 2-10 kg, above 10 kg)."""


def whole_degrees(angle: float) -> int:
    return int(round(angle))


def upper_arm_position(flexion: float) -> int:
    """The upper arm's bands, the same in RULA and REBA: 20 deg either side of the trunk
    1, beyond 20 deg of extension or 20-45 deg of flexion 2, 45-90 deg 3, beyond 4.
    `flexion`: the upper arm's angle forward of the trunk (negative: extension)."""
    a = whole_degrees(flexion)
    if -20 <= a <= 20:
        return 1
    if a < -20 or a <= 45:
        return 2
    return 3 if a <= 90 else 4


def lower_arm_position(flexion: float) -> int:
    """The lower arm's bands, the same in RULA and REBA: 60-100 deg of elbow flexion 1,
    else 2."""
    return 1 if 60 <= whole_degrees(flexion) <= 100 else 2


def upper_arm_score(
    flexion: float, shoulder_raised: bool = False, abducted: bool = False, supported: bool = False
) -> int:
    return max(1, upper_arm_position(flexion) + shoulder_raised + abducted - supported)


def lower_arm_score(flexion: float, across_or_out: bool = False) -> int:
    """`across_or_out`: the hand works across the body's midline or out to the side."""
    return lower_arm_position(flexion) + across_or_out


def wrist_score(flexion: float, deviated: bool = False) -> int:
    """`flexion`: flexion or extension from neutral (either sign)."""
    a = abs(whole_degrees(flexion))
    return (1 if a == 0 else 2 if a <= 15 else 3) + deviated


def wrist_twist_score(end_of_range: bool = False) -> int:
    return 2 if end_of_range else 1


def neck_score(flexion: float, twisted: bool = False, side_bent: bool = False) -> int:
    """`flexion`: the neck's flexion from the trunk (negative: extension)."""
    a = whole_degrees(flexion)
    base = 4 if a < 0 else 1 if a <= 10 else 2 if a <= 20 else 3
    return base + twisted + side_bent


def trunk_score(flexion: float, twisted: bool = False, side_bent: bool = False) -> int:
    """`flexion`: the trunk's flexion from upright, standing (extension scores as upright:
    the paper's bands start at 0)."""
    a = whole_degrees(flexion)
    base = 1 if a <= 0 else 2 if a <= 20 else 3 if a <= 60 else 4
    return base + twisted + side_bent


def legs_score(balanced: bool) -> int:
    """1 standing with the weight evenly on both feet, 2 when it is not."""
    return 1 if balanced else 2


def muscle_use_score(static: bool, repeated: bool) -> int:
    """+1 for a posture mainly static (held longer than a minute) or an action repeated
    more than 4 times a minute."""
    return 1 if static or repeated else 0


def force_score(load: float, static_or_repeated: bool = False, shock: bool = False) -> int:
    """`load` in kg."""
    low, high = INTERMITTENT_LOAD_LIMITS
    if shock:
        return 3
    if load < low:
        return 0
    if load <= high:
        return 2 if static_or_repeated else 1
    return 3 if static_or_repeated else 2


@dataclass(frozen=True)
class RulaParts:
    """The body-part, muscle-use and force scores of one side."""

    upper_arm: int
    lower_arm: int
    wrist: int
    wrist_twist: int
    neck: int
    trunk: int
    legs: int
    muscle_use_a: int = 0
    force_a: int = 0
    muscle_use_b: int = 0
    force_b: int = 0


def posture_score_a(upper_arm: int, lower_arm: int, wrist: int, wrist_twist: int) -> int:
    row = 3 * (min(upper_arm, 6) - 1) + min(lower_arm, 3) - 1
    return TABLE_A[row][2 * (min(wrist, 4) - 1) + min(wrist_twist, 2) - 1]


def posture_score_b(neck: int, trunk: int, legs: int) -> int:
    return TABLE_B[min(neck, 6) - 1][2 * (min(trunk, 6) - 1) + min(legs, 2) - 1]


def grand_score(parts: RulaParts) -> int:
    """Table C of score C (Table A + muscle use + force, arm and wrist) and score D
    (Table B + muscle use + force, neck, trunk and legs)."""
    c = posture_score_a(parts.upper_arm, parts.lower_arm, parts.wrist, parts.wrist_twist)
    c += parts.muscle_use_a + parts.force_a
    d = posture_score_b(parts.neck, parts.trunk, parts.legs) + parts.muscle_use_b + parts.force_b
    return TABLE_C[min(c, 8) - 1][min(d, 7) - 1]


ACTION_LEVELS = (1, 2, 3, 4)


def action_level(score: int) -> int:
    """1: acceptable (1-2); 2: investigate, changes may be needed (3-4); 3: investigate
    and change soon (5-6); 4: investigate and change immediately (7)."""
    return min(4, (score + 1) // 2)
