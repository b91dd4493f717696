"""What the person does for a command, planned once when it arrives: the Activity of a
movement (turn towards the path, walk it round sharp corners and the cell's geometry, turn
to the target orientation), of an animation (a clip, aimed at a target or grasp with
inverse kinematics), of standing idle, and of coming to a stop after a cancel."""

from dataclasses import replace
from functools import partial
from math import atan2, cos, hypot, radians, sin

import numpy as np

from hrc_drake.human.activity import Activity
from hrc_drake.human.aiming import Unreachable
from hrc_drake.human.clip import Clip
from hrc_drake.human.clip_files import no_animation, walks
from hrc_drake.human.furniture import Furniture
from hrc_drake.human.going_in import (
    arrived_going_in,
    going_in,
    placed_going_in,
    put_on_nothing,
)
from hrc_drake.human.grasp import (
    CarryArms,
    carry_arms,
    hold_of,
    palm_targets,
    palms_level_first,
    reach_target,
    release_targets,
)
from hrc_drake.human.hand_ways import WITHDRAWAL, withdrawal
from hrc_drake.human.in_the_way import in_the_way
from hrc_drake.human.messages import NULL_QUATERNION, AnimateCommand, Box, Hold, MoveCommand
from hrc_drake.human.navigation import NavigationMap, NoWay
from hrc_drake.human.palm_room import room_for_the_palms
from hrc_drake.human.performer import IDLE_CLIP, Performer, place
from hrc_drake.human.rotations import wrap_angle
from hrc_drake.human.segments import (
    MIN_TURN,
    ClipSegment,
    Segment,
    StepBackSegment,
    TurnSegment,
)
from hrc_drake.human.skeleton import SIDES
from hrc_drake.human.step_back import stepped_back
from hrc_drake.human.targeting import APPROACH_AT, ONTO_A_TOP, TARGETED, aim_clip
from hrc_drake.human.walk_paths import cut_at_sharp_corners, without_short_legs
from hrc_drake.human.walking import WalkSegment

STOP_SHORT = 0.3
"""m: a carry ends at most this far short of its place, where what the hands hold would
be in something there (a kit carried up to a table with another on it: 7.4 cm in the other,
a cell of our own); a person stops before the box they carry touches what stands in
front. Further back the place is too far for the put-down (it would reach from there)."""
STOP_MARGIN = 0.02
"""m: what the hands hold stops this far before what stands in front (the limit it may
go in is DEPTH_LIMIT)."""
SHORTENINGS = 3
"""Tries at stopping short: each moves the end back by what the held box is in."""
HANDS_FULL = "the hands hold what they carry: no hand is free to reach"
"""Why a reach is refused while the hands hold something: planned as a put-down of what
they hold at the point reached, it said where that would go instead (collaboration's
5th-percentile woman, still holding the carton handed over when its carry was refused, was
told 142 times "what the hands hold would be 10.0 cm into 'crate 1' where it is put": the
carton's centre at the point reached, half its 0.2 m height in the crate under it)."""
FINAL_TURN_WALKING = radians(45.0)
"""A walk turns to face its place over its last steps by at most this; further, the person
turns on the spot there: the closing steps of a walk at full pace that turns further slide
a foot (measured: 50° 3.9 cm, 57° 7.7 cm, 70° 12 cm; at most 0.4 cm up to 45°)."""


def plan_movement(performer: Performer, command: MoveCommand, pose, t: float) -> Activity:
    """Turn towards the path, walk it, then turn to the target orientation. Without given
    waypoints the path goes round the cell's geometry (the navigation map); a target where
    the person would have no room to stand and turn moves to the nearest place that has.
    A carry stops short of its place where what the hands hold would end in something there
    (at most STOP_SHORT).
    Unreachable when there is no such place or no walk keeps clear of the cell."""
    carry = _carry(performer, command.hold)
    furniture = performer.furniture.with_boxes(command.nearby)
    navigation = _walked_on(performer, command, pose)
    activity = _walk(performer, command, pose, t, carry, furniture, navigation)
    if carry is None:
        return activity
    wanted = np.asarray(command.target_position[:2], dtype=float)
    depth, problem = arrived_going_in(performer, activity, carry, furniture)
    for _ in range(SHORTENINGS):
        if not problem:
            return activity
        x, y, yaw = activity.final_pose
        back = depth + STOP_MARGIN
        end = (x - back * cos(yaw), y - back * sin(yaw))
        if hypot(*(end - wanted)) > STOP_SHORT:
            break
        shorter = replace(command, target_position=end)
        activity = _walk(performer, shorter, pose, t, carry, furniture, navigation)
        depth, problem = arrived_going_in(performer, activity, carry, furniture)
    if problem:
        raise Unreachable(problem)
    return activity


