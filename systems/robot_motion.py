"""RobotMotion: the robot's motion planner and executor as one Drake system.

It replaces MoveIt, ros_control and the re-planning workaround of the thesis system
(docs/thesis-system.md): a move command is planned (inverse kinematics, collision-free path, TOPP-RA
timing) inside a periodic update, then executed by advancing a path parameter whose rate is the
product of the SetSpeed fraction and the safety monitor's scale. Each update also writes the
desired motion until the next update as a quintic segment per joint (state, `desired_segment`);
while the robot cruises at a constant rate, one segment runs STEADY_HORIZON ahead, and while it
holds still one runs until something changes; the updates within it are left out unless a
command, the safety scale or the held object changes (`MotionStateMachine.horizon`,
`unchanged`);
the update also samples it at every plant step it covers (`desired_samples`), and Drake's C++
systems hand each step its sample for the inverse-dynamics controller (`add_desired_motion`),
so no Python runs between updates and nothing feeds through.
The state machine is plain Python in hrc_drake/motion/state_machine.py: this system reads its
inputs, runs one update of it, keeps the MotionState and publishes views of it.
See hrc_drake/motion/messages.py for the commands and the status."""

import numpy as np
from pydrake.common import RandomDistribution
from pydrake.common.value import AbstractValue
from pydrake.systems.framework import BasicVector, EventStatus, LeafSystem
from pydrake.systems.primitives import (
    AffineSystem,
    Demultiplexer,
    LinearTransformDensity,
    MatrixGain,
    Saturation,
    WrapToSystem,
)

from hrc_drake.iisy import VARIANTS
from hrc_drake.messages import NO_COMMANDS
from hrc_drake.motion.execution import faithful_segment, hermite_segment, step_samples
from hrc_drake.motion.options import MotionOptions
from hrc_drake.motion.planner import MotionPlanner
from hrc_drake.motion.state_machine import (
    HOLDING_HORIZON,
    STEADY_HORIZON,
    MotionInputs,
    MotionState,
    MotionStateMachine,
)
from hrc_drake.ports import message_value, value_or_none
from hrc_drake.station import StationSpec
from hrc_drake.wiring import (
    GRIPPER_ISSUER,
    ROBOT,
    ROBOT_DESIRED_CLOCK,
    ROBOT_DESIRED_DIFFERENCES,
    ROBOT_DESIRED_MOTION,
    ROBOT_DESIRED_SPLIT,
    ROBOT_MOTION,
    command_input,
    tree_issuer,
)


