"""Known postures of the person, set joint by joint, and their scores by hand (the
methods' own rules applied by the test's author, written down in each docstring)."""

import numpy as np

from hrc_drake.human.body import HumanBody

REACHING_TWISTED = {
    "lumbar_flexion": 30.0,
    "thorax_rotation": 20.0,
    "neck_flexion": 25.0,
    "right_shoulder_flexion": 100.0,
    "right_elbow_flexion": 80.0,
    "right_wrist_flexion": 20.0,
}
"""Trunk flexed 30 deg and twisted 20, neck flexed 25, the right arm raised 100 deg forward,
elbow bent 80, wrist flexed 20; the left arm hanging, both feet on the floor.

RULA, right side: upper arm over 90 deg -> 4; lower arm 60-100 -> 1; wrist over 15 -> 3;
twist mid-range -> 1: Table A 4. Neck over 20 -> 3; trunk 20-60 -> 3, twisted +1 -> 4;
legs even -> 1: Table B 5. No load, no repetition: Table C (4, 5) -> 5.
Left side: upper arm 1, lower arm (straight, 0-60) 2, wrist neutral 1, twist 1: Table A 2;
Table C (2, 5) -> 4. Worst: 5, right.
REBA, right side: trunk 20-60 -> 3, twisted +1 -> 4; neck over 20 -> 2; legs bilateral,
knees straight -> 1: Table A 5, load 0. Upper arm over 90 -> 4; lower arm 60-100 -> 1;
wrist over 15 -> 2: Table B 5, coupling 0 (nothing held). Table C (5, 5) -> 6, activity 0:
6 (medium). Left: upper arm 1, lower arm 2, wrist 1: Table B 1; Table C (5, 1) -> 4.
"""
REACHING_RULA, REACHING_REBA = 5, 6

REACHING_PRONATED = {**REACHING_TWISTED, "right_wrist_pronation": 75.0}
"""REACHING_TWISTED with the right forearm pronated 75 deg (palm turned down).

RULA, right side: twist at the end of its range -> 2: Table A (4, 1, 3, 2) 5; Table C
(5, 5) -> 6. REBA, right side: wrist over 15 -> 2, twisted +1 -> 3: Table B (4, 1, 3) 5, as
with the wrist 2: Table C (5, 5) -> 6.
"""
PRONATED_RULA, PRONATED_REBA = 6, 6


def posture(body: HumanBody, degrees: dict[str, float]) -> np.ndarray:
    """The standing pose with `degrees` set on the named joints."""
    q = body.standing_pose()
    for joint, angle in degrees.items():
        q[body.index(joint)] = np.radians(angle)
    return q