def _walked_on(performer: Performer, command: MoveCommand, pose) -> NavigationMap | None:
    """The map the walk goes on: the cell's, with what stands in its way (the command's
    `in_the_way`) too where the walk on the cell's would pass through it."""
    navigation = performer.navigation
    obstacles = in_the_way(command.in_the_way)
    if navigation is None or not obstacles:
        return navigation
    if navigation.walked_into(_path(navigation, command, pose[:2]), obstacles):
        return navigation.with_obstacles(obstacles)
    return navigation


def _walk(performer: Performer, command: MoveCommand, pose, t: float, carry, furniture, navigation):
    """The walk of `plan_movement` on `navigation`, to the target or the nearest place
    with room, with what the hands hold as `carry` (None: nothing) stepped back from
    `furniture` before a first turn."""
    clip = performer.clips.get(command.animation_name)
    if clip is None or not walks(clip):
        raise Unreachable(f"'{command.animation_name}' is not a walking animation")
    x, y, yaw = pose
    standing = _yaw_of(command.target_quaternion)
    oriented = tuple(command.target_quaternion) != NULL_QUATERNION
    path = _path(navigation, command, (x, y))
    segments: list[Segment] = []
    start = t
    heading = yaw
    if carry is not None:
        back = stepped_back(performer, carry, furniture, pose, path, t)
        if back is not None:
            segments.append(back)
            start = back.end(performer)
            path = _path(navigation, command, back.end_position)
    distance = command.animation_distance or clip.animation_distance
    speed = distance / clip.duration
    stretches = cut_at_sharp_corners(path)
    for k, stretch in enumerate(stretches):
        first = atan2(stretch[1][1] - stretch[0][1], stretch[1][0] - stretch[0][0])
        facing = heading + wrap_angle(first - heading)
        if abs(facing - heading) > MIN_TURN:
            segments.append(
                TurnSegment.between(performer, start, stretch[0], heading, facing, carry)
            )
            start = segments[-1].end(performer)
        walk = WalkSegment(start, tuple(stretch), clip.name, distance, speed, carry)
        last = oriented and k == len(stretches) - 1
        if last and abs(wrap_angle(standing - walk.directions[-1])) <= FINAL_TURN_WALKING:
            walk = walk.facing_at_the_end(standing)
        walk = walk.stepped(performer)
        segments.append(walk)
        start = walk.end(performer)
        heading = facing + wrap_angle(walk.heading(walk.lengths[-1]) - facing)
    final_yaw = heading
    if oriented:
        final_yaw = heading + wrap_angle(standing - heading)
        if abs(final_yaw - heading) > MIN_TURN:
            segments.append(
                TurnSegment.between(performer, start, path[-1], heading, final_yaw, carry)
            )
    if not segments:
        segments.append(TurnSegment.between(performer, t, (x, y), yaw, yaw, carry))
    return Activity.plan(performer, segments, (*path[-1], wrap_angle(final_yaw)), furniture)


def _path(navigation: NavigationMap | None, command: MoveCommand, start) -> list:
    """The walk's path from `start` (x, y): round the cell's geometry to the nearest place
    to stand that has room (on `navigation`), through the command's waypoints."""
    goal = tuple(command.target_position[:2])
    waypoints = command.waypoints
    if navigation is not None:
        oriented = tuple(command.target_quaternion) != NULL_QUATERNION
        yaw = _yaw_of(command.target_quaternion) if oriented else None
        goal, waypoints = _walk_round(navigation, start, goal, yaw, waypoints)
    walkable = navigation.walkable if navigation is not None else None
    return without_short_legs([start, *[tuple(p) for p in waypoints], goal], walkable)


def _walk_round(navigation: NavigationMap, start, goal, yaw: float | None, waypoints):
    """The place to stand nearest `goal` that has room, and the waypoints of the walk there
    (the given ones, or round the cell's geometry)."""
    try:
        goal = navigation.clear_spot(*goal, yaw)
        return goal, waypoints or tuple(navigation.path(start, goal))
    except NoWay as error:
        raise Unreachable(str(error)) from None


