"""A person walks straight at a swinging robot, waits within its reach, and leaves.

With SSM the robot slows, stops before contact and resumes after the person leaves, with no
violation; without SSM the same walk gives violations and a contact on the torso.
"""

import math

import numpy as np
import pytest
from approach_cell import simulate, walk

from hrc_drake.safety.config import SafetyConfig
from hrc_drake.safety.messages import SIGNALS
from hrc_drake.safety.ssm import ZONES

ARRIVE, LEAVE, END = 3.0, 5.0, 10.0
PERSON = walk(stand=0.4, arrive=ARRIVE, leave=LEAVE, bearing=math.radians(55))
TORSO = ("chest", "abdomen")


def signal(data, name):
    return data[SIGNALS.index(name)]


@pytest.fixture(scope="module")
def with_ssm():
    return simulate(SafetyConfig(ssm=True), PERSON, END)


@pytest.fixture(scope="module")
def without_ssm():
    return simulate(SafetyConfig(ssm=False), PERSON, END)


def test_robot_slows_then_stops_before_contact(with_ssm):
    status, times, data = with_ssm
    scale = signal(data, "scale")
    stopped = np.flatnonzero(scale == 0.0)
    first_stop = times[stopped[0]]
    slowing = times[(scale > 0.0) & (scale < 1.0)]
    assert slowing.size and slowing[0] < first_stop < ARRIVE
    totals = status.totals
    assert totals.contacts == 0 and totals.min_separation > 0.1
    assert totals.stops == 1 and totals.reduced_time > 0.0


def test_robot_stays_stopped_while_the_person_is_near_then_resumes(with_ssm):
    _, times, data = with_ssm
    scale, zone = signal(data, "scale"), signal(data, "zone")
    near = (times > ARRIVE) & (times < LEAVE)
    assert np.all(scale[near] == 0.0)
    assert np.all(zone[near] == ZONES.index("stopped"))
    resumed = times[(times > LEAVE) & (scale == 1.0)]
    assert resumed.size, "the robot never returned to full speed"
    after = times >= resumed[0]
    assert np.all(scale[after] == 1.0)
    assert signal(data, "robot_speed")[after].max() > 0.3


def test_monitored_run_has_no_violation(with_ssm):
    status, _, data = with_ssm
    assert status.totals.violations == 0 and status.totals.violation_time == 0.0
    assert not signal(data, "violation").any()


def test_without_ssm_the_same_walk_violates_and_hits_the_torso(without_ssm):
    status, _, data = without_ssm
    totals = status.totals
    assert np.all(signal(data, "scale")[1:] == 1.0)
    assert totals.violations >= 1 and totals.worst_deficit > 0.1
    assert totals.contacts >= 1 and totals.min_separation < 0.0
    assert totals.worst_contact.region in TORSO
    assert totals.worst_contact.violation  # the swing hits harder than the chest allows


def test_separation_is_the_exact_distance_of_the_closest_pair(with_ssm):
    status, _, data = with_ssm
    assert status.totals.min_separation_region in TORSO
    assert status.totals.min_separation_link.startswith("link_")
    logged = signal(data, "separation")
    assert np.nanmin(logged) == pytest.approx(status.totals.min_separation)
