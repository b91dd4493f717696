"""The person's behaviour as pure data: plans of clip segments, cross-fades, the protocol.

`ActorState` is frozen and holds no Drake objects, so it lives in a System's abstract state
and copies cheaply. `pose_at(state, t)` gives the joint positions at any time from the state
alone; `advance(state, t, commands)` is one update of the state machine
SETUP -> IDLE <-> MOVEMENT / ANIMATION (docs: hrc_drake.human.messages).
"""

from bisect import bisect_right
from dataclasses import dataclass, field, replace
from functools import cached_property, lru_cache
from itertools import pairwise
from math import atan2, ceil, copysign, cos, degrees, hypot, inf, pi, radians, sin
from typing import NamedTuple

import numpy as np

from hrc_drake.human.body import HumanBody
from hrc_drake.human.clip import Clip
from hrc_drake.human.grasp import (
    CarryArms,
    carry_arms,
    hold_of,
    palm_targets,
    reach_target,
    release_targets,
)
from hrc_drake.human.keyed_clips import minimum_jerk, turn_clip
from hrc_drake.human.legs import Legs
from hrc_drake.human.messages import (
    NULL_QUATERNION,
    AnimateCommand,
    CancelCommand,
    Hold,
    HumanStatus,
    MoveCommand,
    SetCalledCommand,
)
from hrc_drake.human.navigation import NavigationMap
from hrc_drake.human.skeleton import SIDES
from hrc_drake.human.stepping import (
    START_PHASE,
    SWING_SLACK,
    GaitProfile,
    Spot,
    gait_profile,
    plan_steps,
    sole_target,
    standing_spots,
)
from hrc_drake.human.targeting import TARGETED, AimedMotion, Unreachable, aim_clip
from hrc_drake.messages import (
    CANCELLED,
    FAILED,
    REJECTED,
    RUNNING,
    SUCCEEDED,
    CommandResult,
    ResultLog,
    newer_commands,
)

BLEND_TIME = 0.5
"""Shortest cross-fade between activities (s)."""
BLEND_SPEED = 3.0
"""Longer fades for bigger pose changes keep the fade's peak joint speed under this (rad/s)."""
MINIMUM_JERK_PEAK = 1.875
"""Peak speed of a minimum-jerk fade relative to its average."""
SEGMENT_BLEND = 0.3
"""Cross-fade between the turn and walk parts of one movement (s)."""
MAX_TURN_PER_CYCLE = radians(90.0)
"""A turn on the spot takes two steps of at most half this each per cycle."""
TURN_ROUNDING = 3.0
"""Degrees: turn clips are authored (once per angle) for multiples of this."""
SPEED_RAMP = 0.6
"""Seconds to reach walking speed, and to stop."""
MIN_TURN = radians(3.0)
MIN_LEG = 0.3
"""m: shorter legs between waypoints are dropped."""
SHARP_CORNER = radians(75.0)
"""Walks turn through corners up to this; at sharper ones the person stops and turns."""
CORNER_RADIUS = 0.4
"""Around a waypoint the heading turns smoothly over this distance (m)."""
IDLE_CLIP = "idle"
RELEASING = ("place_floor", "place_table", "hand_over")
"""Clips that, aimed while holding something, put it down (or hand it over)."""


@dataclass(frozen=True)
class Context:
    """What every pose computation needs: the body's joint layout and the clips; and the
    cell's navigation map, which walks go round (None: walk straight)."""

    body: HumanBody
    clips: dict[str, Clip]
    navigation: NavigationMap | None = None

    def index(self, name: str) -> int:
        return self.body.index(name)

    @cached_property
    def root(self) -> tuple[int, int, int]:
        """Indices of base_x, base_y and base_yaw, looked up once: every pose places the root."""
        return self.index("base_x"), self.index("base_y"), self.index("base_yaw")

    @cached_property
    def legs(self) -> Legs:
        """The legs in closed form (walking places the feet on its steps)."""
        return Legs(self.body)

    @cached_property
    def standing(self) -> np.ndarray:
        """Standing at ease (the idle clip's first pose, at the origin): where walks set off
        from and come to rest in."""
        return self.clips[IDLE_CLIP].sample(0.0)

    def gait(self, clip: Clip) -> GaitProfile:
        return gait_profile(self.legs, clip)


def _wrap(angle: float) -> float:
    return (angle + pi) % (2 * pi) - pi


def place(ctx: Context, q: np.ndarray, x: float, y: float, yaw: float) -> np.ndarray:
    """A clip pose (root in the clip frame) put into the world at (x, y) facing yaw."""
    ix, iy, iyaw = ctx.root
    placed = q.copy()
    qx, qy = float(q[ix]), float(q[iy])
    c, s = cos(yaw), sin(yaw)
    placed[ix] = x + c * qx - s * qy
    placed[iy] = y + s * qx + c * qy
    placed[iyaw] = yaw + float(q[iyaw])
    return placed


