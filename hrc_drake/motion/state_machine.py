"""The robot's motion state machine: what RobotMotion does at each update, in plain Python.

RobotMotion (systems/robot_motion.py) reads its input ports into `MotionInputs`, hands them
with the `MotionState` it keeps to `MotionStateMachine.update` and stores the state that
comes back; its outputs are views of that state (`motion_at`, `path_rate_at`, `status`).
Kept apart from the Drake system, the protocol can be read, tested and benchmarked without
building a diagram, as the person's is (hrc_drake.human.protocol). One update:

1. measure the tool's pose and speed, the safety scale, and where execution is on the path;
2. accept each command newer than the last one seen (a Stop before the others): SetSpeed,
   Stop, a move (queued until the robot is at rest), Grip/Release (a vacuum command to the
   workpieces);
3. take the workpieces' answer to the vacuum command and the object the vacuum holds;
4. plan the queued move once the robot is at rest on no path;
5. choose the path rate's change for the next period, or end the path (stopped, arrived, or
   failed to arrive).

The state is immutable and replaced at every update, so Drake's context copies share it.

Longer than 400 lines: the state and the machine that replaces it are one protocol, read
and tested together (splitting them would split each step's rule from the fields it sets).
"""

import dataclasses
import functools
import math
from dataclasses import dataclass

import numpy as np
from pydrake.math import RigidTransform

from hrc_drake.messages import (
    CANCELLED,
    FAILED,
    FINISHED,
    REJECTED,
    RUNNING,
    SUCCEEDED,
    CommandResult,
    ResultLog,
    newer_commands,
)
from hrc_drake.motion.errors import PlanningFailed
from hrc_drake.motion.execution import Progress, desired_motion, next_progress
from hrc_drake.motion.messages import (
    IDLE,
    MOTION_COMMANDS,
    MOVING,
    PLANNING,
    STOPPED,
    STOPPING,
    Grip,
    Release,
    RobotStatus,
    SetSpeed,
    Stop,
)
from hrc_drake.motion.model import HeldPart, RestingObject
from hrc_drake.motion.planner import MotionPlanner
from hrc_drake.motion.timing import TimedPath
from hrc_drake.wiring import GRIPPER_ISSUER
from hrc_drake.workpieces.geometry import Solid
from hrc_drake.workpieces.messages import (
    ROBOT_HOLDER,
    Attach,
    Detach,
    ObjectStatus,
    WorkpiecesStatus,
)

ARRIVAL_SPEED = 0.01
"""rad/s: joint speeds below which a finished move counts as at rest."""
STEADY_HORIZON = 0.05
"""s an update may plan ahead while the robot moves along its path at a constant rate with
nothing to wait for: the updates in between would change nothing but the status's measured
tool pose and speed, so RobotMotion skips them unless an input changes
(`MotionStateMachine.unchanged`)."""
HOLDING_HORIZON = math.inf
"""Holding still with nothing to wait for, the motion is known until an input changes:
the same at every step."""


