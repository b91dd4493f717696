"""The person's hand on the object a robot at rest presents is a hand-over grasp; any other
touch of the robot, or any touch while it moves, is a contact."""

import numpy as np
import pytest

from hrc_drake.safety.config import SafetyConfig
from hrc_drake.safety.judge import Judge
from hrc_drake.safety.messages import CARRIED, SafetyStatus
from hrc_drake.safety.proximity import PairReading, Reading
from hrc_drake.safety.ssm import SsmModel
from hrc_drake.safety.stopping import StopModel

CONFIG = SafetyConfig()
MODEL = SsmModel.from_config(CONFIG, StopModel.of_variant("lbr_iisy3_r760"), 0.01)


def judge_touch(region: str, part: str, robot_speed: float):
    touch = PairReading(region, part, -0.005, robot_approach=0.0, human_approach=0.3)
    reading = Reading(touch, (touch,), robot_speed, 0.3, (1.0, 0.0), np.zeros(0))
    judge = Judge(CONFIG, MODEL, robot_mass=9.0)
    rate = 0.2 if robot_speed > 0.0 else 0.0
    return judge.status(1.0, reading, SafetyStatus(time=0.99), payload=2.0, path_rate=rate)


@pytest.mark.parametrize("region", ["hand", "lower_arm"])
def test_hand_on_the_presented_object_is_no_contact(region):
    status = judge_touch(region, CARRIED, robot_speed=0.0)
    assert status.contact == () and status.totals.contacts == 0


@pytest.mark.parametrize(
    "region, part, robot_speed",
    [("hand", CARRIED, 0.2), ("chest", CARRIED, 0.0), ("hand", "link_6", 0.0)],
)
def test_other_touches_are_contacts(region, part, robot_speed):
    status = judge_touch(region, part, robot_speed)
    assert [c.region for c in status.contact] == [region]
    assert status.totals.contacts == 1
    assert status.totals.robot_contacts == (robot_speed > 0.0)
