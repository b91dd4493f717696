"""The robot's motion state machine without a diagram: commands, the vacuum handshake with
the workpieces and planning at rest, driven update by update with hand-made inputs."""

import numpy as np
import pytest
from pydrake.math import RigidTransform, RollPitchYaw

from hrc_drake.iisy import VARIANTS
from hrc_drake.messages import (
    CANCELLED,
    FAILED,
    REJECTED,
    RUNNING,
    SUCCEEDED,
    CommandResult,
    ResultLog,
)
from hrc_drake.motion.messages import (
    IDLE,
    MOVING,
    STOPPING,
    Grip,
    MoveJoints,
    MoveTo,
    Release,
    Stop,
)
from hrc_drake.motion.options import MotionOptions
from hrc_drake.motion.planner import MotionPlanner
from hrc_drake.motion.state_machine import MotionInputs, MotionStateMachine
from hrc_drake.seeding import stream
from hrc_drake.wiring import GRIPPER_ISSUER, ROBOT_MOTION
from hrc_drake.workpieces.messages import ROBOT_HOLDER, Attach, WorkpiecesStatus
from tests.motion.motion_helpers import make_scenario

PERIOD = MotionOptions().period
SILENT = WorkpiecesStatus(0.0, (), {}, {})
"""The workpieces, holding nothing, before they answer the gripper."""


@pytest.fixture(scope="module")
def machine():
    return MotionStateMachine(
        MotionPlanner(make_scenario().station, MotionOptions(), stream(0, ROBOT_MOTION))
    )


@pytest.fixture(scope="module")
def home():
    return np.array(VARIANTS["lbr_iisy3_r760"].home)


def at_rest(home, t: float, commands=None, workpieces=None) -> MotionInputs:
    """The robot standing still at home at time t."""
    return MotionInputs(t, home, np.zeros_like(home), commands=commands, workpieces=workpieces)


def answered(seq: int, outcome: str) -> WorkpiecesStatus:
    """The workpieces, holding nothing, with the gripper's command `seq` answered."""
    results = ResultLog().recorded(CommandResult(seq, outcome))
    return WorkpiecesStatus(0.0, (), {GRIPPER_ISSUER: results}, {})


def test_grip_without_workpieces_fails_with_reason(machine, home):
    state = machine.update(machine.initial(home), at_rest(home, 0.0, Grip(1)))
    assert state.results.result_of(1).outcome == FAILED
    assert "no workpieces system" in state.results.result_of(1).reason


def test_grip_sends_attach_and_takes_the_workpieces_answer(machine, home):
    state = machine.update(machine.initial(home), at_rest(home, 0.0, Grip(1), SILENT))
    assert state.gripper_command == Attach(
        1, ROBOT_HOLDER, max_mass=VARIANTS["lbr_iisy3_r760"].payload
    )
    assert state.results.outcome_of(1) == RUNNING
    busy = machine.update(state, at_rest(home, PERIOD, (Grip(1), MoveJoints(2)), SILENT))
    assert busy.results.outcome_of(2) == REJECTED
    done = machine.update(busy, at_rest(home, 2 * PERIOD, None, answered(1, FAILED)))
    assert done.results.outcome_of(1) == FAILED and not done.gripper_waiting


def test_gripper_times_out_when_the_workpieces_never_answer(machine, home):
    state = machine.update(machine.initial(home), at_rest(home, 0.0, Grip(1), SILENT))
    late = MotionOptions().gripper_timeout + PERIOD
    state = machine.update(state, at_rest(home, late, None, SILENT))
    assert state.results.result_of(1).reason == "the workpieces system did not answer"


def test_release_with_nothing_held_succeeds_at_once(machine, home):
    state = machine.update(machine.initial(home), at_rest(home, 0.0, Release(1), SILENT))
    assert state.results.result_of(1) == CommandResult(1, SUCCEEDED, "nothing was held")
    assert state.gripper_command is None


def test_a_move_is_planned_at_rest_and_a_stop_cancels_it(machine, home):
    state = machine.update(
        machine.initial(home), at_rest(home, 0.0, MoveJoints(1, configuration="ready"))
    )
    assert state.mode == MOVING and state.move_seq == 1 and state.path is not None
    assert state.status().speed_scale == state.progress.rate
    state = machine.update(state, at_rest(home, PERIOD, (MoveJoints(1), Stop(2))))
    assert state.results.outcome_of(1) == CANCELLED
    assert state.results.outcome_of(2) == RUNNING and state.mode == STOPPING
    for k in range(2, 200):
        state = machine.update(state, at_rest(home, k * PERIOD))
        if state.results.outcome_of(2) == SUCCEEDED:
            break
    assert state.results.outcome_of(2) == SUCCEEDED and state.path is None and state.mode == IDLE


def test_holds_still_until_a_path_exists(machine, home):
    state = machine.initial(home)
    assert state.mode == IDLE and state.path_rate_at(1.0) == 0.0
    assert np.array_equal(state.motion_at(1.0), np.concatenate([home, np.zeros(12)]))


OUT_OF_REACH = RigidTransform(RollPitchYaw(np.pi, 0.0, 0.0), [0.0, 0.65, 1.15])
"""Over the work table, where link_4 would touch it (the iisy 3 on its pedestal)."""


def test_a_move_that_failed_asked_again_from_where_it_failed_is_not_planned_again(home):
    """A user's tree retried a RobotMove the robot cannot make at every tick, and each was
    planned anew to the same failure: a 5 s run took 366 s."""
    planner = MotionPlanner(make_scenario().station, MotionOptions(), stream(0, ROBOT_MOTION))
    machine, planned = MotionStateMachine(planner), []
    plan = planner.plan
    planner.plan = lambda *args: planned.append(args[0].seq) or plan(*args)
    state = machine.initial(home)
    for seq in (1, 2, 3):
        asked = MoveTo(seq, OUT_OF_REACH)
        state = machine.update(state, at_rest(home, seq * PERIOD, asked, SILENT))
        state = machine.update(state, at_rest(home, (seq + 0.5) * PERIOD, asked, SILENT))
        assert state.results.outcome_of(seq) == FAILED
    first, third = state.results.result_of(1), state.results.result_of(3)
    assert planned == [1] and third.reason == first.reason
    assert "unreachable" in first.reason
    elsewhere = home + np.array([0.2, 0, 0, 0, 0, 0])
    state = machine.update(
        state.replace(hold=tuple(elsewhere)),
        at_rest(elsewhere, 1.0, MoveTo(4, OUT_OF_REACH), SILENT),
    )
    assert planned == [1, 4], "from another posture it is planned again"