@dataclass(frozen=True)
class MotionState:
    """Everything RobotMotion remembers between updates (immutable; replaced each update).

    `path`/`progress` exist while the robot executes or stops on a path; `move_seq` is the
    running move (None while a Stop decelerates), `pending` an accepted move waiting to be
    planned (it is planned once the robot is at rest).
    """

    hold: tuple[float, ...]
    tool_pose: RigidTransform
    results: ResultLog = ResultLog()
    seen_seq: int = -1
    path: TimedPath | None = None
    progress: Progress | None = None
    move_seq: int | None = None
    stop_seq: int | None = None
    pending: object = None
    arrived_since: float | None = None
    speed_fraction: float = 1.0
    safety_scale: float = 1.0
    tool_speed: float = 0.0
    gripper_command: Attach | Detach | None = None
    gripper_waiting: bool = False
    gripper_since: float = 0.0
    held_object: int | None = None
    failed_plan: tuple | None = None
    """The last move whose plan failed, as planned (`_plan_key`), and why: every plan draws
    from the same seed, so the same move planned from the same hold fails the same way
    (`_failed_again`)."""
    mode: str = IDLE

    def __deepcopy__(self, memo):
        return self  # immutable: contexts may share it

    @functools.cached_property
    def hold_motion(self) -> np.ndarray:
        """q, v, vdot of holding still at `hold`."""
        hold = np.array(self.hold)
        return np.concatenate([hold, np.zeros(2 * hold.size)])

    def with_result(self, seq: int, outcome: str, reason: str = "") -> "MotionState":
        return self.replace(results=self.results.recorded(CommandResult(seq, outcome, reason)))

    def replace(self, **changes) -> "MotionState":
        """This state with `changes` (field names): `dataclasses.replace` without its checks
        and its frozen `__init__`, a tenth of its cost (an update replaces the state 3-5
        times); `hold_motion` is made again only when `hold` changes."""
        unknown = changes.keys() - _STATE_FIELDS
        if unknown:
            raise TypeError(f"MotionState has no field {', '.join(sorted(unknown))}")
        changed = object.__new__(MotionState)
        fields = changed.__dict__
        fields.update(self.__dict__)
        fields.update(changes)
        if "hold" in changes:
            fields.pop("hold_motion", None)
        return changed

    def motion_at(self, t: float) -> np.ndarray:
        """q, v and vdot stacked at time t: held still, or on the path (extrapolated from the
        last update, so the controller's reference is smooth between updates)."""
        if self.path is None:
            return self.hold_motion
        progress = self.progress.at(t, self.path.duration)
        return np.concatenate(desired_motion(self.path, progress))

    def path_rate_at(self, t: float) -> float:
        """The fraction of full speed the robot moves along its path at t (0 with no path):
        the speed the stopping data are tabulated by."""
        if self.path is None:
            return 0.0
        progress = self.progress.at(t, self.path.duration)
        return 0.0 if progress.finished(self.path.duration) else progress.rate

    @property
    def speed_scale(self) -> float:
        """The scale the path is traversed at: the path rate on a path, else the scale the
        next path would start at."""
        if self.path is not None:
            return self.progress.rate
        return self.speed_fraction * self.safety_scale

    def status(self) -> RobotStatus:
        return RobotStatus(
            mode=self.mode,
            results=self.results,
            tool_pose=self.tool_pose,
            tool_speed=self.tool_speed,
            speed_fraction=self.speed_fraction,
            safety_scale=self.safety_scale,
            speed_scale=self.speed_scale,
            held_object=self.held_object,
        )


_STATE_FIELDS = frozenset(field.name for field in dataclasses.fields(MotionState))


@dataclass(frozen=True)
class MotionInputs:
    """What RobotMotion read from its input ports for one update at time `t`."""

    t: float
    q: np.ndarray
    v: np.ndarray
    safety_scale: float = 1.0
    """The safety monitor's scale, clipped to [0, 1]."""
    commands: object = None
    """The robot tree's command port: None, a command or a tuple of recent commands."""
    workpieces: WorkpiecesStatus | None = None
    """None: no workpieces system is connected (Grip and Release fail)."""
    person_xy: np.ndarray | None = None
    """Where the person stands, when moves are planned around them (else None)."""


