"""From one proximity reading to the monitor's status: S_p, violation, speed scale,
contact assessments and the run's running totals."""

import dataclasses
import functools
import math
from dataclasses import dataclass, field

from hrc_drake.safety.config import CONSTANT, MEASURED, SafetyConfig
from hrc_drake.safety.messages import (
    CARRIED,
    ContactRecord,
    SafetyStatus,
    SafetyTotals,
    ViolationEpisode,
)
from hrc_drake.safety.pfl import QUASI_STATIC, TRANSIENT, assess_contact
from hrc_drake.safety.proximity import Reading
from hrc_drake.safety.sensors_view import SensorView
from hrc_drake.safety.ssm import (
    NO_TERMS,
    REDUCED,
    STOPPED,
    SsmModel,
    max_safe_scale,
    next_scale,
    protective_separation,
    zone,
)


@dataclass(frozen=True)
class Judge:
    """The fixed inputs of judging: settings, the S_p model of the real body and the
    robot's effective mass without a carried object (m_R = M/2 + tool); with safety sensors,
    each sensor's S_p model (by name)."""

    config: SafetyConfig
    model: SsmModel
    robot_mass: float
    sensed: dict[str, SsmModel] = field(default_factory=dict)

    @functools.cached_property
    def slower_models(self) -> tuple[tuple[float, SsmModel], ...]:
        """The longer periods the monitor may measure at, longest first (`far_period` and
        every multiple of `period` below it), each with S_p's model as if the monitor
        measured only that often, with a person who may come at ISO 13855's approach speed
        even where the rule is `measured`."""
        config = self.config
        rule = CONSTANT if config.v_h_rule == MEASURED else config.v_h_rule
        latency = self.model.lead_time - config.period
        multiples = range(math.ceil(config.far_period / config.period - 1e-9) - 1, 1, -1)
        periods = [config.far_period, *(k * config.period for k in multiples)]
        return tuple(
            (
                period,
                SsmModel.from_config(
                    dataclasses.replace(config, period=period, v_h_rule=rule),
                    self.model.stop,
                    latency,
                ),
            )
            for period in periods
            if period > config.period
        )

    def next_period(self, status: SafetyStatus) -> float:
        """How long the monitor may go unmeasured after `status`: the longest of
        `slower_models`' periods at which, at the separation less the hysteresis, a monitor
        measuring that often would keep full speed, while the robot may move at full speed
        and nothing touches; else `period`. Then no measurement in between could have
        slowed the robot (tests/safety/test_far_rate.py). Always `period` with safety
        sensors: their S_p counts one monitor period from a report to the robot, so the
        monitor reads every report as it comes."""
        config = self.config
        if status.scale < 1.0 or status.contact or status.sensing is not None:
            return config.period
        room = status.separation - config.hysteresis
        for (period, model), least in zip(self.slower_models, self._full_speed_rooms, strict=True):
            if room > least + ROOM_TOLERANCE:
                return period
            if room >= least - ROOM_TOLERANCE and max_safe_scale(room, 0.0, model) >= 1.0:
                return period
        return config.period

    @functools.cached_property
    def _full_speed_rooms(self) -> tuple[float, ...]:
        """For each of `slower_models`, about the least room at which it keeps full speed:
        `next_period` compares with it and asks `max_safe_scale` only within
        ROOM_TOLERANCE of it (at every update of a far person it was most of the cost)."""
        return tuple(_least_full_speed_room(model) for _, model in self.slower_models)

    def far(self, status: SafetyStatus) -> bool:
        """Whether the monitor may measure less often than every `period` after `status`."""
        return self.next_period(status) > self.config.period

    def status(
        self,
        time: float,
        reading: Reading,
        before: SafetyStatus,
        payload: float,
        path_rate: float,
        sensing: tuple[SensorView, ...] | None = None,
    ) -> SafetyStatus:
        """`path_rate`: the fraction of full speed the robot moves at along its path;
        `sensing`: the sensors' views of the person, which the scale then follows (the
        violation is still judged on the real body, `reading`)."""
        config = self.config
        closest = reading.closest
        moving = reading.robot_speed > config.moving_speed
        separation, terms, v_h = math.inf, NO_TERMS, 0.0
        if closest is not None:
            separation, v_h = closest.distance, max(closest.human_approach, 0.0)
            v_r = max(closest.robot_approach, 0.0)
            terms = protective_separation(self.model, path_rate, reading.robot_speed, v_r, v_h)
        if sensing is None:
            safe = max_safe_scale(separation, v_h, self.model)
            sensed_protective = math.nan
        else:
            safe = self._sensed_scale(sensing, 0.0)
            sensed_protective = self._sensed_protective(sensing, path_rate, reading.robot_speed)
        safe_with_margin = safe  # all `next_scale` needs when the scale drops to `safe`
        if safe >= before.scale:
            safe_with_margin = (
                max_safe_scale(separation - config.hysteresis, v_h, self.model)
                if sensing is None
                else self._sensed_scale(sensing, config.hysteresis)
            )
        scale = next_scale(before.scale, safe, safe_with_margin, config.min_scale)
        scale = scale if config.ssm else 1.0
        robot_mass = self.robot_mass + payload
        contact = tuple(
            assess_contact(
                c.region,
                c.part,
                c.relative_speed,
                robot_mass,
                config.contact_area_cm2,
                QUASI_STATIC if c.pinned else TRANSIENT,
                depth=-c.distance if moving else 0.0,  # a robot at rest presses nothing
                robot_moving=moving,
            )
            for c in reading.contacts
            if moving or not is_handover_grasp(c)
        )
        now = SafetyStatus(
            time=time,
            separation=separation,
            region=closest.region if closest else "",
            link=closest.part if closest else "",
            ssm=terms,
            scale=scale,
            safe_scale=safe,
            zone=zone(scale),
            walking_speed=reading.walking_speed,
            robot_speed=reading.robot_speed,
            path_rate=path_rate,
            human_approach=v_h,
            violation=moving and separation < terms.total,
            contact=contact,
            ssm_enabled=config.ssm,
            sensing=sensing,
            sensed_protective=sensed_protective,
            robot_parts=reading.robot,
        )
        return _replaced(now, totals=updated_totals(before, now, config.moving_speed))

    def _sensed_scale(self, sensing: tuple[SensorView, ...], hysteresis: float) -> float:
        """The largest scale every sensor's view allows: S_p with its own model within the
        separation it senses (less `hysteresis`), and its fields' limit; a person no
        sensor sees is not slowed for, but a sensor that has reported nothing yet holds the
        robot still (as its outputs do at power-up)."""
        scale = 1.0
        for view in sensing:
            if self.config.sensors.speed_and_separation:
                model = self.sensed[view.name]
                scale = min(scale, max_safe_scale(view.separation - hysteresis, 0.0, model))
            scale = min(scale, view.speed_limit if view.reported else 0.0)
        return scale

    def _sensed_protective(self, sensing, path_rate: float, robot_speed: float) -> float:
        """S_p at the nearest detection, with its sensor's model; the robot's fastest point
        stands in for its speed towards the person, whose direction the sensor cannot
        know."""
        seen = [view for view in sensing if view.seen]
        if not seen:
            return math.nan
        nearest = min(seen, key=lambda view: view.separation)
        model = self.sensed[nearest.name]
        return protective_separation(model, path_rate, robot_speed, robot_speed, 0.0).total


