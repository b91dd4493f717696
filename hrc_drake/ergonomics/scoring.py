"""RULA and REBA body-part scores of one side from the measured posture angles
(`hrc_drake.ergonomics.posture`), and the thresholds the methods leave to the observer."""

from dataclasses import dataclass

from hrc_drake.ergonomics import reba, rula
from hrc_drake.ergonomics.posture import PostureAngles

ABDUCTED = 20.0
"""degrees out of the sagittal plane from which an upper arm counts as abducted (the
upper-arm bands' own neutral range is +-20 degrees)"""
OUT_TO_THE_SIDE = 0.10
"""m: a hand further than this outside its shoulder works out to the side (RULA)"""
TWISTED = 10.0
"""degrees of twist or side bend from which the trunk or the neck counts as twisted or
side-bent (ISO 11226's limit for trunk axial rotation and lateral bending)"""
DEVIATED = 10.0
"""degrees of radial or ulnar deviation from which a wrist counts as deviated"""
WRIST_TWISTED = 10.0
"""degrees of pronation or supination from the forearm's mid-position from which a wrist
counts as twisted (REBA): "twisted" has no band in REBA, so, like a wrist's deviation and
a trunk's or a neck's twist, a turn of 10 degrees counts"""
END_OF_TWIST = 60.0
"""degrees of pronation or supination from which a wrist twist is "at or near the end of
the twisting range" (RULA 2): the outer quarter of the forearm's 80 degrees either way
(docs/human-body.md [ROM], the skeleton's joint limit); short of it the twist is "mainly
in mid-range" (RULA 1)"""


@dataclass(frozen=True)
class Load:
    """What the person's hands hold at one time (kg on each side), how they hold it, and
    what the run around that time shows of it."""

    left: float = 0.0
    right: float = 0.0
    coupling: str = "good"
    static_or_repeated: bool = False

    def on(self, side: str) -> float:
        return self.left if side == "left" else self.right


@dataclass(frozen=True)
class Activity:
    """What the run shows around one time: a static posture (held over a minute) of the
    arm group (A) and of the neck, trunk and legs (B), actions repeated more than 4 times
    a minute, rapid large changes of posture, walking."""

    static_a: bool = False
    static_b: bool = False
    repeated: bool = False
    rapid_change: bool = False
    walking: bool = False


def weight_on_both_feet(angles: PostureAngles, walking: bool) -> bool:
    """Both feet bear weight, or the person walks (REBA counts walking as bilateral)."""
    return walking or all(angles.feet_on_floor.values())


def rula_parts(angles: PostureAngles, side: str, load: Load, activity: Activity):
    arm = angles.arms[side]
    muscle_a = rula.muscle_use_score(activity.static_a, activity.repeated)
    muscle_b = rula.muscle_use_score(activity.static_b, activity.repeated)
    force = rula.force_score(load.on(side), load.static_or_repeated)
    return rula.RulaParts(
        upper_arm=rula.upper_arm_score(arm.flexion, abducted=arm.abduction > ABDUCTED),
        lower_arm=rula.lower_arm_score(
            arm.elbow_flexion, arm.hand_across or arm.hand_lateral > OUT_TO_THE_SIDE
        ),
        wrist=rula.wrist_score(arm.wrist_flexion, arm.wrist_deviation > DEVIATED),
        wrist_twist=rula.wrist_twist_score(abs(arm.wrist_twist) > END_OF_TWIST),
        neck=rula.neck_score(
            angles.neck_flexion, angles.neck_twist > TWISTED, angles.neck_side_bend > TWISTED
        ),
        trunk=rula.trunk_score(
            angles.trunk_flexion, angles.trunk_twist > TWISTED, angles.trunk_side_bend > TWISTED
        ),
        legs=rula.legs_score(weight_on_both_feet(angles, activity.walking)),
        muscle_use_a=muscle_a,
        force_a=force,
        muscle_use_b=muscle_b,
        force_b=force,
    )


def reba_parts(angles: PostureAngles, side: str, load: Load, activity: Activity):
    arm = angles.arms[side]
    twisted = angles.trunk_twist > TWISTED or angles.trunk_side_bend > TWISTED
    neck_twisted = angles.neck_twist > TWISTED or angles.neck_side_bend > TWISTED
    bilateral = weight_on_both_feet(angles, activity.walking)
    return reba.RebaParts(
        trunk=reba.trunk_score(angles.trunk_flexion, twisted),
        neck=reba.neck_score(angles.neck_flexion, neck_twisted),
        legs=reba.legs_score(bilateral, max(angles.knee_flexion.values())),
        upper_arm=reba.upper_arm_score(arm.flexion, arm.abduction > ABDUCTED),
        lower_arm=reba.lower_arm_score(arm.elbow_flexion),
        wrist=reba.wrist_score(
            arm.wrist_flexion,
            arm.wrist_deviation > DEVIATED or abs(arm.wrist_twist) > WRIST_TWISTED,
        ),
        load=reba.load_score(load.left + load.right),
        coupling=reba.coupling_score(load.coupling),
        activity=reba.activity_score(
            activity.static_a or activity.static_b,
            activity.repeated,
            activity.rapid_change or not bilateral,
        ),
    )
