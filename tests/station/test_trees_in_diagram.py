"""Behavior trees drive the robot, the person and the objects inside one Diagram.

Each test gives the agents of the small test cell (`cell.yaml`) trees from `trees/`,
simulates, and checks what happened in the world: poses, object holders and supports,
task events, the statuses the actors report.
"""

import json
import re

import numpy as np
import pytest
from pydrake.common.schema import Transform
from pydrake.math import RigidTransform, RollPitchYaw

from hrc_drake.messages import CANCELLED, SUCCEEDED
from hrc_drake.runner import run
from hrc_drake.workpieces.config import ConveyorConfig
from hrc_drake.workpieces.messages import BOTH_HANDS, RIGHT_HAND, ROBOT_HOLDER
from tests.station.station_cell import Simulation, cell


def base_xy(status) -> np.ndarray:
    return np.array(status.base_pose[:2])


def test_robot_calls_the_person_who_walks_over_and_resets_the_call():
    sim = Simulation(cell("call_robot.xml", "call_human.xml"))
    sim.advance(1.0)
    assert not sim["human_status"].called
    called_seen = False
    for t in np.arange(1.0, 12.0, 0.25):
        called_seen |= sim.advance(t)["human_status"].called
    human = sim["human_status"]
    assert called_seen
    assert not human.called
    assert sim.events("robot") == ["called"] and sim.events("human") == ["helped"]
    table_front = np.array([0.0, 1.55])
    assert np.linalg.norm(base_xy(human) - table_front) < 0.05


def test_a_call_the_persons_tree_resets_is_not_seen_again_in_the_same_tick():
    """A user's person reset the call at the end of a kit change and their loop asked
    IsCalled again at once: it still read the flag as the person last reported it, and the
    person walked to the hand-over spot again for nothing."""
    sim = Simulation(cell("call_robot.xml", "answer_call_once.xml")).advance(12.0)
    assert sim.events("robot") == ["called"]
    assert sim.events("human") == ["helped"]
    assert not sim["human_status"].called


def test_a_call_interrupts_the_persons_animation_and_the_walk_is_accepted():
    """The ReactiveFallback starts the walk and halts the animation in one tick: the
    person takes the cancel first, so the walk is not refused as 'busy'."""
    sim = Simulation(cell("call_robot.xml", "interrupted_by_call.xml")).advance(10.0)
    human = sim["human_status"]
    assert sim.events("human") == ["helped"]
    assert "rejected" not in [result.outcome for result in human.results]
    assert "cancelled" in [result.outcome for result in human.results]
    assert np.linalg.norm(base_xy(human) - np.array([0.0, 1.55])) < 0.05


def test_movement_to_a_generated_pose_ends_inside_the_area():
    scenario = cell(human="walk_random.xml")
    hall = scenario.area("hall")
    sim = Simulation(scenario).advance(6.0)
    goal = sim.tree("human").root_blackboard.get("goal")
    assert hall.contains(goal.xy)
    assert sim.events("human") == ["arrived"]
    assert np.linalg.norm(base_xy(sim["human_status"]) - goal.xy) < 0.05
    assert hall.contains(base_xy(sim["human_status"]))


def test_robot_move_succeeds_once_after_a_speed_change_mid_motion():
    sim = Simulation(cell(robot="move_while_slowing.xml", person=False)).advance(6.0)
    robot = sim["robot_status"]
    assert sim.events("robot") == ["moved"]
    move = sim.tree("robot").node("RobotMove::3")
    assert move.tick_counts[2] == 1  # one SUCCESS
    assert robot.speed_fraction == pytest.approx(0.3)
    np.testing.assert_allclose(robot.tool_pose.translation(), [0.3, 0.3, 1.05], atol=2e-3)


def test_reactive_sequence_halts_the_move_and_the_robot_stops_when_the_person_comes():
    sim = Simulation(cell("stop_when_person_near.xml", "walk_to_table_side.xml"))
    sim.advance(12.0)
    robot = sim["robot_status"]
    assert CANCELLED in [result.outcome for result in robot.results]
    assert sim.events("robot") == ["halted"]
    assert robot.tool_speed < 1e-3
    target = np.array([-0.35, 0.3, 1.0])
    assert np.linalg.norm(robot.tool_pose.translation() - target) > 0.05


