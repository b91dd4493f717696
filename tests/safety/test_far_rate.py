"""The monitor measures less often only where no measurement in between could have changed
its answer: wherever it lets a longer period pass (`Judge.next_period`: `far_period` or a
multiple of its period below it), a person coming at ISO 13855's walking speed (1.6 m/s: the
monitor goes slow only well beyond ISO 13855's 0.5 m, where that speed applies) and the
robot's fastest point coming at full speed for that whole period still leave a separation
at which the monitor, measuring at its own period, keeps full speed; and in the loop, a person
walking in at that speed meets a robot that moves exactly as it would under a monitor
measuring every period."""

import dataclasses

import numpy as np
import pytest

from hrc_drake.safety.config import CONSTANT, ISO_13855, MEASURED, SafetyConfig
from hrc_drake.safety.judge import Judge
from hrc_drake.safety.messages import SafetyStatus
from hrc_drake.safety.ssm import SsmModel, max_safe_scale
from hrc_drake.safety.stopping import StopModel
from tests.safety.walk_in import Case, simulate

STOP = StopModel(speeds=(0.0, 0.33, 0.66, 1.0), times=(0.01, 0.2, 0.4, 0.6), distance_factor=0.5)
LATENCY = 0.01
SEPARATIONS = np.arange(0.0, 6.0, 0.005)


def judge(config: SafetyConfig) -> Judge:
    return Judge(config, SsmModel.from_config(config, STOP, LATENCY), robot_mass=10.0)


def far_separations(j: Judge) -> np.ndarray:
    status = [SafetyStatus(separation=d, scale=1.0) for d in SEPARATIONS]
    return np.array([s.separation for s in status if j.far(s)])


def next_periods(j: Judge) -> np.ndarray:
    return np.array([j.next_period(SafetyStatus(separation=d, scale=1.0)) for d in SEPARATIONS])


@pytest.mark.parametrize("rule", [ISO_13855, CONSTANT, MEASURED])
@pytest.mark.parametrize("far_period", [0.03, 0.05, 0.1])
def test_no_measurement_between_far_ones_could_slow_the_robot(rule, far_period):
    config = SafetyConfig(v_h_rule=rule, far_period=far_period, robot_speed=1.5)
    j = judge(config)
    far = far_separations(j)
    assert far.size > 0 and far.min() > 1.0  # it goes slow far away, and only there
    assert far.min() > config.near_distance
    closing = config.v_h + config.robot_speed
    periods = next_periods(j)
    slower = periods > config.period
    for d, period in zip(SEPARATIONS[slower], periods[slower], strict=True):
        for elapsed in np.linspace(0.0, period, 11):
            for person_speed in (0.0, config.v_h / 2, config.v_h):
                left = d - closing * elapsed
                assert max_safe_scale(left, person_speed, j.model) >= 1.0, (d, period, elapsed)


@pytest.mark.parametrize("far_period", [0.05, 0.1])
def test_the_period_grows_with_the_separation_through_every_multiple(far_period):
    """Between where it must measure every period and where it may wait `far_period` the
    monitor waits every multiple of its period in turn, longer the farther the person."""
    config = SafetyConfig(far_period=far_period, robot_speed=1.5)
    periods = next_periods(judge(config))
    assert np.all(np.diff(periods) >= 0.0)
    expected = config.period * np.arange(1, round(far_period / config.period) + 1)
    assert np.allclose(np.unique(periods), expected)


def test_near_or_slowed_or_touching_measures_every_period():
    j = judge(SafetyConfig())
    assert not j.far(SafetyStatus(separation=0.8, scale=1.0))
    assert not j.far(SafetyStatus(separation=5.0, scale=0.5))
    assert j.far(SafetyStatus(separation=5.0, scale=1.0))


def test_far_period_at_or_below_the_period_never_goes_slow():
    j = judge(SafetyConfig(far_period=0.0))
    assert far_separations(j).size == 0


def test_the_robot_walked_in_on_moves_as_if_every_period_were_measured():
    """Closed loop (tests/safety/walk_in.py): the person walks in from 3 m at 1.6 m/s and
    reaches in at 2.0 m/s while the arm sweeps at full speed, once with the monitor at its
    far rate and once measuring every period. The robot's joints are the same at every
    period: no measurement left out would have slowed it, so none of the violations a
    monitor measuring every period would find was missed (and that one finds none)."""
    walk_in = Case("lbr_iisy3_r760", 90.0, 3.0, 0.5)
    far = simulate(walk_in)
    every = simulate(dataclasses.replace(walk_in, far_period=0.0))
    assert len(far.times) < 0.8 * len(every.times)  # it measured less often while far
    np.testing.assert_array_equal(far.robot_every_period, every.robot_every_period)
    assert every.status.totals.violations == 0 == far.status.totals.violations
    assert every.status.totals.stopped_time > 0.5  # the person came near enough to stop it
