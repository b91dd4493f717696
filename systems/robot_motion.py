"""RobotMotion: the robot's motion planner and executor as one Drake system.

It replaces MoveIt, ros_control and the re-planning workaround of the thesis system
(docs/thesis-system.md): a move command is planned (inverse kinematics, collision-free path, TOPP-RA
timing) inside a periodic update, then executed by advancing a path parameter whose rate is the
product of the SetSpeed fraction and the safety monitor's scale. The desired state for the
inverse-dynamics controller is evaluated from that parameter and the time since the last update, so
it is smooth between updates and the system has no per-step Python events and no direct feedthrough.
See hrc_drake/motion/messages.py for the commands and the status."""

import dataclasses
import functools
from dataclasses import dataclass

import numpy as np
from pydrake.common.value import AbstractValue
from pydrake.math import RigidTransform
from pydrake.systems.framework import BasicVector, EventStatus, LeafSystem
from pydrake.systems.primitives import Demultiplexer

from hrc_drake.iisy import VARIANTS
from hrc_drake.messages import (
    CANCELLED,
    FAILED,
    FINISHED,
    NO_COMMANDS,
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
from hrc_drake.motion.options import MotionOptions
from hrc_drake.motion.planner import MotionPlanner
from hrc_drake.motion.timing import TimedPath
from hrc_drake.ports import message_value, value_or_none
from hrc_drake.station import StationSpec
from hrc_drake.wiring import (
    GRIPPER_ISSUER,
    ROBOT,
    ROBOT_DESIRED_MOTION,
    ROBOT_MOTION,
    command_input,
    tree_issuer,
)
from hrc_drake.workpieces.messages import ROBOT_HOLDER, Attach, Detach

ARRIVAL_SPEED = 0.01
"""rad/s: joint speeds below which a finished move counts as at rest."""


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
    mode: str = IDLE

    def __deepcopy__(self, memo):
        return self  # immutable: contexts may share it

    @functools.cached_property
    def hold_motion(self) -> np.ndarray:
        """q, v, vdot of holding still at `hold`."""
        hold = np.array(self.hold)
        return np.concatenate([hold, np.zeros(2 * hold.size)])

    def with_result(self, seq: int, outcome: str, reason: str = "") -> "MotionState":
        results = self.results.recorded(CommandResult(seq, outcome, reason))
        return dataclasses.replace(self, results=results)

    def replace(self, **changes) -> "MotionState":
        return dataclasses.replace(self, **changes)


class RobotMotion(LeafSystem):
    """Plans and executes the robot's moves; see the module docstring.

    Inputs: `robot_tree_command` (the robot's tree's command or tuple of recent commands; None
    unconnected), `speed_scale`
    (safety scale, 1.0 when unconnected), `robot_state` (arm q, v), `workpieces_status`
    (WorkpiecesStatus, or unconnected when the scenario has no workpieces), `human_status`
    (where the person stands, for `avoid_person`; optional).
    Outputs: `desired_motion` (q, v, vdot stacked), the same as `desired_state` (q, v) and
    `desired_acceleration`, `path_rate` (the fraction of
    full speed it moves along its path now, for the safety monitor), `robot_status`,
    `gripper_command` (the vacuum's Attach/Release for the workpieces' `robot_gripper`
    issuer, or None).
    """

    def __init__(self, station: StationSpec, options: MotionOptions | None = None):
        super().__init__()
        self._options = options or MotionOptions()
        self._planner = MotionPlanner(station, self._options)
        self._model = self._planner.model
        self._variant = VARIANTS[station.variant]
        self._n = len(self._variant.joint_names)
        q0 = station.initial_positions
        initial = MotionState(hold=tuple(q0), tool_pose=self._model.tool_pose(q0))
        self._state_index = self.DeclareAbstractState(AbstractValue.Make(initial))

        self._command = self.DeclareAbstractInputPort(
            command_input(tree_issuer(ROBOT)), message_value()
        )
        self._speed_scale = self.DeclareVectorInputPort("speed_scale", 1)
        self._robot_state = self.DeclareVectorInputPort("robot_state", 2 * self._n)
        self._workpieces = self.DeclareAbstractInputPort("workpieces_status", message_value())
        self._human = self.DeclareAbstractInputPort("human_status", message_value())
        from_state_and_time = {self.time_ticket(), self.all_state_ticket()}
        self._desired_motion = self.DeclareVectorOutputPort(
            "desired_motion", 3 * self._n, self._calc_desired_motion, from_state_and_time
        )
        self.DeclareVectorOutputPort(
            "desired_state", 2 * self._n, self._calc_desired_state, from_state_and_time
        )
        self.DeclareVectorOutputPort(
            "desired_acceleration", self._n, self._calc_desired_acceleration, from_state_and_time
        )
        self.DeclareVectorOutputPort(
            "path_rate", 1, self._calc_path_rate, {self.time_ticket(), self.all_state_ticket()}
        )
        self.DeclareAbstractOutputPort(
            "robot_status",
            message_value,
            self._calc_status,
            {self.all_state_ticket()},
        )
        self.DeclareAbstractOutputPort(
            "gripper_command",
            message_value,
            self._calc_gripper_command,
            {self.all_state_ticket()},
        )
        self.DeclarePeriodicUnrestrictedUpdateEvent(self._options.update_period, 0.0, self._update)

    @property
    def planner(self) -> MotionPlanner:
        return self._planner

    # Outputs: from state and time only.

    def _state(self, context) -> MotionState:
        return context.get_abstract_state(self._state_index).get_value()

    def _calc_desired_motion(self, context, output: BasicVector) -> None:
        """q, v and vdot stacked: held still, or on the path at the current time."""
        state = self._state(context)
        if state.path is None:
            output.SetFromVector(state.hold_motion)
            return
        progress = state.progress.at(context.get_time(), state.path.duration)
        output.SetFromVector(np.concatenate(desired_motion(state.path, progress)))

    def _calc_desired_state(self, context, output: BasicVector) -> None:
        output.SetFromVector(self._desired_motion.Eval(context)[: 2 * self._n])

    def _calc_desired_acceleration(self, context, output: BasicVector) -> None:
        output.SetFromVector(self._desired_motion.Eval(context)[2 * self._n :])

    def _calc_path_rate(self, context, output: BasicVector) -> None:
        """The fraction of full speed the robot moves along its path now (0 with no path):
        the speed the stopping data are tabulated by."""
        state = self._state(context)
        rate = 0.0
        if state.path is not None:
            progress = state.progress.at(context.get_time(), state.path.duration)
            rate = 0.0 if progress.finished(state.path.duration) else progress.rate
        output.SetAtIndex(0, rate)

    def _calc_status(self, context, output: AbstractValue) -> None:
        state = self._state(context)
        output.set_value(
            RobotStatus(
                mode=state.mode,
                results=state.results,
                tool_pose=state.tool_pose,
                tool_speed=state.tool_speed,
                speed_fraction=state.speed_fraction,
                safety_scale=state.safety_scale,
                speed_scale=self._effective_scale(state),
                held_object=state.held_object,
            )
        )

    def _calc_gripper_command(self, context, output: AbstractValue) -> None:
        command = self._state(context).gripper_command
        output.set_value(NO_COMMANDS if command is None else command)

    @staticmethod
    def _effective_scale(state: MotionState) -> float:
        if state.path is not None:
            return state.progress.rate
        return state.speed_fraction * state.safety_scale

    # The periodic update: measure, accept a command, answer the gripper, plan, advance.

    def _update(self, context, new_state) -> EventStatus:
        t = context.get_time()
        x = self._robot_state.Eval(context)
        q, v = x[: self._n], x[self._n :]
        state = self._measured(self._state(context), q, v, self._safety_scale(context), t)
        commands = value_or_none(self._command, context)
        for command in newer_commands(commands, state.seen_seq, cancels=(Stop,)):
            seen = max(state.seen_seq, command.seq)
            state = self._accept(state.replace(seen_seq=seen), command, context, t)
        state = self._workpieces_seen(state, context, t)
        state = self._planned_when_at_rest(state, t, self._person_xy(context))
        state = self._advanced(state, q, v, t)
        new_state.get_mutable_abstract_state(self._state_index).set_value(state)
        return EventStatus.Succeeded()

    def _safety_scale(self, context) -> float:
        if not self._speed_scale.HasValue(context):
            return 1.0
        return float(np.clip(self._speed_scale.Eval(context)[0], 0.0, 1.0))

    def _measured(self, state: MotionState, q, v, safety: float, t: float) -> MotionState:
        progress = state.progress
        if state.path is not None:
            progress = progress.at(t, state.path.duration)
        return state.replace(
            tool_pose=self._model.tool_pose(q),
            tool_speed=self._model.tool_speed(q, v),
            safety_scale=safety,
            progress=progress,
        )

    def _accept(self, state: MotionState, command, context, t: float) -> MotionState:
        if isinstance(command, SetSpeed):
            return self._set_speed(state, command)
        if isinstance(command, Stop):
            return self._stop(state, command)
        if isinstance(command, MOTION_COMMANDS):
            return self._queue_move(state, command)
        if isinstance(command, Grip | Release):
            return self._switch_gripper(state, command, self._workpieces.HasValue(context), t)
        return state.with_result(command.seq, REJECTED, f"unknown command {type(command).__name__}")

    @staticmethod
    def _set_speed(state: MotionState, command: SetSpeed) -> MotionState:
        if not 0.0 <= command.fraction <= 1.0:
            reason = f"speed fraction must be in [0, 1], got {command.fraction}"
            return state.with_result(command.seq, REJECTED, reason)
        return state.replace(speed_fraction=float(command.fraction)).with_result(
            command.seq, SUCCEEDED
        )

    @staticmethod
    def _stop(state: MotionState, command: Stop) -> MotionState:
        """Cancels the running or pending move; succeeds once the robot is at rest."""
        for seq in (state.move_seq, state.stop_seq, getattr(state.pending, "seq", None)):
            if seq is not None:
                state = state.with_result(seq, CANCELLED, f"cancelled by Stop {command.seq}")
        state = state.replace(move_seq=None, pending=None, stop_seq=None)
        if state.path is None:
            return state.with_result(command.seq, SUCCEEDED)
        return state.replace(stop_seq=command.seq).with_result(command.seq, RUNNING)

    def _queue_move(self, state: MotionState, command) -> MotionState:
        busy = self._busy(state)
        if busy:
            return state.with_result(command.seq, REJECTED, busy)
        return state.replace(pending=command).with_result(command.seq, RUNNING)

    @staticmethod
    def _busy(state: MotionState) -> str:
        """Why a new move or gripper command cannot start now ("" when it can)."""
        if state.move_seq is not None:
            return f"busy: move {state.move_seq} is running"
        if state.pending is not None:
            return f"busy: move {state.pending.seq} is being planned"
        if state.gripper_waiting:
            return f"busy: gripper command {state.gripper_command.seq} is running"
        return ""

    def _switch_gripper(self, state: MotionState, command, connected: bool, t) -> MotionState:
        busy = self._busy(state) or ("busy: the robot is stopping" if state.path else "")
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
            Attach(command.seq, ROBOT_HOLDER, max_mass=self._variant.payload)
            if gripping
            else Detach(command.seq, ROBOT_HOLDER)
        )
        state = state.replace(gripper_command=vacuum, gripper_waiting=True, gripper_since=t)
        return state.with_result(command.seq, RUNNING)

    def _workpieces_seen(self, state: MotionState, context, t: float) -> MotionState:
        """The held object, and the answer to a pending gripper command, from the workpieces."""
        status = value_or_none(self._workpieces, context)
        if status is None:
            return state
        held = status.held_by(ROBOT_HOLDER)
        state = state.replace(held_object=held.id if held is not None else None)
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

    def _person_xy(self, context):
        """Where the person stands, when moves are to be planned around them."""
        status = value_or_none(self._human, context) if self._options.avoid_person else None
        return status.base_pose[:2] if status is not None else None

    def _planned_when_at_rest(self, state: MotionState, t: float, person_xy) -> MotionState:
        if state.pending is None or state.path is not None:
            return state
        command = state.pending
        state = state.replace(pending=None)
        try:
            path = self._planner.plan(command, np.array(state.hold), person_xy)
        except PlanningFailed as failure:
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
            return self._ended(state, state.path.position(progress.tau)).with_result(
                state.stop_seq, SUCCEEDED
            )
        if state.move_seq is not None and progress.finished(state.path.duration):
            return self._arriving(state, q, v, t)
        target = 0.0 if state.stop_seq is not None else state.speed_fraction * state.safety_scale
        progress = next_progress(
            state.path,
            progress,
            target,
            self._options.update_period,
            self._model.acceleration_limits,
        )
        mode = MOVING if target > 0.0 else (STOPPED if progress.at_rest else STOPPING)
        return state.replace(progress=progress, mode=mode)

    def _arriving(self, state: MotionState, q, v, t: float) -> MotionState:
        """A finished path succeeds when the robot has arrived and come to rest."""
        error = float(np.max(np.abs(q - state.path.end)))
        if error < self._options.settle_tolerance and np.max(np.abs(v)) < ARRIVAL_SPEED:
            return self._ended(state, state.path.end).with_result(state.move_seq, SUCCEEDED)
        since = t if state.arrived_since is None else state.arrived_since
        if t - since > self._options.settle_timeout:
            reason = f"the robot did not arrive: joint error {error:.4f} rad"
            return self._ended(state, state.path.end).with_result(state.move_seq, FAILED, reason)
        return state.replace(arrived_since=since, mode=MOVING)

    @staticmethod
    def _ended(state: MotionState, hold: np.ndarray) -> MotionState:
        return state.replace(
            hold=tuple(hold),
            path=None,
            progress=None,
            move_seq=None,
            stop_seq=None,
            arrived_since=None,
            mode=PLANNING if state.pending is not None else IDLE,
        )


