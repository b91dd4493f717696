"""An object in the robot's gripper is part of the robot for the safety monitor: its
distance to the person counts, and its mass adds to the payload of contact estimates.

The person stands about 0.5 m from where the robot holds the bar: the monitor only
measures here (SSM off), as the robot may not move that near a person."""

import dataclasses

from hrc_drake.safety.config import SafetyConfig
from hrc_drake.safety.messages import CARRIED
from hrc_drake.workpieces.config import ObjectType
from tests.station.station_cell import Simulation, cell

BAR = ObjectType(shape="box", size=[0.7, 0.04, 0.02], mass=1.5, capacity=1)


def test_the_bar_the_robot_holds_is_what_comes_closest_to_the_person():
    scenario = cell("hold_bar.xml", "stand_by_the_bar.xml")
    types = {**scenario.workpieces.types, "bar": BAR}
    scenario = dataclasses.replace(
        scenario,
        workpieces=dataclasses.replace(scenario.workpieces, types=types),
        safety=SafetyConfig(ssm=False),
    )
    sim = Simulation(scenario)
    links_before_grip = {sim.advance(t)["safety_status"].link for t in (0.5, 1.0)}
    assert CARRIED not in links_before_grip
    sim.advance(12.0)
    assert sim.events("robot") == ["holding"]
    assert sim["workpieces_status"].held_by("robot").type == "bar"
    status = sim["safety_status"]
    assert status.link == CARRIED
    bar_end_x = 0.25 + BAR.size[0] / 2
    assert 0.0 < status.separation < 1.15 - bar_end_x
