"""S_p as the standard has it, recomputed from a run's safety log (`safety.npz`: the robot's
speed fraction, its fastest point's speed, the directed speeds at the closest pair) with
ISO 13855's approach speeds, whatever the monitor's `safety` section assumes.

A monitor that assumes a slower person (`safety.v_h_rule: constant`, `v_h: 0.8`) thus gets a
larger S_p here than its own; with the default rule the two S_p are the same numbers. The
run's safety margin (`hrc_drake.evaluation.margin`) is judged against this S_p.
"""

import dataclasses
import math

import numpy as np

from hrc_drake.safety.config import SafetyConfig
from hrc_drake.safety.ssm import SsmModel, protective_separation
from hrc_drake.safety.stopping import StopModel

ISO_APPROACH = ("v_h_rule", "v_h", "v_h_near", "near_distance")
"""The monitor's settings the reference replaces by ISO 13855's (SafetyConfig's defaults)."""


def reference_model(config: SafetyConfig, stop: StopModel, command_latency: float) -> SsmModel:
    """S_p's model with the monitor's reaction time (with sensors, their slowest response)
    and margins, the robot's `stop` and command latency (s), and ISO 13855's approach
    speeds (2.0 m/s where S_p is at most 0.5 m, else 1.6 m/s)."""
    iso = {name: getattr(SafetyConfig(), name) for name in ISO_APPROACH}
    return SsmModel.from_config(dataclasses.replace(config.truth(), **iso), stop, command_latency)


def reference_protective(log: dict[str, np.ndarray], model: SsmModel) -> np.ndarray:
    """S_p at every logged update, recomputed with `model` (NaN without a person)."""
    inputs = zip(
        log["path_rate"],
        log["robot_speed"],
        log["approach_speed"],
        log["human_approach"],
        log["separation"],
        strict=True,
    )
    return np.array(
        [
            protective_separation(model, rate, speed, v_r, v_h).total
            if math.isfinite(separation)
            else math.nan
            for rate, speed, v_r, v_h, separation in inputs
        ]
    )
