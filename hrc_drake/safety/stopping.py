"""The robot's stop as S_p needs it: stopping time and distance as functions of the speed it
moves at now, from the variant's measured stopping data (models/iisy/stopping/<variant>.yaml,
measured by `python -m hrc_drake.modelgen stopping`: hrc_drake.modelgen.stopping).

RobotMotion brakes on its path with its full joint acceleration limits, so a stop from a
fraction r of full speed takes about r times as long as from full speed (plus up to one
update period) and the fastest point travels about half its speed times that time. The
model takes the worst measured case at each tabulated speed (over axes and extensions):

    T_s(r)    piecewise linear through the worst stopping times at 33, 66 and 100 % speed
              (and the first segment carried on to r = 0, never below 0)
    S_s(r, v) = κ · v · T_s(r), with v the fastest point's speed now (carried objects
              included) and κ the largest measured distance / (point speed × time)
"""

import bisect
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path

import yaml

from hrc_drake.paths import resource_dir

STOPPING_DIR = "iisy/stopping"
"""Inside the model folder (models/ in a checkout): one file per variant."""


@dataclass(frozen=True)
class Stop:
    """One measured stop (SI units; the angle in degrees)."""

    axis: str
    speed: float
    """fraction of full speed the robot moved at (the override)"""
    extension: float
    """fraction of the largest horizontal distance of the tool from the A1 axis"""
    time: float
    """s from the stop command to rest"""
    distance: float
    """m travelled by the fastest point meanwhile"""
    point_speed: float
    """m/s of the fastest point when the stop was commanded"""
    angle: float
    """degrees the axis turned meanwhile"""


def load_stops(variant: str) -> tuple[Stop, ...]:
    """The stored stopping data of `variant`."""
    return _parsed_stops(stopping_file(variant).read_text())


def _parsed_stops(text: str) -> tuple[Stop, ...]:
    return tuple(Stop(**entry) for entry in yaml.safe_load(text)["stops"])


def stopping_file(variant: str, models_dir: Path | None = None) -> Path:
    """Where the stopping data of `variant` are (in the shipped models unless `models_dir`)."""
    return (models_dir or resource_dir("models")) / STOPPING_DIR / f"{variant}.yaml"


@dataclass(frozen=True)
class StopModel:
    """Worst-case stopping time (s) by speed fraction, and the distance factor κ."""

    speeds: tuple[float, ...]
    times: tuple[float, ...]
    distance_factor: float

    @classmethod
    def from_stops(cls, stops: tuple[Stop, ...]) -> "StopModel":
        levels = sorted({s.speed for s in stops})
        if levels[-1] != 1.0:
            raise ValueError(f"stopping data end at {levels[-1]:.0%} speed, not at full speed")
        worst = [max(s.time for s in stops if s.speed == level) for level in levels]
        slope = (worst[1] - worst[0]) / (levels[1] - levels[0])
        at_rest = max(0.0, worst[0] - slope * levels[0])
        factor = max(s.distance / (s.point_speed * s.time) for s in stops if s.time > 0.0)
        return cls((0.0, *levels), (at_rest, *worst), factor)

    @classmethod
    def of_variant(cls, variant: str) -> "StopModel":
        return _stop_model(stopping_file(variant).read_text())

    def time(self, speed_fraction: float) -> float:
        """T_s from `speed_fraction` of full speed (0 at rest; the top speed's beyond it).
        Plain Python: the monitor asks several times an update."""
        if speed_fraction <= 0.0:
            return 0.0
        speeds, times = self.speeds, self.times
        k = min(bisect.bisect_right(speeds, speed_fraction), len(speeds) - 1)
        if speed_fraction >= speeds[k]:
            return times[k]
        share = (speed_fraction - speeds[k - 1]) / (speeds[k] - speeds[k - 1])
        return times[k - 1] + share * (times[k] - times[k - 1])

    def distance(self, speed_fraction: float, point_speed: float) -> float:
        """S_s of the fastest point, moving at `point_speed` now."""
        return self.distance_factor * point_speed * self.time(speed_fraction)


@lru_cache(maxsize=8)
def _stop_model(text: str) -> StopModel:
    """The model of one stopping file's text: parsing its YAML takes 70 ms, and every
    scenario check (each falsify range end again) and safety monitor asks for it."""
    return StopModel.from_stops(_parsed_stops(text))
