"""The robot's stop from full speed (T_s, S_s) per iisy variant, and the SSM parameters.

Measured stop data, when present, live in `models/iisy/stopping_data.yaml` as
`{variant: {stopping_time: s, stopping_distance: m}}` (written by the robot-motion
measurements). Until then, and for variants it lacks, the estimates below are used: a
category-1 stop from the 1 m/s collaborative tool speed at constant deceleration
(S_s = T_s · 1 m/s / 2), slower for the heavier variants.
"""

from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path

import yaml

from hrc_drake.paths import resource_dir
from hrc_drake.safety.config import SafetyConfig
from hrc_drake.safety.ssm import SsmParameters


@dataclass(frozen=True)
class StopData:
    stopping_time: float
    stopping_distance: float


ESTIMATED_STOPS = {
    "lbr_iisy3_r760": StopData(stopping_time=0.25, stopping_distance=0.125),
    "lbr_iisy11_r1300": StopData(stopping_time=0.35, stopping_distance=0.175),
    "lbr_iisy15_r930": StopData(stopping_time=0.35, stopping_distance=0.175),
}
FALLBACK_STOP = StopData(stopping_time=0.35, stopping_distance=0.175)


def stopping_data_file() -> Path:
    return resource_dir("models") / "iisy" / "stopping_data.yaml"


@lru_cache(maxsize=4)
def _measured(path: Path) -> dict[str, StopData]:
    if not path.is_file():
        return {}
    table = yaml.safe_load(path.read_text()) or {}
    return {name: StopData(**values) for name, values in table.items()}


def stop_data(variant: str, path: Path | None = None) -> StopData:
    """Measured stop data of `variant` if available, else the estimate."""
    measured = _measured(path or stopping_data_file())
    return measured.get(variant) or ESTIMATED_STOPS.get(variant, FALLBACK_STOP)


def ssm_parameters(config: SafetyConfig, variant: str) -> SsmParameters:
    """The S_p terms for this robot; the config's stop figures win over measured ones."""
    stop = stop_data(variant)
    return SsmParameters(
        reaction_time=config.reaction_time,
        stopping_time=_given(config.stopping_time, stop.stopping_time),
        stopping_distance=_given(config.stopping_distance, stop.stopping_distance),
        intrusion_distance=config.intrusion_distance,
        sensor_uncertainty=config.sensor_uncertainty,
        robot_uncertainty=config.robot_uncertainty,
    )


def _given(value: float | None, default: float) -> float:
    return default if value is None else value
