"""The segments an activity is planned from: a clip played in place, a turn on the spot,
a step back and a walk (hrc_drake.human.walking). Each gives the pose at any time from its
own data and the Performer, and when it ends."""

from dataclasses import dataclass, replace
from functools import lru_cache
from math import ceil, copysign, cos, degrees, inf, radians, sin

import numpy as np

from hrc_drake.human.aiming import AimedMotion
from hrc_drake.human.body import HumanBody
from hrc_drake.human.clip import Clip
from hrc_drake.human.grasp import CarryArms
from hrc_drake.human.keyed_clips import minimum_jerk, step_back_clip, turn_clip
from hrc_drake.human.performer import IDLE_CLIP, Performer, carried, place
from hrc_drake.human.walking import WalkSegment

MAX_TURN_PER_CYCLE = radians(90.0)
"""A turn on the spot takes two steps of at most half this each per cycle."""
TURN_ROUNDING = 3.0
"""Degrees: turn clips are authored (once per angle) for multiples of this."""
MIN_TURN = radians(3.0)
"""Smaller changes of heading need no turn on the spot."""


@dataclass(frozen=True, eq=False)
class ClipSegment:
    """A clip played in place (idle loops for ever), optionally aimed at a target."""

    clip: str
    start: float
    anchor: tuple[float, float, float]
    speed: float = 1.0
    forever: bool = False
    length: float | None = None
    """Clip seconds played (None: all of it)."""
    aim: AimedMotion | None = None
    carry: CarryArms | None = None
    """Arms held in the carry posture (not with `aim`, which blends them itself)."""

    def end(self, performer: Performer) -> float:
        if self.forever:
            return inf
        return self.start + self._played(performer) / self.speed

    def _played(self, performer: Performer) -> float:
        return self.length if self.length is not None else performer.clips[self.clip].duration

    def clip_time(self, performer: Performer, t: float) -> float:
        clip_time = (t - self.start) * self.speed
        if self.forever:
            return clip_time
        return min(max(clip_time, 0.0), self._played(performer))

    def putting_down(self, performer: Performer, t: float) -> CarryArms | None:
        """The carry of what an aimed put-down holds at t on its way from the carry posture
        to above its place (None: it holds nothing to put down, or is lowering it onto its
        place, where it meets what it is put on)."""
        events = performer.clips[self.clip].events
        if self.aim is None or self.carry is None or "release" not in events:
            return None
        _, way_end = self.aim.paths[0]  # a put-down's first path is its way (held_ways)
        on_its_way = self.clip_time(performer, t) <= self.aim.times[way_end]
        return self.carry if on_its_way else None

    def taking_up(self, performer: Performer, t: float) -> CarryArms | None:
        """The carry of what an aimed pick holds at t, from its grasp on (None: it takes
        nothing, or has not taken it yet)."""
        events = performer.clips[self.clip].events
        if self.aim is None or self.carry is None or "grasp" not in events:
            return None
        return self.carry if self.clip_time(performer, t) >= events["grasp"] else None

    def holding(self, performer: Performer, t: float) -> tuple[str, ...]:
        """The sides whose hands must stay where they are at t: aimed at their targets or
        holding what they took."""
        if self.aim is not None:
            return self.aim.hands if self.aim.holds(self.clip_time(performer, t)) else ()
        return self.carry.hands if self.carry is not None else ()

    def pose(self, performer: Performer, t: float) -> np.ndarray:
        clip_time = self.clip_time(performer, t)
        q = performer.clips[self.clip].sample(clip_time)
        placed = place(performer, q, *self.anchor)
        if self.aim is not None:
            return self.aim.pose(placed, clip_time)
        return carried(placed, self.carry)

    arms_pose = pose
    """The pose as far as the arms are concerned (a WalkSegment's leaves its feet out)."""


