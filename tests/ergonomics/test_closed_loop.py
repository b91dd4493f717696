"""Closed loop: the person in the station holds a known posture (a clip that holds it) and
lifts a known box; the run's report.json gives the hand-scored RULA and REBA and the
hand-computed RWL and lifting index."""

import dataclasses
import json

import numpy as np
import pytest
from pydrake.common.schema import Transform

from hrc_drake.agent_trees import AgentTree
from hrc_drake.human.body import human_body
from hrc_drake.human.clip import Clip, save_clip
from hrc_drake.runner import run
from hrc_drake.workpieces.config import ObjectType, PlacedObject
from tests.ergonomics.postures import REACHING_REBA, REACHING_RULA, REACHING_TWISTED, posture
from tests.station.station_cell import cell

HOLD_TREE = """<root BTCPP_format="4" main_tree_to_execute="Human">
  <BehaviorTree ID="Human"><ActorAnimation animation_name="reaching_twisted"/></BehaviorTree>
</root>"""
LIFT_TREE = """<root BTCPP_format="4" main_tree_to_execute="Human">
  <BehaviorTree ID="Human"><Sequence>
    <RetryUntilSuccessful num_attempts="-1">
      <NextObject area="table" filter="type=box" object_id="{box}"/>
    </RetryUntilSuccessful>
    <ActorPick object_id="{box}" hand="both"/>
    <ActorPlace target="0.2;1.0;1.0"/>
    <Sleep msec="600000"/>
  </Sequence></BehaviorTree>
</root>"""


def holding_clip(body) -> Clip:
    """Standing, then over 3 s into the posture (slowly: no rapid change of posture),
    held 6 s, and back over 3 s."""
    still = body.standing_pose()
    held = posture(body, REACHING_TWISTED)
    ramp = [still + (held - still) * s for s in np.linspace(0.0, 1.0, 4)]
    frames = np.array([*ramp, *[held] * 6, *ramp[::-1]])
    return Clip("reaching_twisted", body.joint_names, frames, fps=1.0)


def scenario_with(tmp_path, tree: str, **changes):
    (tmp_path / "human.xml").write_text(tree)
    scenario = cell()
    scenario.trees = {"human": AgentTree(str(tmp_path / "human.xml"))}
    scenario.visualization.record = False
    return dataclasses.replace(scenario, **changes)


def test_a_held_posture_gives_its_hand_scored_rula_and_reba(tmp_path):
    clip_path = save_clip(holding_clip(human_body()), tmp_path)
    scenario = scenario_with(tmp_path, HOLD_TREE, duration=14.0)
    scenario.human.clips = [str(clip_path)]
    report = run(scenario, out_dir=tmp_path / "run")
    ergonomics = json.loads((tmp_path / "run" / "report.json").read_text())["ergonomics"]
    assert ergonomics["rula"]["max"]["score"] == REACHING_RULA
    assert ergonomics["rula"]["max"]["side"] == "right"
    assert ergonomics["reba"]["max"]["score"] == REACHING_REBA
    held = ergonomics["rula"]["max"]["time"]
    assert 1.0 <= held <= 12.0  # while the clip plays
    assert ergonomics["rula"]["share_by_action_level"]["3"] > 0.3  # RULA 5: 6 of 14 s
    assert ergonomics["lifts"] == []
    assert "Ergonomics" in (tmp_path / "run" / "report.html").read_text()
    assert report.metrics["ergonomics"] == ergonomics


def test_a_known_lift_gives_the_hand_computed_rwl_and_lifting_index(tmp_path):
    """A 10 kg box (0.3 x 0.2 x 0.2 m) on the work table (top at 0.90 m: centre at 1.00 m),
    0.5 m in front of the person's ankles, put down on the table 0.2 m to their left. The
    palms hold it on its sides 5.5 cm from its near face (4.5 cm nearer than its centre)
    and 7 cm below its top (3 cm above its centre: docs/realism.md, palms on a box's faces),
    and NIOSH measures the hands: origin H 45.5 cm, V 103 cm, A 0; destination
    H = sqrt(20^2 + 45.5^2) = 49.7 cm, V 103 cm, A = atan(20/45.5) = 23.7 deg; D 0 (counts
    as 25 cm: DM 1). One lift in 20 s: 3 lifts/min; 8 h a day: long; no handles: fair
    coupling, V >= 75 cm: CM 1.
    Origin: RWL = 23 x 25/45.5 x (1 - 0.003 x 28) x 1 x 1 x 0.55 x 1 = 6.37 kg, LI 1.57.
    Destination: 23 x 25/49.7 x 0.916 x 1 x (1 - 0.0032 x 23.7) x 0.55 = 5.39 kg, LI 1.86."""
    box = ObjectType(size=[0.3, 0.2, 0.2], mass=10.0, capacity=1)
    scenario = scenario_with(tmp_path, LIFT_TREE, duration=20.0)
    scenario.workpieces.types = {"box": box}
    scenario.workpieces.objects = [
        PlacedObject(type="box", pose=Transform(translation=[0.0, 1.0, 1.0]))
    ]
    scenario.human.start = [0.0, 1.5, -90.0]
    report = run(scenario, out_dir=tmp_path / "run")
    (lift,) = report.metrics["ergonomics"]["lifts"]
    assert lift["mass"] == 10.0 and lift["hands"] == "both_hands"
    origin, destination = lift["origin"], lift["destination"]
    assert (origin["h"], origin["v"], origin["a"]) == pytest.approx((45.5, 103, 0), abs=1.0)
    assert (destination["h"], destination["v"]) == pytest.approx((49.7, 103), abs=1.0)
    assert destination["a"] == pytest.approx(23.7, abs=1.0)
    assert origin["rwl"] == pytest.approx(6.37, rel=0.02)
    assert destination["rwl"] == pytest.approx(5.39, rel=0.02)
    assert lift["lifting_index"] == pytest.approx(1.86, rel=0.02)
    assert report.metrics["ergonomics"]["lifting_index_max"]["end"] == "destination"
