"""The scenario's `safety:` section (loadable with Drake's `yaml_load_typed`; every field
has a default, so a scenario without the section gets a monitor with ISO defaults)."""

from dataclasses import dataclass


@dataclass
class SafetyConfig:
    """Speed and separation monitoring and contact assessment settings (SI units).

    `stopping_time` / `stopping_distance` are the robot's stop from full speed; left empty,
    the measured stop data of the robot variant are used (`hrc_drake.safety.stopping`).
    `robot_speed` is the highest speed of any robot point towards the person at speed
    scale 1: the monitor chooses the scale as if the robot moved that fast, which is
    conservative when the running motion is slower.
    """

    enabled: bool = True
    ssm: bool = True
    period: float = 0.01
    v_h: float = 1.6
    measured_human_speed: bool = False
    reaction_time: float = 0.1
    stopping_time: float | None = None
    stopping_distance: float | None = None
    robot_speed: float = 1.0
    intrusion_distance: float = 0.1
    sensor_uncertainty: float = 0.05
    robot_uncertainty: float = 0.02
    hysteresis: float = 0.05
    min_scale: float = 0.05
    moving_speed: float = 0.01
    contact_area_cm2: float = 1.0