@dataclass(frozen=True, eq=False)
class TurnSegment:
    """Step round on the spot from one heading to another: `cycles` cycles of a turn clip
    authored for the angle (rounded to TURN_ROUNDING; the rest of the angle eases in)."""

    start: float
    position: tuple[float, float]
    yaw_from: float
    yaw_to: float
    clip: Clip
    cycles: int
    carry: CarryArms | None = None

    @classmethod
    def between(cls, performer: Performer, start, position, yaw_from, yaw_to, carry=None):
        change = yaw_to - yaw_from
        cycles = ceil(abs(change) / MAX_TURN_PER_CYCLE) if abs(change) >= MIN_TURN else 0
        if cycles == 0:
            return cls(start, position, yaw_from, yaw_to, performer.clips[IDLE_CLIP], 0, carry)
        step = round(degrees(change / cycles) / TURN_ROUNDING) * TURN_ROUNDING
        clip = _turn_clip(performer.body, step or copysign(TURN_ROUNDING, change))
        return cls(start, position, yaw_from, yaw_to, clip, cycles, carry)

    def end(self, performer: Performer) -> float:
        return self.start + self.cycles * self.clip.duration

    def holding(self, performer: Performer, t: float) -> tuple[str, ...]:
        return self.carry.hands if self.carry is not None else ()

    def finishing(self, t: float) -> "TurnSegment":
        """This turn cut short after the cycle (two steps) under way at t, turned as far as
        those cycles step."""
        cycles = min(max(ceil((t - self.start) / self.clip.duration), 1), self.cycles)
        if cycles == self.cycles:
            return self
        stepped = cycles * float(self.clip.root_shift[self.clip.joint_names.index("base_yaw")])
        return replace(self, yaw_to=self.yaw_from + stepped, cycles=cycles)

    def pose(self, performer: Performer, t: float) -> np.ndarray:
        total = self.cycles * self.clip.duration
        clip_time = min(max(t - self.start, 0.0), total)
        q = self.clip.sample(clip_time)
        stepped = float(q[performer.root[2]]) if self.cycles else 0.0
        authored = self.cycles * float(self.clip.root_shift[performer.root[2]])
        rest = self.yaw_to - self.yaw_from - authored
        q[performer.root[2]] = stepped + rest * minimum_jerk(clip_time / total if total else 1.0)
        return carried(place(performer, q, *self.position, self.yaw_from), self.carry)

    arms_pose = pose


@lru_cache(maxsize=256)
def _turn_clip(body: HumanBody, step_degrees: float) -> Clip:
    return turn_clip(body, step_degrees)


STEP_BACK_ROUNDING = 0.05
"""m: steps back are authored (once per distance) for multiples of this."""


@dataclass(frozen=True, eq=False)
class StepBackSegment:
    """Two steps straight back from `position`, facing `yaw`: out from a shelf before
    turning with what the hands hold, whose corners sweep round further ahead than the
    hands hold them (hrc_drake.human.planning)."""

    start: float
    position: tuple[float, float]
    yaw: float
    clip: Clip
    carry: CarryArms | None = None

    @classmethod
    def between(cls, performer: Performer, start, position, yaw, distance, carry=None):
        """`distance` (m) is rounded to STEP_BACK_ROUNDING."""
        rounded = round(distance / STEP_BACK_ROUNDING) * STEP_BACK_ROUNDING
        return cls(start, position, yaw, _step_back_clip(performer.body, rounded), carry)

    def end(self, performer: Performer) -> float:
        return self.start + self.clip.duration

    @property
    def end_position(self) -> tuple[float, float]:
        """Where the person stands once the steps are taken."""
        back = float(self.clip.frames[-1, self.clip.joint_names.index("base_x")])
        return (self.position[0] + back * cos(self.yaw), self.position[1] + back * sin(self.yaw))

    def holding(self, performer: Performer, t: float) -> tuple[str, ...]:
        return self.carry.hands if self.carry is not None else ()

    def pose(self, performer: Performer, t: float) -> np.ndarray:
        q = self.clip.sample(min(max(t - self.start, 0.0), self.clip.duration))
        return carried(place(performer, q, *self.position, self.yaw), self.carry)

    arms_pose = pose


@lru_cache(maxsize=64)
def _step_back_clip(body: HumanBody, distance: float) -> Clip:
    return step_back_clip(body, distance)


Segment = ClipSegment | TurnSegment | StepBackSegment | WalkSegment
