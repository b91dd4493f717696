"""The stored stopping data (ISO 10218-1 Annex B style) cover every variant, behave like a
full-deceleration stop, and match a fresh measurement on RobotMotion; the station's robot
(plant and controller) stops as the data say."""

import itertools

import numpy as np
import pytest

from hrc_drake.iisy import VARIANTS
from hrc_drake.modelgen.stopping import AXES, EXTENSIONS, SPEEDS, measure_stop
from hrc_drake.motion.messages import MoveJoints
from hrc_drake.safety.stopping import StopModel, load_stops
from tests.motion.motion_helpers import build_station, make_scenario

UPDATE_PERIOD = 0.01


@pytest.mark.parametrize("variant", sorted(VARIANTS))
def test_every_axis_speed_and_extension_is_measured(variant):
    stops = load_stops(variant)
    rows = {(s.axis, s.speed, s.extension) for s in stops}
    assert rows == set(itertools.product(AXES, SPEEDS, EXTENSIONS))
    for stop in stops:
        assert 0.0 < stop.time < 2.0 and 0.0 < stop.distance < 1.0
        assert stop.distance <= stop.point_speed * stop.time  # braking, never speeding up


@pytest.mark.parametrize("variant", sorted(VARIANTS))
def test_stop_takes_time_in_proportion_to_the_speed(variant):
    """Full deceleration on the path: from a third of the speed a stop takes about a third
    of the time (plus up to one update) and the fastest point about a ninth of the way."""
    stops = {(s.axis, s.extension, s.speed): s for s in load_stops(variant)}
    for axis, extension in itertools.product(AXES, EXTENSIONS):
        full, third = stops[axis, extension, 1.0], stops[axis, extension, 0.33]
        assert third.time <= 0.33 * full.time + 2 * UPDATE_PERIOD
        assert third.time >= 0.33 * full.time - 2 * UPDATE_PERIOD
        assert third.distance <= 0.33**2 * full.distance * 1.5 + 0.005


def test_stored_stop_matches_a_fresh_measurement():
    stored = next(
        s
        for s in load_stops("lbr_iisy3_r760")
        if (s.axis, s.speed, s.extension) == ("A1", 1.0, 0.66)
    )
    fresh = measure_stop("lbr_iisy3_r760", "A1", 1.0, 0.66)
    assert fresh.time == pytest.approx(stored.time, abs=2e-3)
    assert fresh.distance == pytest.approx(stored.distance, rel=0.02)
    assert fresh.point_speed == pytest.approx(stored.point_speed, rel=0.02)


def test_stop_model_is_the_worst_case_of_the_data():
    stops = load_stops("lbr_iisy3_r760")
    model = StopModel.of_variant("lbr_iisy3_r760")
    for stop in stops:
        assert stop.time <= model.time(stop.speed) + 1e-12
        assert stop.distance <= model.distance(stop.speed, stop.point_speed) + 1e-12


@pytest.mark.parametrize("speed", [1.0, 0.5])
def test_station_robot_stops_as_the_data_say(speed):
    """The plant under its controller, stopped at full and at half speed mid-way through
    an A2 swing: at rest within T_s(speed) of the stop reaching RobotMotion, the tool
    travelling no farther than S_s."""
    variant = "lbr_iisy3_r760"
    station = build_station(make_scenario(variant))
    model = StopModel.of_variant(variant)
    start, goal = np.radians([0, -110, 60, 0, 60, 0]), np.radians([0, -30, 60, 0, 60, 0])
    station.command(MoveJoints(seq=1, q=tuple(start)))
    station.run_until_finished(1)
    station.set_safety_scale(speed)
    station.command(MoveJoints(seq=2, q=tuple(goal)))
    update = round(station.context.get_time() + 1.0, 2)  # an update well into the swing
    station.simulator.AdvanceTo(update - 0.002)  # two plant steps before it
    earlier = station.tool_pose().translation()
    station.simulator.AdvanceTo(update - 0.001)
    before = station.tool_pose().translation()
    tool_speed = np.linalg.norm(before - earlier) / 0.001
    station.set_safety_scale(0.0)  # received by RobotMotion's update at `update`
    stopped_at, path = update, 0.0
    while station.velocity_norm() > 1e-3:
        station.simulator.AdvanceTo(station.context.get_time() + 0.001)
        now = station.tool_pose().translation()
        path += np.linalg.norm(now - before)
        before = now
    took = station.context.get_time() - stopped_at
    assert tool_speed > 0.25 * speed
    assert took <= model.time(speed) + 0.03  # the controller settles the last mm/s
    assert path <= model.distance(speed, tool_speed) + 0.002
