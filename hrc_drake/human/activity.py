"""An activity: the plan of segments the person follows, and the fades that keep the pose
continuous where segments join and where one activity takes over from another."""

from dataclasses import dataclass, replace
from itertools import pairwise
from math import inf

import numpy as np

from hrc_drake.human.clearance import ArmCorrection, arm_correction
from hrc_drake.human.furniture import Furniture
from hrc_drake.human.grasp import CarryArms
from hrc_drake.human.head_room import head_correction
from hrc_drake.human.keyed_clips import fade
from hrc_drake.human.messages import Box
from hrc_drake.human.performer import Performer
from hrc_drake.human.rotations import wrap_angle
from hrc_drake.human.segments import ClipSegment, Segment

BLEND_TIME = 0.5
"""Shortest cross-fade between activities (s)."""
BLEND_SPEED = 3.0
"""Longer fades for bigger pose changes keep the fade's peak joint speed under this (rad/s)."""
MINIMUM_JERK_PEAK = 1.875
"""Peak speed of a minimum-jerk fade relative to its average."""
SEGMENT_BLEND = 0.3
"""Cross-fade between the turn and walk parts of one movement (s)."""


@dataclass(frozen=True, eq=False)
class Activity:
    """A plan of segments; a pose offset left over from the previous activity fades out.

    Fading the offset (rather than mixing two moving poses) keeps the pose continuous when a
    new activity starts and adds no more speed than the offset's own minimum-jerk decay.
    Make one with `Activity.plan`, which works out once what depends on the plan alone.
    """

    segments: tuple[Segment, ...]
    joins: tuple[np.ndarray, ...]
    """At each join between segments, the earlier segment's pose minus the later one's: the
    offset that fades out after the join."""
    end: float
    final_pose: tuple[float, float, float] = (0.0, 0.0, 0.0)
    blend_offset: np.ndarray | None = None
    blend_start: float = 0.0
    blend_time: float = BLEND_TIME
    furniture: Furniture | None = None
    """What the arms keep out of (None: the cell's furniture; an aimed clip adds the objects
    near its target)."""
    reached_for: tuple[Box, float] | None = None
    """What the hands are about to take and when they come to it: until then the arms keep
    out of it too (pushed off a box beside it, a hand on its way went into it)."""
    clear: tuple[ArmCorrection, ...] = ()
    """Keep the head (hrc_drake.human.head_room), then the arms
    (hrc_drake.human.clearance) out of the furniture, each laid over the pose before it;
    worked out once the activity takes over (`blended_from`)."""

    @classmethod
    def plan(
        cls,
        performer: Performer,
        segments,
        final_pose: tuple[float, float, float],
        furniture: Furniture | None = None,
        reached_for: tuple[Box, float] | None = None,
    ) -> "Activity":
        """The activity of `segments`, ending at `final_pose`; its end time and the offsets at
        its joins are worked out here, once, rather than at every update that needs them."""
        segments = tuple(segments)
        joins = tuple(_join(performer, before, after) for before, after in pairwise(segments))
        end = segments[-1].end(performer)
        return cls(segments, joins, end, final_pose, furniture=furniture, reached_for=reached_for)

    def furniture_of(self, performer: Performer) -> Furniture:
        """What the arms keep out of in this activity."""
        return self.furniture if self.furniture is not None else performer.furniture

    def blended_from(self, performer: Performer, pose: np.ndarray, t: float) -> "Activity":
        """This activity taking over at t from `pose`: the difference fades out, over longer
        than BLEND_TIME where the pose changes so much that the fade would be too fast; the
        arms are kept out of the furniture all the while, fades included."""
        offset = difference(performer, pose, self.planned_pose(performer, t))
        change = float(np.max(np.abs(offset[3:])))
        duration = max(BLEND_TIME, MINIMUM_JERK_PEAK * change / BLEND_SPEED)
        blended = replace(self, blend_offset=offset, blend_start=t, blend_time=duration)
        return replace(blended, clear=blended._arms_clear(performer, t))

    def kept_clear(self, performer: Performer, t: float) -> "Activity":
        """This activity from t with the head and arms kept out of the furniture, as it is
        played when it takes over from its own pose (what a plan goes into before then is
        not what the person does: `blended_from`)."""
        return replace(self, clear=self._arms_clear(performer, t))

    def _arms_clear(self, performer: Performer, t: float) -> tuple[ArmCorrection, ...]:
        """The corrections that keep the head, then the arms, out of the furniture from t to
        the end (of one loop of a clip that loops for ever)."""
        furniture = self.furniture_of(performer)
        if not furniture.pieces:
            return ()
        last = self.segments[-1]
        end = self.end
        if end == inf:
            end = max(last.start, t) + performer.clips[last.clip].duration
        early = None
        if self.reached_for is not None:
            box, until = self.reached_for
            early = (furniture.with_boxes((box,)), until)
        body = performer.body
        blended = _by_time(lambda u: self._blended_pose(performer, u, arms_only=True))
        head = head_correction(body, furniture, blended, t, end)
        heads = () if head is None else (head,)
        arms = arm_correction(
            body,
            furniture,
            lambda u: _corrected(heads, blended(u), u),
            t,
            end,
            lambda u: self._segment_at(u).holding(performer, u),
            early,
        )
        return heads if arms is None else (*heads, arms)

    def putting_down(self, performer: Performer, t: float) -> CarryArms | None:
        """The carry of what the hands hold at t to put down (None: nothing)."""
        segment = self._segment_at(t)
        return segment.putting_down(performer, t) if isinstance(segment, ClipSegment) else None

    def taking_up(self, performer: Performer, t: float) -> CarryArms | None:
        """The carry of what the hands have taken at t in a pick (None: nothing)."""
        segment = self._segment_at(t)
        return segment.taking_up(performer, t) if isinstance(segment, ClipSegment) else None

    def _segment_at(self, t: float) -> Segment:
        return self.segments[self._index_at(t)]

    def _index_at(self, t: float) -> int:
        k = 0
        while k + 1 < len(self.segments) and t >= self.segments[k + 1].start:
            k += 1
        return k

    def start(self) -> float:
        return self.segments[0].start

    def planned_pose(self, performer: Performer, t: float, arms_only: bool = False) -> np.ndarray:
        """The plan's pose (`arms_only`: as far as the arms are concerned, the segments'
        `arms_pose`); the joins between its segments fade the same way."""
        k = self._index_at(t)
        segment = self.segments[k]
        q = segment.arms_pose(performer, t) if arms_only else segment.pose(performer, t)
        join = self.segments[k].start
        if k > 0 and t < join + SEGMENT_BLEND:
            q = q + fade(t - join, SEGMENT_BLEND) * self.joins[k - 1]
        return q

    def pose(self, performer: Performer, t: float) -> np.ndarray:
        return _corrected(self.clear, self._blended_pose(performer, t), t)

    def _blended_pose(self, performer: Performer, t: float, arms_only: bool = False) -> np.ndarray:
        q = self.planned_pose(performer, t, arms_only)
        if self.blend_offset is not None and t < self.blend_start + self.blend_time:
            q = q + fade(t - self.blend_start, self.blend_time) * self.blend_offset
        return q


def _by_time(pose):
    """`pose(t)` worked out once per t, read-only: the head's and the arms' checks sample
    the same instants, the arms' verifications some of them again."""
    poses = {}

    def at(t: float) -> np.ndarray:
        if t not in poses:
            poses[t] = np.array(pose(t))
            poses[t].flags.writeable = False
        return poses[t]

    return at


def _corrected(corrections, q: np.ndarray, t: float) -> np.ndarray:
    """q with each of `corrections` laid over it in turn."""
    for correction in corrections:
        q = correction.over(q, t)
    return q


def _join(performer: Performer, before: Segment, after: Segment) -> np.ndarray:
    """Where `after` starts, the pose `before` would have there minus its own."""
    t = after.start
    return difference(performer, before.pose(performer, t), after.pose(performer, t))


def difference(performer: Performer, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """a - b, with the yaw difference taken the short way round."""
    offset = a - b
    iyaw = performer.root[2]
    offset[iyaw] = wrap_angle(float(offset[iyaw]))
    return offset