class MotionStateMachine:
    """The transitions of MotionState for one robot: its planner, options and payload."""

    def __init__(self, planner: MotionPlanner):
        self._planner = planner
        self._options = planner.options
        self._model = planner.model
        self._payload = planner.model.variant.payload

    def initial(self, q0: np.ndarray) -> MotionState:
        """Holding still at `q0`."""
        return MotionState(hold=tuple(q0), tool_pose=self._model.tool_pose(q0))

    def update(self, state: MotionState, inputs: MotionInputs) -> MotionState:
        """One update: measure, accept the new commands, answer the gripper, plan, advance."""
        t = inputs.t
        state = self._measured(state, inputs)
        for command in newer_commands(inputs.commands, state.seen_seq, cancels=(Stop,)):
            seen = max(state.seen_seq, command.seq)
            state = self._accept(state.replace(seen_seq=seen), command, inputs)
        state = self._workpieces_seen(state, inputs.workpieces, t)
        state = self._planned_when_at_rest(state, t, inputs)
        return self._advanced(state, inputs.q, inputs.v, t)

    def horizon(self, state: MotionState) -> float:
        """How long the motion after an update that left `state` is known in advance:
        HOLDING_HORIZON while holding still, STEADY_HORIZON while moving at a constant rate
        short of the path's end (nothing to wait for, plan or settle), else one period."""
        if state.pending is not None or state.gripper_waiting:
            return self._options.period
        if state.path is None:
            return HOLDING_HORIZON
        progress = state.progress
        cruising = (
            state.stop_seq is None
            and state.move_seq is not None
            and state.arrived_since is None
            and progress.rate_change == 0.0
            and progress.rate == state.speed_fraction * state.safety_scale
            and progress.tau + progress.rate * STEADY_HORIZON < state.path.duration
        )
        return STEADY_HORIZON if cruising else self._options.period

    def unchanged(self, state: MotionState, commands, safety_scale: float, workpieces) -> bool:
        """Whether an update within the horizon of the last would only measure the tool
        again: no new command, the same safety scale, the same object held (the inputs as
        MotionInputs names them)."""
        if newer_commands(commands, state.seen_seq) or safety_scale != state.safety_scale:
            return False
        if workpieces is None:
            return True
        held = workpieces.held_by(ROBOT_HOLDER)
        return (held.id if held is not None else None) == state.held_object

    def _measured(self, state: MotionState, inputs: MotionInputs) -> MotionState:
        progress = state.progress
        if state.path is not None:
            progress = progress.at(inputs.t, state.path.duration)
        tool_pose, tool_speed = self._model.tool_pose_and_speed(inputs.q, inputs.v)
        return state.replace(
            tool_pose=tool_pose,
            tool_speed=tool_speed,
            safety_scale=inputs.safety_scale,
            progress=progress,
        )

    def _accept(self, state: MotionState, command, inputs: MotionInputs) -> MotionState:
        if isinstance(command, SetSpeed):
            return _set_speed(state, command)
        if isinstance(command, Stop):
            return _stop(state, command)
        if isinstance(command, MOTION_COMMANDS):
            return _queue_move(state, command)
        if isinstance(command, Grip | Release):
            return self._switch_gripper(state, command, inputs.workpieces is not None, inputs.t)
        return state.with_result(command.seq, REJECTED, f"unknown command {type(command).__name__}")

    def _switch_gripper(self, state: MotionState, command, connected: bool, t) -> MotionState:
        """Sends the vacuum's Attach or Detach to the workpieces; the command runs until they
        answer (`_workpieces_seen`)."""
        busy = _busy(state) or ("busy: the robot is stopping" if state.path else "")
        if busy:
            return state.with_result(command.seq, REJECTED, busy)
        if not connected:
            return state.with_result(command.seq, FAILED, "no workpieces system is connected")
        gripping = isinstance(command, Grip)
        if gripping and state.held_object is not None:
            return state.with_result(command.seq, FAILED, f"already holding {state.held_object}")
        if not gripping and state.held_object is None:
            return state.with_result(command.seq, SUCCEEDED, "nothing was held")
        vacuum = (
            Attach(command.seq, ROBOT_HOLDER, max_mass=self._payload)
            if gripping
            else Detach(command.seq, ROBOT_HOLDER)
        )
        state = state.replace(gripper_command=vacuum, gripper_waiting=True, gripper_since=t)
        return state.with_result(command.seq, RUNNING)

    def _workpieces_seen(
        self, state: MotionState, status: WorkpiecesStatus | None, t: float
    ) -> MotionState:
        """The held object, and the answer to a pending gripper command, from the workpieces."""
        if status is None:
            return state
        held = status.held_by(ROBOT_HOLDER)
        held_object = held.id if held is not None else None
        if held_object != state.held_object:
            state = state.replace(held_object=held_object)
        if not state.gripper_waiting:
            return state
        seq = state.gripper_command.seq
        result = status.results_of(GRIPPER_ISSUER).result_of(seq)
        if result is not None and result.outcome in FINISHED:
            state = state.replace(gripper_waiting=False)
            return state.with_result(seq, result.outcome, result.reason)
        if t - state.gripper_since > self._options.gripper_timeout:
            state = state.replace(gripper_waiting=False)
            return state.with_result(seq, FAILED, "the workpieces system did not answer")
        return state

    def _planned_when_at_rest(self, state: MotionState, t: float, inputs) -> MotionState:
        """Plans the queued move from where the robot holds, with what the tool holds: only
        at rest, so the path starts where the robot is and at zero speed."""
        if state.pending is None or state.path is not None:
            return state
        command = state.pending
        state = state.replace(pending=None)
        held = _held_part(inputs.workpieces, state.tool_pose)
        objects = _resting_objects(inputs.workpieces)
        key = _plan_key(command, state.hold, held, inputs.person_xy, objects)
        again = _failed_again(state, key)
        if again:
            return state.with_result(command.seq, FAILED, again)
        try:
            path = self._planner.plan(
                command, np.array(state.hold), inputs.person_xy, held, objects
            )
        except PlanningFailed as failure:
            state = state.replace(failed_plan=(key, str(failure)))
            return state.with_result(command.seq, FAILED, str(failure))
        if path is None:
            return state.with_result(command.seq, SUCCEEDED, "already at the target")
        start_rate = state.speed_fraction * state.safety_scale  # the path starts at rest
        return state.replace(
            path=path,
            progress=Progress(0.0, start_rate, 0.0, t),
            move_seq=command.seq,
            arrived_since=None,
        )

    def _advanced(self, state: MotionState, q, v, t: float) -> MotionState:
        """Chooses the path rate's change for the next period, or ends the path."""
        if state.path is None:
            return state.replace(mode=PLANNING if state.pending is not None else IDLE)
        progress = state.progress
        if state.stop_seq is not None and progress.at_rest:
            return _ended(state, state.path.position(progress.tau)).with_result(
                state.stop_seq, SUCCEEDED
            )
        if state.move_seq is not None and progress.finished(state.path.duration):
            return self._arriving(state, q, v, t)
        target = 0.0 if state.stop_seq is not None else state.speed_fraction * state.safety_scale
        progress = next_progress(
            state.path,
            progress,
            target,
            self._options.period,
            self._model.acceleration_limits,
        )
        mode = MOVING if target > 0.0 else (STOPPED if progress.at_rest else STOPPING)
        return state.replace(progress=progress, mode=mode)

    def _arriving(self, state: MotionState, q, v, t: float) -> MotionState:
        """A finished path succeeds when the robot has arrived and come to rest."""
        error = float(np.max(np.abs(q - state.path.end)))
        if error < self._options.settle_tolerance and np.max(np.abs(v)) < ARRIVAL_SPEED:
            return _ended(state, state.path.end).with_result(state.move_seq, SUCCEEDED)
        since = t if state.arrived_since is None else state.arrived_since
        if t - since > self._options.settle_timeout:
            reason = f"the robot did not arrive: joint error {error:.4f} rad"
            return _ended(state, state.path.end).with_result(state.move_seq, FAILED, reason)
        return state.replace(arrived_since=since, mode=MOVING)


