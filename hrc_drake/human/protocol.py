"""The person's protocol: the state machine SETUP -> IDLE <-> MOVEMENT / ANIMATION
(docs: hrc_drake.human.messages) as pure data and functions.

`ActorState` is frozen and holds no Drake objects, so it lives in a System's abstract state
and copies cheaply. `pose_at(performer, state, t)` gives the joint positions at any time
from the state alone; `advance(performer, state, t, commands)` is one update: it takes each
issuer's new commands, plans their activities (hrc_drake.human.planning), finishes the one
that is done, fires clip events and samples the pose; `status` is what the person reports.
A command refused is remembered, so that the same one asked again before the person has
done anything else is refused at once (`_refused_again`).
"""

from dataclasses import replace
from math import hypot
from typing import NamedTuple

import numpy as np

from hrc_drake.human.activity import Activity
from hrc_drake.human.aiming import Unreachable
from hrc_drake.human.clip import Clip
from hrc_drake.human.going_in import refuse_going_in
from hrc_drake.human.grasp import hold_of
from hrc_drake.human.in_the_way import in_the_way, rest_of_walk
from hrc_drake.human.messages import (
    CancelCommand,
    Hold,
    HumanStatus,
    InTheWayCommand,
    MoveCommand,
    SetCalledCommand,
)
from hrc_drake.human.performer import IDLE_CLIP, Performer, place
from hrc_drake.human.planning import (
    plan_animation,
    plan_idle,
    plan_movement,
    plan_stop,
    still_stepping,
)
from hrc_drake.human.rotations import wrap_angle
from hrc_drake.human.segments import StepBackSegment, TurnSegment
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

UPDATE_PERIOD = 1.0 / 60.0
"""s between the person's updates by default: above Meshcat's frame rate, so the replay
shows every pose, and well below a step's duration."""

RELEASING = ("place_floor", "place_table", "hand_over")
"""Clips that, aimed while holding something, put it down (or hand it over)."""


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
    move: MoveCommand | None = None
    """The walk under way (what it goes round when something comes into its way)."""
    refused: tuple | None = None
    """The last command refused, as asked (its seq left out), the activity it was refused
    in and why (`_refused_again`)."""

    def __deepcopy__(self, memo):
        """Immutable: Drake's state copies can share it."""
        return self

    @property
    def anchor(self) -> tuple[float, float, float]:
        """Where the next activity starts: the idle spot, or where the person is now."""
        if self.state == "IDLE" and self.activity is not None:
            return self.activity.final_pose
        return self.base


def pose_at(performer: Performer, state: ActorState, t: float) -> np.ndarray:
    """The joint positions at t, from the state alone (standing at the start pose before
    the first update)."""
    if state.activity is None:
        return place(performer, performer.clips[IDLE_CLIP].sample(0.0), *state.start_pose)
    return state.activity.pose(performer, t)


def advance(performer: Performer, state: ActorState, t: float, commands: dict) -> ActorState:
    """One update at time t with each issuer's command port value (None, a command or a
    tuple of recent commands): the commands not seen before are handled in order."""
    previous_t = state.last_update
    if state.state == "SETUP":
        state = state._replace(
            state="IDLE",
            base=state.start_pose,
            animation=IDLE_CLIP,
            activity=plan_idle(performer, state.start_pose, t),
        )
        previous_t = t
    state = _take_commands(performer, state, t, commands)
    if state.running >= 0 and t >= state.activity.end:
        final = state.activity.final_pose
        state = _record(state, state.running, SUCCEEDED)
        idle = plan_idle(performer, final, t, state.hold)
        state = _switch(performer, state, idle, t, state="IDLE", running=-1, animation=IDLE_CLIP)
    fired = _events(performer, state, previous_t, t) if state.state != "IDLE" else []
    q = pose_at(performer, state, t)
    base = _base_pose(performer, q)
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


def _take_commands(performer: Performer, state: ActorState, t: float, commands: dict) -> ActorState:
    """Handle each issuer's commands not seen before, in order (most updates bring none)."""
    seen = dict(state.seen)
    for issuer, value in commands.items():
        for command in newer_commands(value, seen.get(issuer, -1), cancels=(CancelCommand,)):
            seen[issuer] = max(seen.get(issuer, -1), command.seq)
            state = _handle(performer, state, command, t)
    if seen == dict(state.seen):
        return state
    return state._replace(seen=tuple(sorted(seen.items())))


def _handle(performer: Performer, state: ActorState, command, t: float) -> ActorState:
    if isinstance(command, SetCalledCommand):
        return _record(state._replace(called=command.called), command.seq, SUCCEEDED)
    if isinstance(command, InTheWayCommand):  # news, not an action: no result to report
        return _go_round(performer, state, command.boxes, t)
    if isinstance(command, CancelCommand):
        if state.running < 0:
            return _record(state, command.seq, SUCCEEDED, "nothing to cancel")
        state = _record(state, state.running, CANCELLED, f"cancelled by {command.seq}")
        state = _switch(
            performer,
            state,
            plan_stop(performer, state.activity, state.base, state.hold, t),
            t,
            state="IDLE",
            running=-1,
            animation=IDLE_CLIP,
        )
        return _record(state, command.seq, SUCCEEDED)
    if state.running >= 0:
        return _record(state, command.seq, REJECTED, f"busy with command {state.running}")
    walking, t0 = still_stepping(performer, state.activity, t)
    asked = None if walking else (replace(command, seq=0), (state.anchor, state.hold))
    again = _refused_again(state, asked)
    if again:
        return _record(state, command.seq, FAILED, again)
    try:
        if isinstance(command, MoveCommand):
            activity, mode = plan_movement(performer, command, state.anchor, t0), "MOVEMENT"
        else:
            activity, mode = plan_animation(performer, command, state.anchor, t0), "ANIMATION"
    except Unreachable as error:
        return _refuse(state, command.seq, str(error), asked)
    activity = _after_stepping(performer, walking, activity)
    switched = _switch(
        performer,
        state,
        activity,
        t,
        state=mode,
        running=command.seq,
        animation=command.animation_name,
        hold=hold_after(command, state.anchor),
        move=command if isinstance(command, MoveCommand) else None,
    )
    if _aimed(command):
        try:
            refuse_going_in(performer, switched.activity, t)
        except Unreachable as error:
            return _refuse(state, command.seq, str(error), asked)
    return _record(switched, command.seq, RUNNING)