def travel(t: float, distance: float, speed: float, ramp: float = SPEED_RAMP):
    """Distance covered and the total time of a move that speeds up and slows down smoothly.

    Speed follows smoothstep ramps of `ramp` seconds; a short move never reaches `speed`.
    """
    if distance <= 0.0:
        return 0.0, 0.0
    cruise = min(speed, distance / ramp)
    total = distance / cruise + ramp
    t = min(max(t, 0.0), total)

    def ramp_distance(u):
        return cruise * ramp * (u**3 - u**4 / 2)

    if t < ramp:
        return ramp_distance(t / ramp), total
    if t > total - ramp:
        return distance - ramp_distance((total - t) / ramp), total
    return cruise * ramp / 2 + cruise * (t - ramp), total


# --- plan segments ------------------------------------------------------------------------------


@dataclass(frozen=True, eq=False)
class ClipSegment:
    """A clip played in place (idle loops for ever), optionally aimed at a target."""

    clip: str
    start: float
    anchor: tuple[float, float, float]
    speed: float = 1.0
    forever: bool = False
    aim: AimedMotion | None = None
    carry: CarryArms | None = None
    """Arms held in the carry posture (not with `aim`, which blends them itself)."""

    def end(self, ctx: Context) -> float:
        return inf if self.forever else self.start + ctx.clips[self.clip].duration / self.speed

    def clip_time(self, ctx: Context, t: float) -> float:
        clip_time = (t - self.start) * self.speed
        return (
            clip_time if self.forever else min(max(clip_time, 0.0), ctx.clips[self.clip].duration)
        )

    def pose(self, ctx: Context, t: float) -> np.ndarray:
        clip_time = self.clip_time(ctx, t)
        q = ctx.clips[self.clip].sample(clip_time)
        placed = place(ctx, q, *self.anchor)
        if self.aim is not None:
            return self.aim.pose(placed, clip_time)
        return _carried(placed, self.carry)


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
    def between(cls, ctx: Context, start, position, yaw_from, yaw_to, carry=None):
        change = yaw_to - yaw_from
        cycles = ceil(abs(change) / MAX_TURN_PER_CYCLE) if abs(change) >= MIN_TURN else 0
        if cycles == 0:
            return cls(start, position, yaw_from, yaw_to, ctx.clips[IDLE_CLIP], 0, carry)
        step = round(degrees(change / cycles) / TURN_ROUNDING) * TURN_ROUNDING
        clip = _turn_clip(ctx.body, step or copysign(TURN_ROUNDING, change))
        return cls(start, position, yaw_from, yaw_to, clip, cycles, carry)

    def end(self, ctx: Context) -> float:
        return self.start + self.cycles * self.clip.duration

    def finishing(self, t: float) -> "TurnSegment":
        """This turn cut short after the cycle (two steps) under way at t, turned as far as
        those cycles step."""
        cycles = min(max(ceil((t - self.start) / self.clip.duration), 1), self.cycles)
        if cycles == self.cycles:
            return self
        stepped = cycles * float(self.clip.root_shift[self.clip.joint_names.index("base_yaw")])
        return replace(self, yaw_to=self.yaw_from + stepped, cycles=cycles)

    def pose(self, ctx: Context, t: float) -> np.ndarray:
        total = self.cycles * self.clip.duration
        clip_time = min(max(t - self.start, 0.0), total)
        q = self.clip.sample(clip_time)
        stepped = float(q[ctx.root[2]]) if self.cycles else 0.0
        authored = self.cycles * float(self.clip.root_shift[ctx.root[2]])
        rest = self.yaw_to - self.yaw_from - authored
        q[ctx.root[2]] = stepped + rest * minimum_jerk(clip_time / total if total else 1.0)
        return _carried(place(ctx, q, *self.position, self.yaw_from), self.carry)


@lru_cache(maxsize=256)
def _turn_clip(body: HumanBody, step_degrees: float) -> Clip:
    return turn_clip(body, step_degrees)


