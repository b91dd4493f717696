"""From one proximity reading to the monitor's status: S_p, violation, speed scale,
contact assessments and the run's running totals."""

import math
from dataclasses import dataclass

from hrc_drake.safety.config import SafetyConfig
from hrc_drake.safety.messages import CARRIED, SafetyStatus, SafetyTotals
from hrc_drake.safety.pfl import assess_contact
from hrc_drake.safety.proximity import Reading
from hrc_drake.safety.ssm import (
    REDUCED,
    STOPPED,
    SsmParameters,
    max_safe_scale,
    next_scale,
    protective_separation,
    zone,
)


@dataclass(frozen=True)
class Judge:
    """The fixed inputs of judging: settings, S_p terms and the robot's effective mass
    without a carried object (m_R = M/2 + tool)."""

    config: SafetyConfig
    params: SsmParameters
    robot_mass: float

    def status(self, time: float, reading: Reading, before: SafetyStatus, payload: float):
        config = self.config
        closest = reading.closest
        separation = closest.distance if closest else math.inf
        v_r = max(closest.robot_approach, 0.0) if closest else 0.0
        v_h = self._person_speed(closest)
        actual_scale = min(1.0, reading.robot_speed / config.robot_speed)
        protective = protective_separation(v_h, v_r, self.params, actual_scale)
        safe = max_safe_scale(separation, v_h, config.robot_speed, self.params)
        safe_with_margin = max_safe_scale(
            separation - config.hysteresis, v_h, config.robot_speed, self.params
        )
        scale = next_scale(before.scale, safe, safe_with_margin, config.min_scale)
        scale = scale if config.ssm else 1.0
        robot_at_rest = reading.robot_speed <= config.moving_speed
        contact = tuple(
            assess_contact(
                c.region, c.relative_speed, self.robot_mass + payload, config.contact_area_cm2
            )
            for c in reading.contacts
            if not (robot_at_rest and is_handover_grasp(c))
        )
        now = SafetyStatus(
            time=time,
            separation=separation,
            region=closest.region if closest else "",
            link=closest.part if closest else "",
            protective=protective,
            scale=scale,
            safe_scale=safe,
            zone=zone(scale),
            human_speed=reading.human_speed,
            robot_speed=reading.robot_speed,
            approach_speed=v_r,
            violation=reading.robot_speed > config.moving_speed and separation < protective,
            contact=contact,
            ssm_enabled=config.ssm,
        )
        return _replaced(now, totals=updated_totals(before, now))

    def _person_speed(self, closest) -> float:
        if self.config.measured_human_speed:
            return max(closest.human_approach, 0.0) if closest else 0.0
        return self.config.v_h


def updated_totals(before: SafetyStatus, now: SafetyStatus) -> SafetyTotals:
    """Totals after `now`; durations credit the interval since `before` to its state."""
    totals = before.totals
    dt = now.time - before.time
    changes = {}
    if now.separation < totals.min_separation:
        changes.update(
            min_separation=now.separation,
            min_separation_region=now.region,
            min_separation_link=now.link,
            min_separation_time=now.time,
        )
    changes["reduced_time"] = totals.reduced_time + dt * (before.zone == REDUCED)
    changes["stopped_time"] = totals.stopped_time + dt * (before.zone == STOPPED)
    changes["stops"] = totals.stops + (now.zone == STOPPED and before.zone != STOPPED)
    changes["violations"] = totals.violations + (now.violation and not before.violation)
    changes["violation_time"] = totals.violation_time + dt * before.violation
    if now.violation:
        changes["worst_deficit"] = max(totals.worst_deficit, now.protective - now.separation)
    changes.update(_contact_totals(before, now, dt))
    return _replaced(totals, **changes)


def _contact_totals(before: SafetyStatus, now: SafetyStatus, dt: float) -> dict:
    totals = before.totals
    starts = bool(now.contact) and not before.contact
    episode_violated = any(c.violation for c in before.contact) and not starts
    violates = any(c.violation for c in now.contact)
    worst = max(now.contact, key=lambda c: (c.violation, c.limit_ratio), default=None)
    if totals.worst_contact is not None and worst is not None:
        worst = max(totals.worst_contact, worst, key=lambda c: (c.violation, c.limit_ratio))
    return {
        "contacts": totals.contacts + starts,
        "contact_time": totals.contact_time + dt * bool(before.contact),
        "contact_violations": totals.contact_violations + (violates and not episode_violated),
        "worst_contact": worst or totals.worst_contact,
    }


def _replaced(message, **changes):
    """`dataclasses.replace` for our plain frozen messages, without its Python loop over the
    fields (this runs at every update)."""
    return type(message)(**{**vars(message), **changes})


HANDOVER_REGIONS = ("hand", "lower_arm")
"""Body regions that take hold of the object a robot at rest presents in a hand-over."""


def is_handover_grasp(pair) -> bool:
    """The person's hand on the object in the robot's gripper: an intended contact with
    the workpiece, not a collision with the robot, while the robot stands still."""
    return pair.part == CARRIED and pair.region in HANDOVER_REGIONS