class RobotMotion(LeafSystem):
    """Plans and executes the robot's moves; see the module docstring.

    Inputs: `robot_tree_command` (the robot's tree's command or tuple of recent commands; None
    unconnected), `speed_scale`
    (safety scale, 1.0 when unconnected), `robot_state` (arm q, v), `workpieces_status`
    (WorkpiecesStatus, or unconnected when the scenario has no workpieces), `human_status`
    (where the person stands, for `avoid_person`; optional).
    Outputs: `desired_segment` (the time of the last update, then per joint the coefficients of
    the desired motion's quintic in the time since), `desired_samples` (that quintic sampled
    at the plant steps n h it covers, h = `sample_step`: step n's samples in slot
    n mod `sample_slots`; see `add_desired_motion`), `path_rate` (the fraction of full speed
    it moves along its path now, for the safety monitor), `robot_status`,
    `gripper_command` (the vacuum's Attach/Release for the workpieces' `robot_gripper`
    issuer, or None).
    """

    def __init__(
        self,
        station: StationSpec,
        seed: np.random.SeedSequence,
        options: MotionOptions | None = None,
        *,
        sample_step: float,
    ):
        """`seed`: the planner's stream of the run's seed; `sample_step`: the plant's time
        step, at which the controller reads the desired motion."""
        super().__init__()
        self._options = options or MotionOptions()
        self.sample_step = sample_step
        self.sample_slots = sample_slots(max(STEADY_HORIZON, self._options.period), sample_step)
        self._planner = MotionPlanner(station, self._options, seed)
        self._machine = MotionStateMachine(self._planner)
        self._n = len(VARIANTS[station.variant].joint_names)
        initial = self._machine.initial(station.initial_positions)
        self._state_index = self.DeclareAbstractState(AbstractValue.Make(initial))
        self._slot_numbers = np.arange(self.sample_slots)
        segment, _ = self._segment_ahead(initial, 0.0)
        self._segment = self.DeclareDiscreteState(segment)
        self._samples = self.DeclareDiscreteState(self._samples_of(segment))
        self._segment_end = self.DeclareDiscreteState(np.zeros(1))
        """When the desired segment ends: the next update that must run."""

        self._command = self.DeclareAbstractInputPort(
            command_input(tree_issuer(ROBOT)), message_value()
        )
        self._speed_scale = self.DeclareVectorInputPort("speed_scale", 1)
        self._robot_state = self.DeclareVectorInputPort("robot_state", 2 * self._n)
        self._workpieces = self.DeclareAbstractInputPort("workpieces_status", message_value())
        self._human = self.DeclareAbstractInputPort("human_status", message_value())
        self.DeclareStateOutputPort("desired_segment", self._segment)
        self.DeclareStateOutputPort("desired_samples", self._samples)
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
        self.DeclarePeriodicUnrestrictedUpdateEvent(self._options.period, 0.0, self._update)

    @property
    def planner(self) -> MotionPlanner:
        return self._planner

    # Outputs: from state and time only.

    def _state(self, context) -> MotionState:
        return context.get_abstract_state(self._state_index).get_value()

    def _segment_ahead(self, state: MotionState, t: float) -> tuple[np.ndarray, float]:
        """The desired segment from `t` (`desired_segment`) and how long it runs: as long as
        the state machine knows the motion ahead where one quintic follows it
        (`faithful_segment`), else one period."""
        period = self._options.period
        start = state.motion_at(t)
        horizon = self._machine.horizon(state)
        if horizon == HOLDING_HORIZON:  # a constant: its quintic holds beyond any duration
            return np.concatenate([[t], hermite_segment(start, start, period).ravel()]), horizon
        if horizon > period:
            coefficients = hermite_segment(start, state.motion_at(t + horizon), horizon)
            if faithful_segment(coefficients, state.motion_at(t + horizon / 2), horizon):
                return np.concatenate([[t], coefficients.ravel()]), horizon
        coefficients = hermite_segment(start, state.motion_at(t + period), period)
        return np.concatenate([[t], coefficients.ravel()]), period

    def _samples_of(self, segment: np.ndarray) -> np.ndarray:
        """`desired_samples` of `segment`: its steps from the one before its start on, each
        in its slot n mod `sample_slots` (the steps of a segment and their neighbours never
        share a slot)."""
        h, slots = self.sample_step, self.sample_slots
        first = round(segment[0] / h) - 1
        steps = first + (self._slot_numbers - first) % slots
        return step_samples(segment[0], segment[1:].reshape(self._n, -1), h, steps * h).ravel()

    def _calc_path_rate(self, context, output: BasicVector) -> None:
        output.SetAtIndex(0, self._state(context).path_rate_at(context.get_time()))

    def _calc_status(self, context, output: AbstractValue) -> None:
        output.set_value(self._state(context).status())

    def _calc_gripper_command(self, context, output: AbstractValue) -> None:
        command = self._state(context).gripper_command
        output.set_value(NO_COMMANDS if command is None else command)

    # The periodic update: read the inputs, run the state machine, keep its state.

    def _update(self, context, new_state) -> EventStatus:
        if self._within_segment(context):
            return EventStatus.DidNothing()
        t = context.get_time()
        state = self._machine.update(self._state(context), self._inputs(context))
        new_state.get_mutable_abstract_state(self._state_index).set_value(state)
        segment, horizon = self._segment_ahead(state, t)
        new_state.get_mutable_discrete_state(self._segment).set_value(segment)
        new_state.get_mutable_discrete_state(self._samples).set_value(self._samples_of(segment))
        new_state.get_mutable_discrete_state(self._segment_end).set_value([t + horizon])
        return EventStatus.Succeeded()

    def _within_segment(self, context) -> bool:
        """Whether the desired segment still runs and nothing it was planned on changed:
        the C++ desired motion carries on and this update is skipped."""
        end = context.get_discrete_state(self._segment_end).get_value()[0]
        if context.get_time() > end - self._options.period / 2:
            return False
        return self._machine.unchanged(
            self._state(context),
            value_or_none(self._command, context),
            self._safety_scale(context),
            value_or_none(self._workpieces, context),
        )

    def _inputs(self, context) -> MotionInputs:
        x = self._robot_state.Eval(context)
        return MotionInputs(
            t=context.get_time(),
            q=x[: self._n],
            v=x[self._n :],
            safety_scale=self._safety_scale(context),
            commands=value_or_none(self._command, context),
            workpieces=value_or_none(self._workpieces, context),
            person_xy=self._person_xy(context),
        )

    def _safety_scale(self, context) -> float:
        if not self._speed_scale.HasValue(context):
            return 1.0
        return float(np.clip(self._speed_scale.Eval(context)[0], 0.0, 1.0))

    def _person_xy(self, context):
        """Where the person stands, when moves are to be planned around them."""
        status = value_or_none(self._human, context) if self._options.avoid_person else None
        return status.base_pose[:2] if status is not None else None