def test_spawned_part_goes_from_robot_to_person_and_is_carried_away():
    sim = Simulation(cell("hand_on_robot.xml", "carry_away.xml"))
    holders, supports = [], []
    for t in np.arange(0.5, 24.0, 0.5):
        objects = sim.advance(t)["workpieces_status"].objects
        assert len(objects) == 1
        holders.append(objects[0].holder)
        supports.append(objects[0].support)
    assert holders[0] is None and supports[0] == "work_table"
    # An 8 cm, 0.3 kg part: the person takes it in one hand (hrc_drake.human.grasp).
    assert ROBOT_HOLDER in holders and RIGHT_HAND in holders and BOTH_HANDS not in holders
    assert holders.index(ROBOT_HOLDER) < holders.index(RIGHT_HAND)
    final = sim["workpieces_status"].objects[0]
    assert final.holder is None and final.support == "floor"
    np.testing.assert_allclose(final.pose.translation()[:2], [3.0, 2.5], atol=0.1)
    assert sim.events("robot") == ["placed"] and sim.events("human") == ["carried"]


def test_same_scenario_and_seed_give_identical_transition_logs(tmp_path):
    scenario = cell("call_robot.xml", "walk_random.xml")
    for name in ("first", "second"):
        run(scenario, duration=6.0, out_dir=tmp_path / name)
    for log in ("bt_robot.jsonl", "bt_human.jsonl", "bt_human.btlog", "report.json"):
        first, second = (tmp_path / name / log for name in ("first", "second"))
        assert first.read_bytes() == second.read_bytes(), log
    assert (tmp_path / "first" / "bt_human.jsonl").read_text().count("\n") > 5


def test_a_persons_failed_pick_says_why_in_the_run_logs(tmp_path):
    """The person is told to take a part a belt carries past them: the pick is refused
    when it starts (played, the hands closed where the part had been), and the reason
    reaches the node's failure, the tree's log and report.json, as a robot's failed move
    does."""
    scenario = cell(human="pick_from_belt.xml")
    belt = ConveyorConfig(start=[0.45, 1.0, 0.9], end=[0.45, -0.2, 0.9], speed=0.3)
    scenario.workpieces.conveyors["belt"] = belt
    facing_the_belt = RigidTransform(RollPitchYaw(0, 0, np.pi), [1.0, 0.6, 0.0])
    scenario.locations["belt_side"] = Transform(facing_the_belt)
    report = run(scenario, duration=7.0, out_dir=tmp_path)
    why = report.metrics["bt"]["human"]["pick_moving_part"]["first_failure"]
    rests = r"take it where the belt brings it to rest, at \(0\.45, -0\.16, 0\.93\)"
    assert re.fullmatch(rf"part 1 is moving on belt 'belt' at 0\.30 m/s: {rests}", why), why
    log = [json.loads(line) for line in (tmp_path / "bt_human.jsonl").read_text().splitlines()]
    failures = [record for record in log if record["to"] == "FAILURE"]
    assert [(record["path"], record["reason"]) for record in failures] == [
        ("pick_moving_part", why)
    ]


def test_a_pick_while_the_hands_hold_something_fails_at_once_and_keeps_the_hold():
    """Holding a part, the person is told to take another: the pick fails at once, saying
    why, and the hands keep what they hold (played through, the hands went to the second
    part and left the first: a hand 5.6 cm off what it held in a cell of our own)."""
    sim = Simulation(cell(human="pick_while_holding.xml")).advance(12.0)
    pick = sim.tree("human").node("pick_while_holding")
    assert pick.failure_reason == "right_hand already holds object 1"
    assert sim.events("human") == ["went_on"]
    objects = {obj.id: obj for obj in sim["workpieces_status"].objects}
    assert objects[1].holder == RIGHT_HAND and objects[2].holder is None
    walked_and_took_the_first = [SUCCEEDED, SUCCEEDED]
    assert [result.outcome for result in sim["human_status"].results] == walked_and_took_the_first


def test_a_part_that_vanishes_while_the_person_reaches_for_it_fails_the_pick():
    """The part is despawned between the start of the person's pick and the moment the
    hands close (as when the robot or a belt takes it first): the pick fails with the
    reason, the person stops reaching and the tree goes on; the run does not crash."""
    sim = Simulation(cell(human="pick_what_vanishes.xml")).advance(7.0)
    pick = sim.tree("human").node("pick_vanishing_part")
    assert pick.failure_reason == "no object 1 (gone or never made) at the clip's 'grasp'"
    human = sim["human_status"]
    assert CANCELLED in [result.outcome for result in human.results]
    assert human.animation == "idle"
    assert sim.events("human") == ["went_on"]
