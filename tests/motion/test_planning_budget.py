"""A plan's outcome does not depend on wall time: planning budgets are counts, so a loaded
machine or a busy sweep worker plans exactly what a quiet one does (same scenario and seed,
same bytes)."""

import itertools
import time

import numpy as np
import pytest
from pydrake.math import RigidTransform, RollPitchYaw

from hrc_drake.motion.errors import PlanningFailed
from hrc_drake.motion.messages import MoveJoints, MoveLinear, MoveTo
from hrc_drake.motion.options import MotionOptions
from hrc_drake.motion.planner import MotionPlanner
from hrc_drake.seeding import stream
from hrc_drake.wiring import ROBOT_MOTION
from tests.motion.motion_helpers import make_scenario

SEED = stream(0, ROBOT_MOTION)
"""The planner's stream of seed 0, as a run of seed 0 gives it."""

TOOL_DOWN = RollPitchYaw(np.pi, 0.0, 0.0)
COMMANDS = (
    MoveTo(1, RigidTransform(TOOL_DOWN, [-0.3, 0.3, 1.1])),
    MoveTo(2, RigidTransform(TOOL_DOWN, [-0.1, 0.42, 0.96])),  # behind the box: path search
    MoveLinear(3, RigidTransform(TOOL_DOWN, [-0.1, 0.42, 1.1])),
    MoveJoints(4, configuration="ready"),
    MoveTo(5, RigidTransform(TOOL_DOWN, [0.0, 0.9, 0.93])),  # out of reach after IK checks
    MoveTo(6, RigidTransform(TOOL_DOWN, [0.3, 0.6, 0.85])),  # inside the table: every start
)


def plan_outcomes(planner: MotionPlanner) -> list:
    """Per command: the timed path's knots (positions and duration), or the failure."""
    outcomes = []
    q = np.array(planner.model.variant.home)
    for command in COMMANDS:
        try:
            path = planner.plan(command, q)
        except PlanningFailed as failure:
            outcomes.append(str(failure))
            continue
        if path is None:
            outcomes.append(None)
            continue
        taus = np.linspace(0.0, path.duration, 25)
        outcomes.append((path.duration, np.array([path.position(t) for t in taus])))
        q = path.end
    return outcomes


class _Clock:
    """A stand-in for the process's clocks that advances by `step` seconds per reading."""

    def __init__(self, step: float):
        self._readings = itertools.count()
        self._step = step

    def __call__(self) -> float:
        return next(self._readings) * self._step


@pytest.fixture(scope="module")
def planner():
    return MotionPlanner(make_scenario(box_at=(0.3, 0.35)).station, MotionOptions(), SEED)


@pytest.fixture(scope="module")
def quiet_outcomes(planner):
    outcomes = plan_outcomes(planner)
    assert sum(isinstance(o, str) for o in outcomes) >= 1, "some commands must fail"
    assert sum(isinstance(o, tuple) for o in outcomes) >= 3, "most commands must plan"
    return outcomes


@pytest.mark.parametrize("step", [1e-9, 1e3], ids=["very slow clock", "very fast clock"])
def test_plans_are_the_same_whatever_the_clock_says(planner, quiet_outcomes, monkeypatch, step):
    for name in ("perf_counter", "monotonic", "time", "process_time"):
        monkeypatch.setattr(time, name, _Clock(step))
    outcomes = plan_outcomes(planner)
    assert len(outcomes) == len(quiet_outcomes)
    for got, expected in zip(outcomes, quiet_outcomes, strict=True):
        if isinstance(expected, tuple):
            assert isinstance(got, tuple), got
            assert got[0] == expected[0]
            np.testing.assert_array_equal(got[1], expected[1])
        else:
            assert got == expected


def test_budgets_are_counts_from_the_options():
    """A smaller search budget fails a move that needs a search; the default plans it."""
    scenario = make_scenario(box_at=(0.3, 0.35))
    tight = MotionPlanner(scenario.station, MotionOptions(search_nodes=2), SEED)
    home = np.array(tight.model.variant.home)
    with pytest.raises(PlanningFailed, match="no collision-free path"):
        tight.plan(COMMANDS[1], home)
    assert (
        MotionPlanner(scenario.station, MotionOptions(), SEED).plan(COMMANDS[1], home) is not None
    )