@dataclass(frozen=True, eq=False)
class WalkSegment:
    """Walk along a polyline from a standstill to a standstill, on footsteps
    (hrc_drake.human.stepping): the gait clip's phase runs with time, the pelvis along the
    path (speeding up and slowing down smoothly), the legs onto the planned steps.

    The path's legs are kept as plain floats: a pose looks up one point and one heading, and
    scalar arithmetic is quicker than numpy's for that.
    """

    start: float
    path: tuple[tuple[float, float], ...]
    clip: str
    animation_distance: float
    speed: float
    carry: CarryArms | None = None
    steps: dict = field(default_factory=dict)
    """Per side, the foot's stances (stepping.Stance) and their strike times."""
    over: float = 0.0
    """When the last foot stands flat at the goal."""
    halt: tuple[float, float, float, float] | None = None
    """(time, distance, speed, ramp): from then on the walk slows to a stop as soon as it
    can (cancelled), covering speed * ramp / 2 more."""
    final_turn: float = 0.0
    """How far the heading turns from the last leg's direction over the walk's last steps
    (`final_room`), so that the person arrives facing the way they are to stand."""

    def facing_at_the_end(self, yaw: float) -> "WalkSegment":
        """The walk turning to face `yaw` over its last steps where the corner rule allows
        (else as it is: the person turns on the spot after it)."""
        turn = _wrap(yaw - self.directions[-1])
        return (
            replace(self, final_turn=turn)
            if walkable_turn(turn, final_room(self.lengths))
            else self
        )

    def halted(self, ctx: Context, t: float) -> "WalkSegment":
        """This walk coming to a stop from t as soon as it can: the feet keep the steps they
        have taken and close in a step or two; a foot in the air lands where the slowing body
        needs it (the step planned at full pace would land ahead of where the body stops)."""
        speed = self.speed_at(t)
        ramp = max(SPEED_RAMP * min(speed / self.speed, 1.0), 1e-3)
        walk = replace(self, halt=(t, self.distance(t), speed, ramp))
        kept = {
            side: stances[: bisect_right(strikes, t)]
            for side, (stances, strikes) in self.steps.items()
        }
        return walk.stepped(ctx, kept)

    def stepped(self, ctx: Context, kept=None) -> "WalkSegment":
        """This walk with its footsteps planned: the feet leave their standing places at the
        start (or have taken the `kept` steps) and close side by side at the goal."""
        clip = ctx.clips[self.clip]
        arrive = self._arrival()
        end = self.distance(arrive)
        clip_speed = clip.animation_distance / clip.duration
        stances, over = plan_steps(
            ctx.gait(clip),
            clip.duration,
            self.start,
            arrive,
            self.distance,
            lambda t: self.speed_at(t) / clip_speed,
            self.spot,
            standing_spots(ctx.legs, self._standing_place(0.0), 0.0),
            standing_spots(ctx.legs, self._standing_place(end), end),
            kept,
        )
        steps = {side: (plan, tuple(s.strike for s in plan)) for side, plan in stances.items()}
        return replace(self, steps=steps, over=over)

    def _arrival(self) -> float:
        """When the pelvis comes to rest."""
        if self.halt is not None:
            return self.halt[0] + self.halt[3]
        return self.start + travel(0.0, self.lengths[-1], self.speed)[1]

    @cached_property
    def _legs(self) -> np.ndarray:
        """Each leg's (dx, dy)."""
        return np.diff(np.array(self.path), axis=0)

    @cached_property
    def lengths(self) -> tuple[float, ...]:
        """Distance along the path to each waypoint."""
        return (0.0, *np.cumsum(np.linalg.norm(self._legs, axis=1)).tolist())

    @cached_property
    def directions(self) -> tuple[float, ...]:
        """Direction of each leg, unwrapped (no jumps of 2π between legs)."""
        legs = self._legs
        return tuple(np.unwrap(np.arctan2(legs[:, 1], legs[:, 0])).tolist())

    def end(self, ctx: Context) -> float:
        return self.over

    def distance(self, t: float) -> float:
        """How far along the path the pelvis is at t."""
        if self.halt is not None and t > self.halt[0]:
            since, covered, speed, ramp = self.halt
            u = min((t - since) / ramp, 1.0)
            return covered + speed * ramp * (u - u**3 + u**4 / 2)
        return travel(t - self.start, self.lengths[-1], self.speed)[0]

    def clip_time(self, ctx: Context, t: float) -> float:
        """Time into the walk cycle (past its duration: later cycles)."""
        return (START_PHASE * ctx.clips[self.clip].duration) + max(t - self.start, 0.0)

    def point(self, along: float) -> tuple[float, float]:
        """The path's point `along` it (before its start and past its end, straight on)."""
        lengths, path = self.lengths, self.path
        k = min(max(bisect_right(lengths, along) - 1, 0), len(path) - 2)
        s = (along - lengths[k]) / max(lengths[k + 1] - lengths[k], 1e-9)
        (x0, y0), (x1, y1) = path[k], path[k + 1]
        return x0 + s * (x1 - x0), y0 + s * (y1 - y0)

    def spot(self, along: float, lateral: float) -> Spot:
        """A foot's spot `lateral` to the left of the path at `along`, turned with it."""
        x, y = self.point(along)
        heading = self.heading(along)
        return Spot(along, lateral, x - sin(heading) * lateral, y + cos(heading) * lateral, heading)

    def _standing_place(self, pelvis: float):
        """`place` (as `spot`) for feet standing round the pelvis `pelvis` along the path:
        ahead and to the side of it as it faces there (at the goal it may face otherwise
        than the path runs)."""
        x, y = self.point(pelvis)
        heading = self.heading(pelvis)
        c, s = cos(heading), sin(heading)

        def place(along: float, lateral: float) -> Spot:
            ahead = along - pelvis
            return Spot(
                along, lateral, x + c * ahead - s * lateral, y + s * ahead + c * lateral, heading
            )

        return place

    @cached_property
    def _corner_radii(self) -> tuple[float, ...]:
        """Per waypoint, the distance before and after it over which the heading turns: at
        most CORNER_RADIUS and half of either leg, so neighbouring turns never overlap."""
        legs = np.diff(self.lengths)
        return (0.0, *(min(CORNER_RADIUS, a / 2, b / 2) for a, b in pairwise(legs)))

    def heading(self, along: float) -> float:
        """Path direction, turning smoothly through each waypoint."""
        directions, lengths, radii = self.directions, self.lengths, self._corner_radii
        heading = directions[0]
        for corner in range(1, len(directions)):
            offset = along - lengths[corner] + radii[corner]
            if offset > 0:
                w = minimum_jerk(offset / (2 * radii[corner])) if radii[corner] > 0 else 1.0
                heading += w * (directions[corner] - directions[corner - 1])
        if self.final_turn:
            room = final_room(self.lengths)
            offset = along - self.lengths[-1] + 2 * room
            if offset > 0:
                heading += minimum_jerk(offset / (2 * room)) * self.final_turn
        return heading

    def speed_at(self, t: float) -> float:
        """The pelvis's speed along the path at t (m/s)."""
        dt = 1e-3
        return (self.distance(t + dt) - self.distance(t - dt)) / (2 * dt)

    def _pace(self, t: float) -> float:
        """How far into walking the body is: its speed as a fraction of the cruising speed
        (0 standing, 1 at full pace)."""
        total = self.lengths[-1]
        cruise = min(self.speed, total / SPEED_RAMP) if total > 0 else 1.0
        return self.speed_at(t) / cruise

    def pose(self, ctx: Context, t: float) -> np.ndarray:
        clip = ctx.clips[self.clip]
        clip_time = self.clip_time(ctx, t)
        gait = clip.sample(clip_time)
        standing = ctx.standing
        pace = min(max(self._pace(t), 0.0), 1.0)
        q = standing + pace * (gait - standing)
        ix, iy, iyaw = ctx.root
        surge = float(gait[ix]) - clip_time / clip.duration * clip.animation_distance
        along = self.distance(t) + pace * surge
        heading = self.heading(along) + pace * float(gait[iyaw])
        sideways = pace * float(gait[iy])
        x, y = self.point(along)
        q[ix], q[iy], q[iyaw] = 0.0, 0.0, 0.0
        q = place(ctx, q, x - sin(heading) * sideways, y + cos(heading) * sideways, heading)
        gait_profile = ctx.gait(clip)
        targets = {}
        for side, (stances, strikes) in self.steps.items():
            k = max(bisect_right(strikes, t) - 1, 0)
            targets[side] = sole_target(
                gait_profile,
                stances,
                k,
                side,
                t,
                clip.duration,
                ctx.legs.half_foot,
                self.distance(t),
                min(self.speed_at(t) / (clip.animation_distance / clip.duration), 1.0),
                self.spot,
            )
        iz = ctx.index("pelvis_height")
        reach = min(
            ctx.legs.highest_pelvis(q, s, position, forward, _least_knee(slack))
            for s, (position, forward, slack) in targets.items()
        )
        q[iz] = min(q[iz], reach)
        for side, (position, forward, slack) in targets.items():
            if slack > 0.0:  # in the air: short of its place rather than a locked knee
                position = ctx.legs.within_reach(q, side, position, forward, STANCE_KNEE)
            q = ctx.legs.place_foot(q, side, position, forward)
        return _carried(q, self.carry)


