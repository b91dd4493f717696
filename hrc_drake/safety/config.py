"""The scenario's `safety:` section (loadable with Drake's `yaml_load_typed`; every field
has a default, so a scenario without the section gets a monitor with ISO defaults)."""

import dataclasses
from dataclasses import dataclass, field

from hrc_drake.safety.sensors import Sensor, SensorsConfig

ISO_13855 = "iso13855"
CONSTANT = "constant"
MEASURED = "measured"
V_H_RULES = (ISO_13855, CONSTANT, MEASURED)


@dataclass
class SafetyConfig:
    """Speed and separation monitoring and contact assessment settings (SI units); the
    figures and their sources are in docs/safety.md.

    Person speed v_h: with `v_h_rule` iso13855 (ISO 13855) it is `v_h_near` where the
    protective distance computed with it is at most `near_distance`, else `v_h` (walking);
    with `constant`, always `v_h`; with `measured`, the measured speed of the closest body
    region towards the robot (0 for a person standing still or walking away: it trusts the
    person not to speed up within the robot's stop).

    T_r, the reaction time, is `sensing_time` (how long the sensing takes to report the
    person: a safety scanner's response time) plus the monitor's `period` (the person may
    move just after a measurement) plus the robot's command latency (one RobotMotion update
    period). The stop itself comes from the robot variant's measured stopping data.

    `robot_speed` is the highest speed of any robot point (with what it carries) at full
    speed: the monitor chooses the speed scale as if the robot moved that fast. A `moving`
    robot is one whose fastest point exceeds `moving_speed`: only a moving robot violates
    SSM or causes a contact.

    While the person is so far from the robot that the monitor would allow full speed even
    if it measured only every `far_period`, or a multiple of `period` below it (with the
    `measured` rule: and the person came at `v_h`), it measures that much less often
    (`Judge.next_period`); 0 measures every `period` always.

    A contact is quasi-static (clamping) when the touched body region has cell geometry or
    another robot part within `clamping_gap` on its far side; otherwise it is transient.

    With `sensors` (hrc_drake.safety.sensors) the monitor sees the person only through
    them: it slows down for their detections, with each sensor's own response time, ISO
    13855 intrusion distance C and measurement error Z_d in S_p. Without, it knows every
    point of the person's body (ground truth).
    """

    enabled: bool = True
    ssm: bool = True
    period: float = 0.01
    far_period: float = 0.05
    v_h_rule: str = ISO_13855
    v_h: float = 1.6
    v_h_near: float = 2.0
    near_distance: float = 0.5
    sensing_time: float = 0.08
    robot_speed: float = 1.0
    intrusion_distance: float = 0.1
    sensor_uncertainty: float = 0.05
    robot_uncertainty: float = 0.02
    hysteresis: float = 0.05
    min_scale: float = 0.05
    moving_speed: float = 0.01
    contact_area_cm2: float = 1.0
    clamping_gap: float = 0.02
    sensors: SensorsConfig = field(default_factory=SensorsConfig)

    def truth(self) -> "SafetyConfig":
        """The settings the real body is judged by (the run's violations and margin): with
        sensors, the person is known as late as the slowest sensor reports them."""
        if not self.sensors.present:
            return self
        return dataclasses.replace(self, sensing_time=self.sensors.response_time)

    def seen_through(self, sensor: Sensor) -> "SafetyConfig":
        """The settings S_p is computed with for the person as `sensor` sees them: its
        response time, its intrusion distance C and its measurement error Z_d."""
        return dataclasses.replace(
            self,
            sensing_time=sensor.response_time,
            intrusion_distance=sensor.intrusion,
            sensor_uncertainty=sensor.measurement_error,
        )