def _refused_again(state: ActorState, asked) -> str:
    """Why `asked` (the command without its seq, and where the person stands and what the
    hands hold when it is asked) was refused the last time it was asked, if it was the last
    command refused ("": it was not, or `asked` is None, the person still stepping, so its
    plan would start elsewhere).

    A tree retrying a pick the person cannot make asked it every tick, and each was
    planned anew, 6.5 s of planning to the same refusal (a run at 0.03 of real time, #26).
    The same command holds the same object, target and what stands near them, so none of
    them moved; the person stands where they stood, holding what they held, so the plan
    starts from the same place. (It was the same activity once: a tree that walks to the
    place before each try, a walk of no length, had every try planned, a user's cell at 0.1
    of real time.) The memory is the person's state, in Drake's Context: a run restarted
    from a Context remembers only that run's refusals, and no other run sees them."""
    if asked is None or state.refused is None or state.refused[:2] != asked:
        return ""
    return state.refused[2]


def _refuse(state: ActorState, seq: int, reason: str, asked) -> ActorState:
    """Command `seq` failed for `reason`, remembered with `asked` (None: not remembered)."""
    refused = None if asked is None else (*asked, reason)
    return _record(state._replace(refused=refused), seq, FAILED, reason)


def _go_round(performer: Performer, state: ActorState, boxes: tuple, t: float) -> ActorState:
    """The walk under way, if the rest of it would pass through one of `boxes`: coming to a
    stop in a step or two and walking on round them; with no way round, stopped, and its
    command failed saying what is in the way."""
    if state.state != "MOVEMENT" or performer.navigation is None:
        return state
    obstacles = in_the_way(boxes)
    blocking = performer.navigation.walked_into(rest_of_walk(state.activity, t), obstacles)
    if not blocking:
        return state
    stop = plan_stop(performer, state.activity, state.base, state.hold, t)
    walking, t0 = still_stepping(performer, stop, t)
    command = replace(state.move, in_the_way=boxes)
    try:
        activity = plan_movement(performer, command, stop.final_pose, t0)
    except Unreachable as error:
        names = ", ".join(f"'{o.name}'" for o in blocking)
        state = _record(state, state.running, FAILED, f"{names} in the way: {error}")
        return _switch(performer, state, stop, t, state="IDLE", running=-1, animation=IDLE_CLIP)
    return _switch(performer, state, _after_stepping(performer, walking, activity), t, move=command)


def _after_stepping(performer: Performer, walking: tuple, activity: Activity) -> Activity:
    """`activity` after the walk or turn still coming to a stop (`walking`, if any)."""
    if not walking:
        return activity
    return Activity.plan(performer, (*walking, *activity.segments), activity.final_pose)


def _aimed(command) -> bool:
    """Whether `command` puts the hands on something (a target or a grasp)."""
    return not isinstance(command, MoveCommand) and (
        command.target is not None or command.grasp is not None
    )


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


def _switch(performer: Performer, actor: ActorState, activity: Activity, t: float, **changes):
    """Start `activity` at t, cross-fading from the current pose."""
    activity = activity.blended_from(performer, pose_at(performer, actor, t), t)
    return actor._replace(activity=activity, activity_events=(), **changes)


def _events(performer: Performer, state: ActorState, t0: float, t1: float) -> list[str]:
    """Clip events whose time passed between two updates (turning on the spot and stepping
    back fire none)."""
    if state.activity is None or t1 <= t0:
        return []
    fired = []
    for segment in state.activity.segments:
        if not isinstance(segment, TurnSegment | StepBackSegment):
            a, b = segment.clip_time(performer, t0), segment.clip_time(performer, t1)
            if a < b:  # the segment's clip played during this update
                fired += _clip_events(performer.clips[segment.clip], a, b)
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


def _base_pose(performer: Performer, q: np.ndarray) -> tuple[float, float, float]:
    ix, iy, iyaw = performer.root
    return float(q[ix]), float(q[iy]), wrap_angle(float(q[iyaw]))


def progress(performer: Performer, state: ActorState, t: float) -> float:
    if state.running < 0 or state.activity is None:
        last = state.results.last
        return 1.0 if last is not None and last.outcome == SUCCEEDED else 0.0
    start, end = state.activity.start(), state.activity.end
    return float(min(max((t - start) / max(end - start, 1e-9), 0.0), 1.0))


def status(performer: Performer, state: ActorState, t: float, hands_and_head: tuple) -> HumanStatus:
    """The status after an update; `hands_and_head` are the world poses of the left and right
    hand grasp frames and the head gaze frame at state.pose, (x, y, z, qw, qx, qy, qz) each."""
    left, right, head = hands_and_head
    return HumanStatus(
        state=state.state,
        progress=progress(performer, state, t),
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