def _held_part(status: WorkpiecesStatus | None, tool_pose: RigidTransform) -> HeldPart | None:
    """The object the vacuum holds, where it hangs from the tool now (None: nothing)."""
    held = status.held_by(ROBOT_HOLDER) if status is not None else None
    if held is None:
        return None
    shape = Solid(held.shape, held.size).drake_shape()
    return HeldPart(shape, tool_pose.InvertAndCompose(held.pose))


def _resting_objects(status: WorkpiecesStatus | None) -> tuple[RestingObject, ...]:
    """The objects at rest on something (not held, falling or carried along a belt), where
    they are now: a path planned now keeps out of them."""
    if status is None:
        return ()
    return tuple(
        RestingObject(Solid(o.shape, o.size), o.pose, f"{o.type} {o.id}")
        for o in status.objects
        if o.holder is None and o.support is not None and _still(o)
    )


def _still(status: ObjectStatus) -> bool:
    return not np.any(status.velocity.get_coeffs())


def _plan_key(
    command, hold: tuple, held: HeldPart | None, person_xy, objects: tuple[RestingObject, ...]
) -> tuple:
    """What a plan's outcome depends on: the move as asked (its seq left out), where the
    robot holds, where what it holds hangs from the tool, where the person stands and the
    objects rest (to a tenth of a millimetre: a robot holding still measures its tool a hair
    apart each time)."""
    asked = tuple(
        _rounded(getattr(command, field.name))
        for field in dataclasses.fields(command)
        if field.name != "seq"
    )
    hanging = None if held is None else _rounded(held.X_TP)
    person = None if person_xy is None else _rounded(person_xy)
    resting = tuple((o.solid, _rounded(o.X_WO)) for o in objects)
    return (type(command).__name__, asked, hold, hanging, person, resting)