Segment = ClipSegment | TurnSegment | WalkSegment

STANCE_KNEE = radians(10.0)
"""The least a walking stance knee bends: where the paced pelvis would need a longer leg it
rides lower. Near a straight knee a millimetre of pelvis height is a tenth of a radian of
knee, so a knee nearly locked would jerk at every small change of height."""
SWING_KNEE = radians(15.0)
"""The least a swinging leg's knee bends (until its foot settles on its step): the pelvis
rides low enough for it, and the knee never whips straight reaching for a far target."""


def _least_knee(slack: float) -> float:
    """The least knee bend of a leg whose foot may fall `slack` short of its place (in the
    air: more bent; settling: easing to a stance knee's)."""
    return STANCE_KNEE + (SWING_KNEE - STANCE_KNEE) * slack / SWING_SLACK


def _carried(q: np.ndarray, carry: CarryArms | None) -> np.ndarray:
    return q if carry is None else carry.over(q)


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

    @classmethod
    def plan(cls, ctx: Context, segments, final_pose: tuple[float, float, float]) -> "Activity":
        """The activity of `segments`, ending at `final_pose`; its end time and the offsets at
        its joins are worked out here, once, rather than at every update that needs them."""
        segments = tuple(segments)
        joins = tuple(
            difference(ctx, before.pose(ctx, after.start), after.pose(ctx, after.start))
            for before, after in pairwise(segments)
        )
        return cls(segments, joins, segments[-1].end(ctx), final_pose)

    def start(self) -> float:
        return self.segments[0].start

    def planned_pose(self, ctx: Context, t: float) -> np.ndarray:
        """The plan's pose; the joins between its segments fade the same way."""
        k = 0
        while k + 1 < len(self.segments) and t >= self.segments[k + 1].start:
            k += 1
        q = self.segments[k].pose(ctx, t)
        join = self.segments[k].start
        if k > 0 and t < join + SEGMENT_BLEND:
            q = q + fade(t - join, SEGMENT_BLEND) * self.joins[k - 1]
        return q

    def pose(self, ctx: Context, t: float) -> np.ndarray:
        q = self.planned_pose(ctx, t)
        if self.blend_offset is not None and t < self.blend_start + self.blend_time:
            q = q + fade(t - self.blend_start, self.blend_time) * self.blend_offset
        return q