ROOM_TOLERANCE = 1e-9
"""m either side of `_least_full_speed_room` where `next_period` asks the exact test."""


def _least_full_speed_room(model: SsmModel) -> float:
    """The separation above which `max_safe_scale` (for a person at rest) is 1, by
    bisection: the scale grows with the separation far beyond ISO 13855's near distance,
    where full speed becomes safe."""
    low, high = 0.0, 1.0
    while max_safe_scale(high, 0.0, model) < 1.0:
        low, high = high, 2.0 * high
    while high - low > ROOM_TOLERANCE / 4:
        middle = (low + high) / 2
        low, high = (low, middle) if max_safe_scale(middle, 0.0, model) >= 1.0 else (middle, high)
    return high


def updated_totals(before: SafetyStatus, now: SafetyStatus, moving_speed: float) -> SafetyTotals:
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
    at_rest = before.robot_speed <= moving_speed
    changes["reduced_time"] = totals.reduced_time + dt * (before.zone == REDUCED)
    changes["stopped_time"] = totals.stopped_time + dt * (before.zone == STOPPED and at_rest)
    changes["stops"] = totals.stops + (now.zone == STOPPED and before.zone != STOPPED)
    changes["violation_time"] = totals.violation_time + dt * before.violation
    changes["contact_time"] = totals.contact_time + dt * bool(before.contact)
    if now.violation:
        changes["violation_episodes"] = _episodes(totals.violation_episodes, before, now)
    if now.contact:
        changes["contact_records"] = _contact_records(totals.contact_records, before, now)
    return _replaced(totals, **changes)


def _episodes(episodes: tuple, before: SafetyStatus, now: SafetyStatus) -> tuple:
    """The episodes with `now` (a violation) added: a new one, or the running one grown."""
    current = ViolationEpisode(
        now.time, now.time, now.region, now.link, now.separation, now.protective
    )
    if not before.violation:
        return (*episodes, current)
    running = episodes[-1]
    worst = current if current.deficit > running.deficit else running
    grown = _replaced(worst, start=running.start, end=now.time)
    return (*episodes[:-1], grown)


def _contact_records(records: tuple, before: SafetyStatus, now: SafetyStatus) -> tuple:
    """The records with the contacts of `now`: a touching pair that touched at the last
    update grows its record (the last one of that pair), any other starts one."""
    touching_before = {(c.region, c.part) for c in before.contact}
    records = list(records)
    for contact in now.contact:
        pair = (contact.region, contact.part)
        if pair not in touching_before:
            records.append(
                ContactRecord(now.time, now.time, contact, contact.robot_moving, contact.violation)
            )
            continue
        k = max(i for i, r in enumerate(records) if (r.worst.region, r.worst.part) == pair)
        record = records[k]
        worst = contact if contact.severity > record.worst.severity else record.worst
        violation = record.violation or contact.violation
        records[k] = _replaced(record, end=now.time, worst=worst, violation=violation)
    return tuple(records)


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