def add_robot_motion(
    builder,
    station: StationSpec,
    plant,
    arm,
    controller,
    options: MotionOptions | None = None,
    workpieces=None,
) -> RobotMotion:
    """Adds RobotMotion as "robot_motion" between the plant and its RobotController.

    The controller reads the desired motion at every plant step: one Python output
    (`desired_motion`), split into state and acceleration in C++, not three Python calls.
    Feeds the acceleration forward when the controller takes a reference acceleration. With
    `workpieces` (the Workpieces system) the vacuum gripper issues its `robot_gripper`
    commands and reads its status; without, Grip and Release fail with a reason.
    """
    motion = builder.AddNamedSystem(ROBOT_MOTION, RobotMotion(station, options))
    builder.Connect(plant.get_state_output_port(arm), motion.GetInputPort("robot_state"))
    n = motion.GetOutputPort("desired_acceleration").size()
    split = builder.AddNamedSystem(ROBOT_DESIRED_MOTION, Demultiplexer([2 * n, n]))
    builder.Connect(motion.GetOutputPort("desired_motion"), split.get_input_port())
    builder.Connect(split.get_output_port(0), controller.GetInputPort("desired_state"))
    if controller.HasInputPort("desired_acceleration"):
        builder.Connect(split.get_output_port(1), controller.GetInputPort("desired_acceleration"))
    if workpieces is not None:
        builder.Connect(
            motion.GetOutputPort("gripper_command"),
            workpieces.GetInputPort(command_input(GRIPPER_ISSUER)),
        )
        builder.Connect(
            workpieces.GetOutputPort("workpieces_status"), motion.GetInputPort("workpieces_status")
        )
    return motion