def _rounded(value):
    """A value of a plan's key, comparable: poses and arrays as rounded tuples."""
    if isinstance(value, RigidTransform):
        value = value.GetAsMatrix34()
    if isinstance(value, np.ndarray | list | tuple):
        return tuple(np.round(np.asarray(value, dtype=float), 4).ravel())
    return value


def _failed_again(state: MotionState, key: tuple) -> str:
    """Why the move of `key` failed the last time it was planned, if it was the last plan
    to fail ("": it was not). A tree retrying a target the robot cannot reach planned it
    anew at every tick: a 5 s run of a user's cell took 366 s."""
    if state.failed_plan is None or state.failed_plan[0] != key:
        return ""
    return state.failed_plan[1]


def _set_speed(state: MotionState, command: SetSpeed) -> MotionState:
    if not 0.0 <= command.fraction <= 1.0:
        reason = f"speed fraction must be in [0, 1], got {command.fraction}"
        return state.with_result(command.seq, REJECTED, reason)
    return state.replace(speed_fraction=float(command.fraction)).with_result(command.seq, SUCCEEDED)


def _stop(state: MotionState, command: Stop) -> MotionState:
    """Cancels the running or pending move; succeeds once the robot is at rest."""
    for seq in (state.move_seq, state.stop_seq, getattr(state.pending, "seq", None)):
        if seq is not None:
            state = state.with_result(seq, CANCELLED, f"cancelled by Stop {command.seq}")
    state = state.replace(move_seq=None, pending=None, stop_seq=None)
    if state.path is None:
        return state.with_result(command.seq, SUCCEEDED)
    return state.replace(stop_seq=command.seq).with_result(command.seq, RUNNING)


def _queue_move(state: MotionState, command) -> MotionState:
    """Accepts a move when nothing else runs; it is planned once the robot is at rest."""
    busy = _busy(state)
    if busy:
        return state.with_result(command.seq, REJECTED, busy)
    return state.replace(pending=command).with_result(command.seq, RUNNING)


def _busy(state: MotionState) -> str:
    """Why a new move or gripper command cannot start now ("" when it can)."""
    if state.move_seq is not None:
        return f"busy: move {state.move_seq} is running"
    if state.pending is not None:
        return f"busy: move {state.pending.seq} is being planned"
    if state.gripper_waiting:
        return f"busy: gripper command {state.gripper_command.seq} is running"
    return ""


def _ended(state: MotionState, hold: np.ndarray) -> MotionState:
    """Off the path, holding still at `hold`."""
    return state.replace(
        hold=tuple(hold),
        path=None,
        progress=None,
        move_seq=None,
        stop_seq=None,
        arrived_since=None,
        mode=PLANNING if state.pending is not None else IDLE,
    )
