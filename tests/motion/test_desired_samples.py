"""The controller reads at every plant step the desired motion RobotMotion planned: its
quintic segment sampled at that step and around it, differenced as the plant follows it."""

import numpy as np
from pydrake.systems.framework import EventStatus

from hrc_drake.motion.execution import hermite_segment, step_samples
from hrc_drake.motion.messages import MoveJoints
from systems.robot_motion import desired_differences
from tests.motion.motion_helpers import build_station, make_scenario


def test_samples_are_the_quintic_at_the_step_and_its_neighbours():
    rng = np.random.default_rng(3)
    start, step = 12.34, 0.002
    coefficients = hermite_segment(rng.normal(size=18), rng.normal(size=18), 0.05)
    times = start + step * np.arange(-1, 27)
    samples = step_samples(start, coefficients, step, times).reshape(len(times), 3, -1)
    for k, offset in enumerate((-step, 0.0, step)):
        since = times + offset - start
        exact = np.array([np.polyval(row[::-1], since) for row in coefficients]).T
        assert np.abs(samples[:, k] - exact).max() < 1e-12


def test_the_controller_reads_each_steps_samples_of_the_segment():
    """Through a move, a steady hold and the updates between them: at every plant step the
    desired state and acceleration are the segment's samples differenced. (The monitor
    also sees the ends of AdvanceTo, between steps: there the outputs are the next step's.)"""
    station = build_station(make_scenario())
    h = station.plant.time_step()
    desired_state = station.diagram.GetOutputPort("robot_desired_state")
    desired_acceleration = station.diagram.GetOutputPort("robot_desired_acceleration")
    segment_port = station.motion.GetOutputPort("desired_segment")
    differences = desired_differences(6, h)
    errors = []

    def compare(context):
        segment = segment_port.Eval(station.motion.GetMyContextFromRoot(context))
        step = next_step(context.get_time(), h)
        samples = step_samples(segment[0], segment[1:].reshape(6, -1), h, [step])
        expected = differences @ samples[0]
        read = np.concatenate([desired_state.Eval(context), desired_acceleration.Eval(context)])
        errors.append(np.abs(read - expected).reshape(3, -1).max(axis=1))
        return EventStatus.Succeeded()

    station.simulator.set_monitor(compare)
    station.command(MoveJoints(seq=1, configuration="ready"))
    station.run_until_finished(1)
    station.simulator.AdvanceTo(station.context.get_time() + 0.2)
    errors = np.array(errors)
    assert len(errors) > 0.2 / h
    assert errors[:, 0].max() < 1e-12  # q
    assert errors[:, 1].max() < 1e-9  # v: differences over h
    assert errors[:, 2].max() < 1e-6  # vdot: over h²


def next_step(t: float, h: float) -> float:
    """The time n h of the plant step with (n - 1) h < t <= n h."""
    n = round(t / h)
    return (n + 1) * h if n * h < t else n * h