def plan_animation(performer: Performer, command: AnimateCommand, pose, t: float) -> Activity:
    """Play a clip where the person stands (`pose`); with a target or a grasp, aimed at it by
    inverse kinematics, taking hold of what it grasps."""
    clip = performer.clips.get(command.animation_name)
    if clip is None:
        raise Unreachable(no_animation(command.animation_name, performer.clips))
    if command.animation_speed <= 0:
        raise Unreachable("animation_speed must be positive")
    carry = _carry(performer, command.hold)
    furniture = performer.furniture.with_boxes(command.nearby)
    played = partial(_played, performer, clip, command, pose, t, furniture=furniture)
    if command.target is None and command.grasp is None:
        return played(None, carry)
    if clip.name not in TARGETED:
        raise Unreachable(f"'{clip.name}' takes no target")
    hands, takes = _aimed_hands(performer, clip, command, pose, furniture)
    lowest = None
    if takes:
        carry = _carry(performer, hold_of(command.grasp, pose[2]))
        lowest = dict.fromkeys(hands, command.grasp.center[2] + command.grasp.size[2] / 2)
    placed = lambda q: place(performer, q, *pose)  # noqa: E731
    aim = partial(
        aim_clip, performer.body, clip, placed, hands, pose[2], carry, takes, furniture, lowest
    )
    *levels, last = palms_level_first(hands, carry, takes)
    for level in levels:  # held level where that does not go into the cell, else turned
        try:
            activity = played(aim(level=level), carry)
        except Unreachable:
            continue
        if not going_in(performer, activity.kept_clear(performer, t), t):
            return activity
    return played(aim(level=last), carry)


def _played(performer, clip, command, pose, t, aim, carry, furniture) -> Activity:
    """`clip` played where the person stands, aimed by `aim` (None: as it is)."""
    if aim is not None and len(aim.hands) == 1:
        aim = aim.with_the_other_arm_at_ease(performer.body, performer.clips[IDLE_CLIP])
    segment = ClipSegment(clip.name, t, pose, command.animation_speed, aim=aim, carry=carry)
    return Activity.plan(performer, (segment,), pose, furniture, _reached_for(clip, command, t))


def _reached_for(clip: Clip, command: AnimateCommand, t: float):
    """What the hands take and when they reach its approach point, where they slow down
    to close on it (None: the clip takes nothing)."""
    if command.grasp is None:
        return None
    grasp = command.grasp
    approach = APPROACH_AT * clip.events[TARGETED[clip.name]] / command.animation_speed
    return Box(grasp.center, grasp.yaw, grasp.size), t + approach


def _aimed_hands(
    performer: Performer, clip: Clip, command: AnimateCommand, pose, furniture: Furniture
) -> tuple[dict, bool]:
    """Each aiming hand's target (position, orientation or None), and whether the clip
    takes an object: the palms on the faces of what it takes, on the faces of what they
    put down at the target (off what stands beside it, with room for the palms), or
    (holding nothing) the right hand's edge of a reach on the target and both hands of
    other clips either side of it, as far apart as the clip has them."""
    if command.grasp is not None:
        return palm_targets(command.grasp, pose[2]), True
    if clip.name == "reach" and command.hold is not None:
        raise Unreachable(HANDS_FULL)
    if command.hold is not None:
        center = room_for_the_palms(
            performer.body, furniture, command.hold, command.target, pose[2]
        )
        problem = placed_going_in(furniture, command.hold, center, pose[2]) or (
            clip.name == ONTO_A_TOP and put_on_nothing(furniture, command.hold, center)
        )
        if problem:
            raise Unreachable(problem)
        return release_targets(command.hold, center, pose[2]), False
    target = np.asarray(command.target, dtype=float)
    if clip.name == "reach":
        return reach_target(performer.body, target, pose[2]), False
    q = place(performer, clip.sample(clip.events[TARGETED[clip.name]]), *pose)
    hands = {s: performer.body.frame_pose(f"{s}_hand_grasp", q).translation() for s in SIDES}
    middle = np.mean(list(hands.values()), axis=0)
    return {s: (target + p - middle, None) for s, p in hands.items()}, False


