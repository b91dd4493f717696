"""The SSM parameters of a robot: the scenario's safety settings plus the robot's stop.

T_s and S_s are the variant's measured stop from top speed (`models/iisy/stopping.yaml`,
written by `python -m hrc_drake.motion.stopping`); a scenario may override them.
"""

from hrc_drake.motion.stopping import stopping_data
from hrc_drake.safety.config import SafetyConfig
from hrc_drake.safety.ssm import SsmParameters


def ssm_parameters(config: SafetyConfig, variant: str) -> SsmParameters:
    """The S_p terms for this robot; the config's stop figures win over measured ones."""
    given = (config.stopping_time, config.stopping_distance)
    if None in given:
        stop = stopping_data(variant)
        given = (
            _given(config.stopping_time, stop.time),
            _given(config.stopping_distance, stop.distance),
        )
    return SsmParameters(
        reaction_time=config.reaction_time,
        stopping_time=given[0],
        stopping_distance=given[1],
        intrusion_distance=config.intrusion_distance,
        sensor_uncertainty=config.sensor_uncertainty,
        robot_uncertainty=config.robot_uncertainty,
    )


def _given(value: float | None, default: float) -> float:
    return default if value is None else value