def add_robot_motion(
    builder,
    station: StationSpec,
    seed: np.random.SeedSequence,
    plant,
    arm,
    controller,
    options: MotionOptions | None = None,
    workpieces=None,
) -> tuple[RobotMotion, Demultiplexer]:
    """Adds RobotMotion as ROBOT_MOTION between the plant and its RobotController, with its
    desired motion (`add_desired_motion`) sampled at the plant's steps; `seed` is the
    planner's stream of the run's seed.
    With `workpieces` (the Workpieces system) the vacuum gripper issues its `robot_gripper`
    commands and reads its status; without, Grip and Release fail with a reason. Returns
    RobotMotion and the desired motion's split (outputs q, v and vdot)."""
    motion = builder.AddNamedSystem(
        ROBOT_MOTION, RobotMotion(station, seed, options, sample_step=plant.time_step())
    )
    builder.Connect(plant.get_state_output_port(arm), motion.GetInputPort("robot_state"))
    split = add_desired_motion(builder, motion)
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
    return motion, split


def add_desired_motion(builder, motion: RobotMotion) -> Demultiplexer:
    """Adds the C++ systems that hand each plant step `motion`'s desired motion
    (`add_step_samples` of its `desired_samples`); returns their split."""
    return add_step_samples(
        builder,
        motion.GetOutputPort("desired_samples"),
        motion.sample_slots,
        motion.sample_step,
    )