def fade(elapsed: float, duration: float) -> float:
    """1 at the start of a fade, 0 at its end, minimum-jerk in between."""
    return 1.0 - minimum_jerk(elapsed / duration)


def difference(ctx: Context, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """a - b, with the yaw difference taken the short way round."""
    offset = a - b
    iyaw = ctx.root[2]
    offset[iyaw] = _wrap(float(offset[iyaw]))
    return offset


# --- the protocol -------------------------------------------------------------------------------


class ActorState(NamedTuple):
    """Everything the person remembers between updates.

    A named tuple rather than a dataclass: every update makes a new one, and a tuple's
    `_replace` costs a fraction of `dataclasses.replace`.
    """

    state: str = "SETUP"
    activity: Activity | None = None
    running: int = -1
    seen: tuple[tuple[str, int], ...] = ()
    """(issuer, newest seq taken from it), per command issuer."""
    results: ResultLog = ResultLog()
    called: bool = False
    event: str = ""
    event_count: int = 0
    activity_events: tuple[str, ...] = ()
    """Clip events fired since the current activity started (what a node waits for)."""
    last_update: float = 0.0
    start_pose: tuple[float, float, float] = (0.0, 0.0, 0.0)
    animation: str = ""
    base: tuple[float, float, float] = (0.0, 0.0, 0.0)
    """Base pose measured at the last update (the speed comes from its change)."""
    speed: float = 0.0
    pose: np.ndarray | None = None
    """Joint positions at the last update."""
    hold: Hold | None = None
    """What the hands hold once the current activity is done (the last command said)."""

    def __deepcopy__(self, memo):
        """Immutable: Drake's state copies can share it."""
        return self

    @property
    def anchor(self) -> tuple[float, float, float]:
        """Where the next activity starts: the idle spot, or where the person is now."""
        if self.state == "IDLE" and self.activity is not None:
            return self.activity.final_pose
        return self.base


def pose_at(ctx: Context, state: ActorState, t: float) -> np.ndarray:
    if state.activity is None:
        return place(ctx, ctx.clips[IDLE_CLIP].sample(0.0), *state.start_pose)
    return state.activity.pose(ctx, t)


def _idle(ctx: Context, pose: tuple[float, float, float], t: float, hold=None) -> Activity:
    segment = ClipSegment(IDLE_CLIP, t, pose, forever=True, carry=_carry(ctx, hold))
    return Activity.plan(ctx, (segment,), pose)


def _carry(ctx: Context, hold: Hold | None) -> CarryArms | None:
    return None if hold is None else carry_arms(ctx.body, hold)


def _base_pose(ctx: Context, q: np.ndarray) -> tuple[float, float, float]:
    ix, iy, iyaw = ctx.root
    return float(q[ix]), float(q[iy]), _wrap(float(q[iyaw]))


def _yaw_of(quaternion) -> float:
    w, x, y, z = quaternion
    return atan2(2 * (w * z + x * y), 1 - 2 * (y * y + z * z))


def _without_short_legs(path: list) -> list:
    """The path without waypoints closer than MIN_LEG to the point before them (the goal
    stays): a short leg would make the person swing round on the spot while walking."""
    kept = [path[0]]
    for point in path[1:-1]:
        if hypot(point[0] - kept[-1][0], point[1] - kept[-1][1]) >= MIN_LEG:
            kept.append(point)
    goal = path[-1]
    if hypot(goal[0] - kept[-1][0], goal[1] - kept[-1][1]) > 1e-3:
        kept.append(goal)
    return kept


def walkable_turn(turn: float, room: float) -> bool:
    """Whether a walk can turn its heading by `turn` over `2 * room` of its path (the stance
    foot twisting no further than a hip turns: SHARP_CORNER over 2 * CORNER_RADIUS)."""
    return abs(turn) <= SHARP_CORNER * room / CORNER_RADIUS


def final_room(lengths) -> float:
    """Half the length of a walk's end over which it turns to face the way it stands: at
    most CORNER_RADIUS and half the last leg, or a quarter of it where the walk rounds a
    corner into it (the corner may take its first half). `lengths` as WalkSegment's."""
    last_leg = lengths[-1] - lengths[-2]
    return min(CORNER_RADIUS, last_leg / (2 if len(lengths) == 2 else 4))


def _stretches(path: list) -> list[list]:
    """The path cut at its sharp corners: walked through round a corner, the stance foot
    would have to twist further than a hip turns, so the person stops there and turns on
    the spot. A corner is sharp beyond SHARP_CORNER where the heading can turn over
    2 * CORNER_RADIUS, and in proportion beyond less where a short leg leaves less room
    (the heading turns over half the shorter leg on either side)."""
    stretches, current = [], [path[0]]
    for before, corner, after in zip(path, path[1:], path[2:], strict=False):
        current.append(corner)
        turn = _wrap(
            atan2(after[1] - corner[1], after[0] - corner[0])
            - atan2(corner[1] - before[1], corner[0] - before[0])
        )
        room = min(CORNER_RADIUS, hypot(*np.subtract(corner, before)) / 2)
        room = min(room, hypot(*np.subtract(after, corner)) / 2)
        if not walkable_turn(turn, room):
            stretches.append(current)
            current = [corner]
    current.append(path[-1])
    return [*stretches, current] if len(path) > 1 else []


def plan_movement(ctx: Context, command: MoveCommand, pose, t: float) -> Activity:
    """Turn towards the path, walk it, then turn to the target orientation. Without given
    waypoints the path goes round the cell's geometry (the navigation map); a place to
    stand (a target with an orientation) that is not clear moves to the nearest that is."""
    clip = ctx.clips.get(command.animation_name)
    if clip is None or not clip.loop or clip.animation_distance <= 0:
        raise Unreachable(f"'{command.animation_name}' is not a walking animation")
    x, y, yaw = pose
    goal = tuple(command.target_position[:2])
    waypoints = command.waypoints
    standing = _yaw_of(command.target_quaternion)
    oriented = tuple(command.target_quaternion) != NULL_QUATERNION
    if ctx.navigation is not None:
        if oriented:
            goal = ctx.navigation.clear_spot(*goal, standing)
        if not waypoints:
            waypoints = ctx.navigation.path((x, y), goal)
    path = _without_short_legs([(x, y), *[tuple(p) for p in waypoints], goal])
    segments: list[Segment] = []
    start = t
    heading = yaw
    carry = _carry(ctx, command.hold)
    distance = command.animation_distance or clip.animation_distance
    speed = distance / clip.duration
    stretches = _stretches(path)
    for k, stretch in enumerate(stretches):
        first = atan2(stretch[1][1] - stretch[0][1], stretch[1][0] - stretch[0][0])
        facing = heading + _wrap(first - heading)
        if abs(facing - heading) > MIN_TURN:
            segments.append(TurnSegment.between(ctx, start, stretch[0], heading, facing, carry))
            start = segments[-1].end(ctx)
        walk = WalkSegment(start, tuple(stretch), clip.name, distance, speed, carry)
        if oriented and k == len(stretches) - 1:
            walk = walk.facing_at_the_end(standing)
        walk = walk.stepped(ctx)
        segments.append(walk)
        start = walk.end(ctx)
        heading = facing + _wrap(walk.heading(walk.lengths[-1]) - facing)
    final_yaw = heading
    if oriented:
        final_yaw = heading + _wrap(standing - heading)
        if abs(final_yaw - heading) > MIN_TURN:
            segments.append(TurnSegment.between(ctx, start, path[-1], heading, final_yaw, carry))
    if not segments:
        segments.append(TurnSegment.between(ctx, t, (x, y), yaw, yaw, carry))
    return Activity.plan(ctx, segments, (*path[-1], _wrap(final_yaw)))


def plan_animation(ctx: Context, command: AnimateCommand, pose, t: float) -> Activity:
    clip = ctx.clips.get(command.animation_name)
    if clip is None:
        raise Unreachable(f"no animation named '{command.animation_name}'")
    if command.animation_speed <= 0:
        raise Unreachable("animation_speed must be positive")
    aim, carry = None, _carry(ctx, command.hold)
    if command.target is not None or command.grasp is not None:
        if clip.name not in TARGETED:
            raise Unreachable(f"'{clip.name}' takes no target")
        hands, takes = _aimed_hands(ctx, clip, command, pose)
        if takes:
            carry = _carry(ctx, hold_of(command.grasp, pose[2]))
        placed = lambda q: place(ctx, q, *pose)  # noqa: E731
        aim = aim_clip(ctx.body, clip, placed, hands, pose[2], carry, takes)
    segment = ClipSegment(clip.name, t, pose, command.animation_speed, aim=aim, carry=carry)
    return Activity.plan(ctx, (segment,), pose)


def _aimed_hands(ctx: Context, clip: Clip, command: AnimateCommand, pose) -> tuple[dict, bool]:
    """Each aiming hand's target (position, orientation or None), and whether the clip
    takes an object: the palms on the faces of what it takes, on the faces of what they
    put down at the target, or (holding nothing) the right hand's edge of a reach on the
    target and both hands of other clips either side of it, as far apart as the clip has
    them."""
    if command.grasp is not None:
        return palm_targets(command.grasp, pose[2]), True
    if command.hold is not None:
        return release_targets(command.hold, command.target, pose[2]), False
    target = np.asarray(command.target, dtype=float)
    if clip.name == "reach":
        return reach_target(ctx.body, target, pose[2]), False
    q = place(ctx, clip.sample(clip.events[TARGETED[clip.name]]), *pose)
    hands = {s: ctx.body.frame_pose(f"{s}_hand_grasp", q).translation() for s in SIDES}
    middle = np.mean(list(hands.values()), axis=0)
    return {s: (target + p - middle, None) for s, p in hands.items()}, False


def hold_after(command, pose) -> Hold | None:
    """What the hands hold once `command` is done: what it takes, nothing after it puts
    something down (a place, or a hand-over giving what the hands hold), else what they
    held."""
    if isinstance(command, MoveCommand):
        return command.hold
    if command.grasp is not None:
        return hold_of(command.grasp, pose[2])
    releases = command.target is not None and command.animation_name in RELEASING
    return None if releases else command.hold


def _record(state: ActorState, seq: int, outcome: str, reason: str = "") -> ActorState:
    return state._replace(results=state.results.recorded(CommandResult(seq, outcome, reason)))


def _switch(ctx: Context, actor: ActorState, activity: Activity, t: float, **changes):
    """Start `activity` at t, cross-fading from the current pose."""
    offset = difference(ctx, pose_at(ctx, actor, t), activity.planned_pose(ctx, t))
    change = float(np.max(np.abs(offset[3:])))
    duration = max(BLEND_TIME, MINIMUM_JERK_PEAK * change / BLEND_SPEED)
    activity = replace(activity, blend_offset=offset, blend_start=t, blend_time=duration)
    return actor._replace(activity=activity, activity_events=(), **changes)


def _stepping_at(ctx: Context, activity: Activity | None, t: float):
    """The walk or turn on the spot the activity is in at t (None: standing or playing a
    clip): the feet are stepping, so it cannot stop dead."""
    if activity is None:
        return None
    current = [s for s in activity.segments if s.start <= t]
    segment = current[-1] if current else None
    if isinstance(segment, WalkSegment | TurnSegment) and t < segment.end(ctx):
        return segment
    return None


def _stopping(ctx: Context, state: ActorState, t: float) -> Activity:
    """Standing idle after a cancel: at once, or a walk under way first comes to a stop in
    a step or two and a turn on the spot finishes the step it is taking (stopping dead
    would slide the feet)."""
    stepping = _stepping_at(ctx, state.activity, t)
    if stepping is None:
        return _idle(ctx, state.base, t, state.hold)
    if isinstance(stepping, TurnSegment):
        stop = stepping.finishing(t)
        pose = (*stop.position, _wrap(stop.yaw_to))
    else:
        stop = stepping.halted(ctx, t)
        along = stop.distance(stop.over)
        pose = (*stop.point(along), _wrap(stop.heading(along)))
    carry = _carry(ctx, state.hold)
    rest = ClipSegment(IDLE_CLIP, stop.end(ctx), pose, forever=True, carry=carry)
    return Activity.plan(ctx, (stop, rest), pose)


def _still_stepping(ctx: Context, activity: Activity | None, t: float):
    """A walk or turn coming to a stop (after a cancel) that what comes next must wait
    for: its segment and when it is over (none and t when nothing is under way)."""
    stepping = _stepping_at(ctx, activity, t)
    return ((stepping,), stepping.end(ctx)) if stepping is not None else ((), t)


def _handle(ctx: Context, state: ActorState, command, t: float) -> ActorState:
    if isinstance(command, SetCalledCommand):
        return _record(state._replace(called=command.called), command.seq, SUCCEEDED)
    if isinstance(command, CancelCommand):
        if state.running < 0:
            return _record(state, command.seq, SUCCEEDED, "nothing to cancel")
        state = _record(state, state.running, CANCELLED, f"cancelled by {command.seq}")
        state = _switch(
            ctx,
            state,
            _stopping(ctx, state, t),
            t,
            state="IDLE",
            running=-1,
            animation=IDLE_CLIP,
        )
        return _record(state, command.seq, SUCCEEDED)
    if state.running >= 0:
        return _record(state, command.seq, REJECTED, f"busy with command {state.running}")
    walking, t0 = _still_stepping(ctx, state.activity, t)
    try:
        if isinstance(command, MoveCommand):
            activity, mode = plan_movement(ctx, command, state.anchor, t0), "MOVEMENT"
        else:
            activity, mode = plan_animation(ctx, command, state.anchor, t0), "ANIMATION"
    except Unreachable as error:
        return _record(state, command.seq, FAILED, str(error))
    if walking:
        segments = (*walking, *activity.segments)
        activity = Activity.plan(ctx, segments, activity.final_pose)
    state = _switch(
        ctx,
        state,
        activity,
        t,
        state=mode,
        running=command.seq,
        animation=command.animation_name,
        hold=hold_after(command, state.anchor),
    )
    return _record(state, command.seq, RUNNING)


def _events(ctx: Context, state: ActorState, t0: float, t1: float) -> list[str]:
    """Clip events whose time passed between two updates (turning on the spot fires none)."""
    if state.activity is None or t1 <= t0:
        return []
    fired = []
    for segment in state.activity.segments:
        if not isinstance(segment, TurnSegment):
            a, b = segment.clip_time(ctx, t0), segment.clip_time(ctx, t1)
            if a < b:  # the segment's clip played during this update
                fired += _clip_events(ctx.clips[segment.clip], a, b)
    return fired


def _clip_events(clip: Clip, a: float, b: float) -> list[str]:
    """Events of `clip` in the clip-time span (a, b] (in any cycle of a loop); an event at
    time 0 also fires when the span starts at 0."""
    cycles = range(int(a // clip.duration), int(b // clip.duration) + 1) if clip.loop else [0]
    return [
        name
        for name, time in clip.events.items()
        if any(a < time + n * clip.duration <= b for n in cycles) or a == 0 == time
    ]


def _take_commands(ctx: Context, state: ActorState, t: float, commands: dict) -> ActorState:
    """Handle each issuer's commands not seen before, in order (most updates bring none)."""
    seen = dict(state.seen)
    for issuer, value in commands.items():
        for command in newer_commands(value, seen.get(issuer, -1), cancels=(CancelCommand,)):
            seen[issuer] = max(seen.get(issuer, -1), command.seq)
            state = _handle(ctx, state, command, t)
    if seen == dict(state.seen):
        return state
    return state._replace(seen=tuple(sorted(seen.items())))


def advance(ctx: Context, state: ActorState, t: float, commands: dict) -> ActorState:
    """One update at time t with each issuer's command port value (None, a command or a
    tuple of recent commands): the commands not seen before are handled in order."""
    previous_t = state.last_update
    if state.state == "SETUP":
        state = state._replace(
            state="IDLE",
            base=state.start_pose,
            animation=IDLE_CLIP,
            activity=_idle(ctx, state.start_pose, t),
        )
        previous_t = t
    state = _take_commands(ctx, state, t, commands)
    if state.running >= 0 and t >= state.activity.end:
        final = state.activity.final_pose
        state = _record(state, state.running, SUCCEEDED)
        idle = _idle(ctx, final, t, state.hold)
        state = _switch(ctx, state, idle, t, state="IDLE", running=-1, animation=IDLE_CLIP)
    fired = _events(ctx, state, previous_t, t) if state.state != "IDLE" else []
    q = pose_at(ctx, state, t)
    base = _base_pose(ctx, q)
    speed = 0.0
    if t > previous_t:
        speed = hypot(base[0] - state.base[0], base[1] - state.base[1]) / (t - previous_t)
    return state._replace(
        last_update=t,
        event=fired[-1] if fired else "",
        event_count=state.event_count + len(fired),
        activity_events=state.activity_events + tuple(fired),
        base=base,
        speed=speed,
        pose=q,
    )


def progress(ctx: Context, state: ActorState, t: float) -> float:
    if state.running < 0 or state.activity is None:
        last = state.results.last
        return 1.0 if last is not None and last.outcome == SUCCEEDED else 0.0
    start, end = state.activity.start(), state.activity.end
    return float(min(max((t - start) / max(end - start, 1e-9), 0.0), 1.0))


def status(ctx: Context, state: ActorState, t: float, hands_and_head: tuple) -> HumanStatus:
    """The status after an update; `hands_and_head` are the world poses of the left and right
    hand grasp frames and the head gaze frame at state.pose, (x, y, z, qw, qx, qy, qz) each."""
    left, right, head = hands_and_head
    return HumanStatus(
        state=state.state,
        progress=progress(ctx, state, t),
        base_pose=state.base,
        base_speed=state.speed,
        left_hand=left,
        right_hand=right,
        head=head,
        called=state.called,
        event=state.event,
        event_count=state.event_count,
        activity_events=state.activity_events,
        animation=state.animation,
        results=state.results,
        time=t,
    )
