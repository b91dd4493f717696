"""Walking: a walk from a standstill to a standstill along a path, on planned footsteps.

A WalkSegment moves the pelvis along a polyline with smooth speed ramps (`travel`), turns the
heading smoothly through each waypoint (and, at the end, to the way the person is to
stand), plays the gait clip with time and puts the feet on the steps planned for it
(hrc_drake.human.stepping). The corner rules (`walkable_turn`, `final_room`) say where a
walk can turn and where the person has to stop and turn on the spot instead.
"""

from bisect import bisect_right
from dataclasses import dataclass, field, replace
from functools import cached_property
from itertools import pairwise
from math import cos, radians, sin

import numpy as np

from hrc_drake.human.grasp import CarryArms
from hrc_drake.human.keyed_clips import fade, minimum_jerk
from hrc_drake.human.performer import Performer, carried, place
from hrc_drake.human.rotations import wrap_angle
from hrc_drake.human.stepping import (
    START_PHASE,
    SWING_SLACK,
    Spot,
    plan_steps,
    sole_target,
    standing_spots,
)

SPEED_RAMP = 0.6
"""Seconds to reach walking speed, and to stop."""
SHARP_CORNER = radians(75.0)
"""Walks turn through corners up to this; at sharper ones the person stops and turns."""
CORNER_RADIUS = 0.4
"""Around a waypoint the heading turns smoothly over this distance (m)."""
STANCE_KNEE = radians(10.0)
"""The least a walking stance knee bends: where the paced pelvis would need a longer leg it
rides lower. Near a straight knee a millimetre of pelvis height is a tenth of a radian of
knee, so a knee nearly locked would jerk at every small change of height."""
SWING_KNEE = radians(15.0)
"""The least a swinging leg's knee bends (until its foot settles on its step): the pelvis
rides low enough for it, and the knee never whips straight reaching for a far target."""


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
    feet_from: dict = field(default_factory=dict)
    """After a halt, per side (since, until, position, forward): how far the foot's sole was,
    in the walk before, from where this one has it; it fades out by the foot's next strike,
    so a foot goes on from where it was to its new step (a fade of the whole pose went on
    after the foot had landed and slid it 2-7 cm along the floor)."""

    def facing_at_the_end(self, yaw: float) -> "WalkSegment":
        """The walk turning to face `yaw` over its last steps where the corner rule allows
        (else as it is: the person turns on the spot after it)."""
        turn = wrap_angle(yaw - self.directions[-1])
        return (
            replace(self, final_turn=turn)
            if walkable_turn(turn, final_room(self.lengths))
            else self
        )

    def halted(self, performer: Performer, t: float) -> "WalkSegment":
        """This walk coming to a stop from t as soon as it can: the feet keep the steps they
        have taken and close in a step or two; a foot in the air lands where the slowing body
        needs it (the step planned at full pace would land ahead of where the body stops).
        A walk already coming to a stop goes on as it is (told again to stop, it came to a
        stop on a profile that forgot the first one's: the pelvis jumped)."""
        if self.halt is not None and t >= self.halt[0]:
            return self
        speed = self.speed_at(t)
        ramp = max(SPEED_RAMP * min(speed / self.speed, 1.0), 1e-3)
        walk = replace(self, halt=(t, self.distance(t), speed, ramp), feet_from={})
        kept = {
            side: stances[: bisect_right(strikes, t)]
            for side, (stances, strikes) in self.steps.items()
        }
        walk = walk.stepped(performer, kept)
        return replace(walk, feet_from=walk._feet_offsets(performer, self, t))

    def _feet_offsets(self, performer: Performer, before: "WalkSegment", t: float) -> dict:
        """`feet_from` taking over from the walk `before` at t."""
        theirs, ours = before._sole_targets(performer, t), self._sole_targets(performer, t)
        offsets = {}
        for side, (_, strikes) in self.steps.items():
            k = bisect_right(strikes, t)
            until = strikes[k] if k < len(strikes) else self.over
            (p, f, _), (p0, f0, _) = theirs[side], ours[side]
            offsets[side] = (t, until, np.subtract(p, p0), np.subtract(f, f0))
        return offsets

    def stepped(self, performer: Performer, kept=None) -> "WalkSegment":
        """This walk with its footsteps planned: the feet leave their standing places at the
        start (or have taken the `kept` steps) and close side by side at the goal."""
        clip = performer.clips[self.clip]
        arrive = self._arrival()
        end = self.distance(arrive)
        clip_speed = clip.animation_distance / clip.duration
        stances, over = plan_steps(
            performer.gait(clip),
            clip.duration,
            self.start,
            arrive,
            self.distance,
            lambda t: self.speed_at(t) / clip_speed,
            self.spot,
            standing_spots(performer.legs, self._standing_place(0.0), 0.0),
            standing_spots(performer.legs, self._standing_place(end), end),
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

    def end(self, performer: Performer) -> float:
        return self.over

    def holding(self, performer: Performer, t: float) -> tuple[str, ...]:
        """The sides whose hands hold something (they stay where they are)."""
        return self.carry.hands if self.carry is not None else ()

    def distance(self, t: float) -> float:
        """How far along the path the pelvis is at t."""
        if self.halt is not None and t > self.halt[0]:
            since, covered, speed, ramp = self.halt
            u = min((t - since) / ramp, 1.0)
            return covered + speed * ramp * (u - u**3 + u**4 / 2)
        return travel(t - self.start, self.lengths[-1], self.speed)[0]

    def clip_time(self, performer: Performer, t: float) -> float:
        """Time into the walk cycle (past its duration: later cycles)."""
        return (START_PHASE * performer.clips[self.clip].duration) + max(t - self.start, 0.0)

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

    def _pace(self, speed: float) -> float:
        """How far into walking the body is at `speed` along the path: as a fraction of
        the cruising speed (0 standing, 1 at full pace)."""
        total = self.lengths[-1]
        cruise = min(self.speed, total / SPEED_RAMP) if total > 0 else 1.0
        return speed / cruise

    def pose(self, performer: Performer, t: float) -> np.ndarray:
        return self._pose(performer, t, feet=True)

    def _sole_targets(self, performer: Performer, t: float, pelvis=None, speed=None) -> dict:
        """Per side, where the sole goes at t (position, forward axis, how far short of it
        the leg may fall); `pelvis` and `speed` as at t, when already worked out."""
        clip = performer.clips[self.clip]
        pelvis = self.distance(t) if pelvis is None else pelvis
        speed = self.speed_at(t) if speed is None else speed
        clip_pace = min(speed / (clip.animation_distance / clip.duration), 1.0)
        gait_profile = performer.gait(clip)
        targets = {}
        for side, (stances, strikes) in self.steps.items():
            k = max(bisect_right(strikes, t) - 1, 0)
            target = sole_target(
                gait_profile,
                stances,
                k,
                side,
                t,
                clip.duration,
                performer.legs.half_foot,
                pelvis,
                clip_pace,
                self.spot,
            )
            if side in self.feet_from:
                target = _carried_over(target, self.feet_from[side], t)
            targets[side] = target
        return targets

    def arms_pose(self, performer: Performer, t: float) -> np.ndarray:
        """The pose as far as the arms are concerned: the legs as the clip has them, the
        feet not placed (placing them moves the legs' joints only, and no arm hangs from
        a leg), which the arms' check of a whole walk need not pay for."""
        return self._pose(performer, t, feet=False)

    def _pose(self, performer: Performer, t: float, feet: bool) -> np.ndarray:
        clip = performer.clips[self.clip]
        clip_time = self.clip_time(performer, t)
        gait = clip.sample(clip_time)
        standing = performer.standing
        pelvis, speed = self.distance(t), self.speed_at(t)  # each worked out once a pose
        pace = min(max(self._pace(speed), 0.0), 1.0)
        q = standing + pace * (gait - standing)
        ix, iy, iyaw = performer.root
        surge = float(gait[ix]) - clip_time / clip.duration * clip.animation_distance
        along = pelvis + pace * surge
        heading = self.heading(along) + pace * float(gait[iyaw])
        sideways = pace * float(gait[iy])
        x, y = self.point(along)
        q[ix], q[iy], q[iyaw] = 0.0, 0.0, 0.0
        q = place(performer, q, x - sin(heading) * sideways, y + cos(heading) * sideways, heading)
        targets = self._sole_targets(performer, t, pelvis, speed)
        iz = performer.index("pelvis_height")
        reach = min(
            performer.legs.highest_pelvis(q, s, position, forward, _least_knee(slack))
            for s, (position, forward, slack) in targets.items()
        )
        q[iz] = min(q[iz], reach)
        return carried(_feet_placed(performer.legs, q, targets) if feet else q, self.carry)


def _carried_over(target, offset, t: float):
    """A sole's `target` with the `offset` (since, until, position, forward) of the walk
    before a halt, fading out from `since` to `until`."""
    since, until, position, forward = offset
    if t >= until:
        return target
    w = fade(t - since, max(until - since, 1e-9))
    moved_forward = np.add(target[1], w * forward)
    moved_forward /= np.linalg.norm(moved_forward)
    return tuple(np.add(target[0], w * position)), tuple(moved_forward), target[2]


def _feet_placed(legs, q: np.ndarray, targets: dict) -> np.ndarray:
    """q with each foot placed at its target (side: position, forward, slack)."""
    for side, (position, forward, slack) in targets.items():
        if slack > 0.0:  # in the air: short of its place rather than a locked knee
            position = legs.within_reach(q, side, position, forward, STANCE_KNEE)
        q = _above_the_floor(
            legs, legs.place_foot(q, side, position, forward), side, position, forward
        )
    return q


def _above_the_floor(legs, q, side: str, position, forward) -> np.ndarray:
    """q with the `side` foot, placed at `position`, raised as far as its sole's edge would
    reach under the floor (a rolled foot in the air, or landing on its heel)."""
    under = legs.under_the_floor(q, side)
    if under <= 0.0:
        return q
    return legs.place_foot(q, side, np.asarray(position) + [0.0, 0.0, under], forward)


def _least_knee(slack: float) -> float:
    """The least knee bend of a leg whose foot may fall `slack` short of its place (in the
    air: more bent; settling: easing to a stance knee's)."""
    return STANCE_KNEE + (SWING_KNEE - STANCE_KNEE) * slack / SWING_SLACK


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