def add_step_samples(builder, samples, slots: int, step: float) -> Demultiplexer:
    """Adds the C++ systems that hand each plant step (`step` apart) its samples from the
    output `samples` (`RobotMotion.desired_samples`, in `slots` slots): a clock counting
    the steps (`add_step_clock`: a one-hot vector of the step's slot), the step's samples
    (ROBOT_DESIRED_MOTION: the samples' matrix, a column per slot, times the one-hot
    vector), their differences (ROBOT_DESIRED_DIFFERENCES) and their split
    (ROBOT_DESIRED_SPLIT) into the desired state (q, v: output 0) and acceleration
    (output 1): what the controller reads at every step.

    At a time between steps (in ((n - 1) h, n h]) the outputs are those of step n. A run
    starts at time 0. The product is Drake's LinearTransformDensity (A w + b for inputs A
    and w), the one C++ primitive that multiplies two signals; its density output is never
    asked for. Per plant step at 2 ms this costs 0.13x the bare robot's whole step, the
    SymbolicVectorSystem that evaluated the segment at each step before 0.47x
    (`benchmarks/desired_motion.py`)."""
    rows = samples.size() // slots
    clock = add_step_clock(builder, slots, step)
    selected = builder.AddNamedSystem(
        ROBOT_DESIRED_MOTION, LinearTransformDensity(RandomDistribution.kUniform, slots, rows)
    )
    builder.Connect(clock, selected.get_input_port_w_in())
    builder.Connect(samples, selected.get_input_port_A())
    joints = rows // 3
    differences = builder.AddNamedSystem(
        ROBOT_DESIRED_DIFFERENCES, MatrixGain(desired_differences(joints, step))
    )
    builder.Connect(selected.get_output_port_w_out(), differences.get_input_port())
    split = builder.AddNamedSystem(ROBOT_DESIRED_SPLIT, Demultiplexer([2 * joints, joints]))
    builder.Connect(differences.get_output_port(), split.get_input_port())
    return split


def sample_slots(horizon: float, step: float) -> int:
    """Slots for the samples of a segment of up to `horizon` s at steps `step` apart: its
    steps and one more on either side, as the update's time and the steps' times may round
    either way of each other."""
    return int(np.ceil(horizon / step - 1e-9)) + 3


def add_step_clock(builder, slots: int, step: float):
    """Adds a clock whose output, from time 0, at each step n h (h = `step`) and until the
    next, is the one-hot vector e_(n mod slots), in exact integer arithmetic: a counter n
    (ROBOT_DESIRED_CLOCK; its output g_i = 1 + i - n for each slot i), wrapped into
    [2 - slots, 2) (1 for i = n mod slots, at most 0 for every other slot) and clamped to
    [0, 1]. Memory and work per step grow with the slots, not with their square (as a
    permutation matrix turning a one-hot state would: 200 MB at the smallest plant step
    the scenario allows). Returns the output."""
    slot = np.arange(slots, dtype=float)
    counter = builder.AddNamedSystem(
        ROBOT_DESIRED_CLOCK,
        AffineSystem(
            A=[[1.0]],
            B=np.zeros((1, 0)),
            f0=[1.0],
            C=-np.ones((slots, 1)),
            D=np.zeros((slots, 0)),
            y0=1.0 + slot,
            time_period=step,
        ),
    )
    wrap = builder.AddNamedSystem(f"{ROBOT_DESIRED_CLOCK}_wrap", WrapToSystem(slots))
    for i in range(slots):
        wrap.set_interval(i, 2.0 - slots, 2.0)
    clamp = builder.AddNamedSystem(
        f"{ROBOT_DESIRED_CLOCK}_clamp", Saturation(np.zeros(slots), np.ones(slots))
    )
    builder.Connect(counter.get_output_port(), wrap.get_input_port())
    builder.Connect(wrap.get_output_port(), clamp.get_input_port())
    return clamp.get_output_port()


def desired_differences(joints: int, time_step: float) -> np.ndarray:
    """The matrix taking the samples (q(t - h), q(t), q(t + h)) to q, v and vdot (stacked) as
    a plant stepping every `time_step` h can follow them exactly: v is the backward difference
    (q(t) - q(t - h)) / h and vdot the central one (q(t + h) - 2 q(t) + q(t - h)) / h².

    A discrete plant steps v' = v + h vdot, q' = q + h v' (semi-implicit Euler, as SAP
    does), so with these references and exact inverse dynamics q stays on q(t) at every
    step; with v(t) and vdot(t) instead the velocity would lag half a step and the PD hold
    a steady error of about Kd h vdot / (2 Kp), twice as large at 2 ms as at 1 ms."""
    one, none, h = np.eye(joints), np.zeros((joints, joints)), time_step
    return np.block(
        [
            [none, one, none],
            [-one / h, one / h, none],
            [one / h**2, -2.0 * one / h**2, one / h**2],
        ]
    )