def plan_idle(
    performer: Performer, pose: tuple[float, float, float], t: float, hold=None
) -> Activity:
    """Standing at ease at `pose` from t on, for as long as no command comes (the arms in
    the carry posture while the hands `hold` something)."""
    segment = ClipSegment(IDLE_CLIP, t, pose, forever=True, carry=_carry(performer, hold))
    return Activity.plan(performer, (segment,), pose)


def plan_stop(
    performer: Performer, activity: Activity | None, base, hold: Hold | None, t: float
) -> Activity:
    """Standing idle after a cancel: at once, or a walk under way first comes to a stop in
    a step or two and a turn on the spot finishes the step it is taking (stopping dead
    would slide the feet); empty hands cut short on a surface (a reach) leave it first, the
    way they came. `base` is where the person stands, `hold` what the hands hold."""
    stepping = _stepping_at(performer, activity, t)
    if stepping is None:
        base = _feet_at(activity, base, t)
        withdrawing = _withdrawing(performer, activity, base, hold, t)
        if withdrawing is None:
            return plan_idle(performer, base, t, hold)
        rest = ClipSegment(IDLE_CLIP, withdrawing.end(performer), base, forever=True)
        return Activity.plan(performer, (withdrawing, rest), base, activity.furniture)
    if isinstance(stepping, ClipSegment):
        stop, pose = stepping, stepping.anchor
    elif isinstance(stepping, TurnSegment):
        stop = stepping.finishing(t)
        pose = (*stop.position, wrap_angle(stop.yaw_to))
    elif isinstance(stepping, StepBackSegment):
        stop, pose = stepping, (*stepping.end_position, stepping.yaw)
    else:
        stop = stepping.halted(performer, t)
        along = stop.distance(stop.over)
        pose = (*stop.point(along), wrap_angle(stop.heading(along)))
    carry = _carry(performer, hold)
    rest = ClipSegment(IDLE_CLIP, stop.end(performer), pose, forever=True, carry=carry)
    return Activity.plan(performer, (stop, rest), pose)


def still_stepping(performer: Performer, activity: Activity | None, t: float):
    """A walk or turn coming to a stop (after a cancel) that what comes next must wait
    for: its segment and when it is over (none and t when nothing is under way)."""
    stepping = _stepping_at(performer, activity, t)
    return ((stepping,), stepping.end(performer)) if stepping is not None else ((), t)


def _stepping_at(performer: Performer, activity: Activity | None, t: float):
    """The walk, turn on the spot or withdrawal of the hands the activity is in at t (None:
    standing or playing a clip): the feet are stepping or the hands leaving a surface, so it
    cannot stop dead."""
    segment = _segment_at(activity, t)
    under_way = isinstance(segment, WalkSegment | TurnSegment | StepBackSegment) or (
        isinstance(segment, ClipSegment) and segment.length is not None
    )
    if under_way and t < segment.end(performer):
        return segment
    return None


def _segment_at(activity: Activity | None, t: float):
    if activity is None:
        return None
    current = [s for s in activity.segments if s.start <= t]
    return current[-1] if current else None


def _feet_at(activity: Activity | None, base, t: float):
    """Where the person's feet stand at t, as a pose: a clip played in place stands where it
    was placed, however its pelvis leans (a pick cut short 2 cm into a lean and idled from
    there slid both feet 2 cm: coexistence seed 5 at 84.8 s); else `base`."""
    segment = _segment_at(activity, t)
    return segment.anchor if isinstance(segment, ClipSegment) else base


def _withdrawing(performer: Performer, activity, base, hold, t: float) -> ClipSegment | None:
    """Empty hands cut short in an aimed clip over a surface, leaving it (None: there are
    none)."""
    segment = _segment_at(activity, t)
    if hold is not None or not isinstance(segment, ClipSegment) or segment.aim is None:
        return None
    clip = performer.clips[IDLE_CLIP]
    aim = withdrawal(
        performer.body,
        activity.furniture_of(performer),
        clip,
        lambda q: place(performer, q, *base),
        activity.pose(performer, t),
        segment.aim.hands,
        base[2],
    )
    if aim is None:
        return None
    return ClipSegment(IDLE_CLIP, t, base, length=WITHDRAWAL, aim=aim)


def _carry(performer: Performer, hold: Hold | None) -> CarryArms | None:
    return None if hold is None else carry_arms(performer.body, hold)


def _yaw_of(quaternion) -> float:
    w, x, y, z = quaternion
    return atan2(2 * (w * z + x * y), 1 - 2 * (y * y + z * z))
