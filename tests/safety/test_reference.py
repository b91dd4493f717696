"""The reference S_p a run's margin is judged by: the monitor's own model but for the
approach speeds, which are ISO 13855's whatever the monitor assumes."""

import dataclasses

import numpy as np

from hrc_drake.safety.config import CONSTANT, SafetyConfig
from hrc_drake.safety.reference import reference_model, reference_protective
from hrc_drake.safety.ssm import SsmModel
from hrc_drake.safety.stopping import StopModel

STOP = StopModel(speeds=(0.0, 0.33, 0.66, 1.0), times=(0.01, 0.2, 0.4, 0.6), distance_factor=0.5)
ISO = SafetyConfig(sensing_time=0.12, intrusion_distance=0.2)
SLOW = dataclasses.replace(ISO, v_h_rule=CONSTANT, v_h=0.8)
"""A monitor that takes the person for half as fast as ISO 13855 does."""


def test_a_monitor_assuming_a_slower_person_is_judged_with_iso_13855s_speeds():
    assert reference_model(SLOW, STOP, 0.01) == SsmModel.from_config(ISO, STOP, 0.01)
    assert reference_model(SLOW, STOP, 0.01) != SsmModel.from_config(SLOW, STOP, 0.01)


def test_no_s_p_without_a_person():
    log = {
        "path_rate": np.array([1.0, 1.0]),
        "robot_speed": np.array([0.5, 0.5]),
        "approach_speed": np.array([0.5, 0.5]),
        "human_approach": np.array([1.6, 1.6]),
        "separation": np.array([np.inf, 1.0]),
    }
    found = reference_protective(log, reference_model(ISO, STOP, 0.01))
    assert np.isnan(found[0]) and found[1] > 0.0
