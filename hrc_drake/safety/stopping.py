"""The robot's stop as S_p needs it: stopping time and distance as functions of the speed it
moves at now, from the variant's measured stopping data (`hrc_drake.motion.stopping`).

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

from hrc_drake.motion.stopping import Stop, load_stops


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
        return cls.from_stops(load_stops(variant))

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
