"""The realism audit: what it measures of the person and of what the person and the robot
hold, step by step, in a diagram and in a run."""

import json
import math
from dataclasses import replace

import numpy as np
import pytest
from pydrake.math import RigidTransform
from pydrake.systems.analysis import Simulator

from hrc_drake.builder import build_diagram
from hrc_drake.evaluation.realism import (
    AuditState,
    Sample,
    audited,
    over_limits,
    realism_metrics,
    realism_rows,
)
from hrc_drake.human.walking import travel
from hrc_drake.scenario import HumanConfig, load_scenario, overridden
from hrc_drake.systems.realism_audit import PersonPose, Recorded
from hrc_drake.wiring import REALISM_AUDIT
from hrc_drake.workpieces.geometry import Solid
from hrc_drake.workpieces.messages import BOTH_HANDS, ROBOT_HOLDER
from tests.corpus.corpus_helpers import ROBOT_PUT_DOWN_INTO_THE_TABLE, write_workspace

STRIDE = 1.0
DT = 1.0 / 60.0


def _sample(t, soles=None, pelvis=None, walking=False, **worst) -> Sample:
    return Sample(
        time=t,
        static_depths=worst.get("static", ()),
        object_depths=worst.get("objects", ()),
        carried_depths=worst.get("carried", ()),
        hand_gaps=worst.get("gaps", ()),
        tilts=worst.get("tilts", ()),
        sole_points=soles or {},
        pelvis=pelvis,
        walking=walking,
    )


def _run(samples) -> AuditState:
    state = AuditState()
    for sample in samples:
        state = audited(state, sample, STRIDE)
    return state


def test_a_standing_sole_point_that_moves_slides():
    track = [np.array([0.05 * k / 10, 0.0, 0.0]) for k in range(11)]
    state = _run(_sample(k * DT, {"left_heel": p}) for k, p in enumerate(track))
    assert state.foot_slip.value == pytest.approx(0.05)
    assert state.foot_slip.what == "left_heel"


def test_a_foot_lifted_and_put_down_elsewhere_does_not_slide():
    down, up, elsewhere = np.zeros(3), np.array([0.2, 0.0, 0.05]), np.array([0.4, 0.0, 0.0])
    state = _run(_sample(k * DT, {"right_toe": p}) for k, p in enumerate([down, up, elsewhere]))
    assert state.foot_slip.value == 0.0


def _walk(speed_at, duration, walking=True):
    """Samples of a pelvis walking along x with speed `speed_at(t)`."""
    x, samples = 0.0, []
    for k in range(round(duration / DT) + 1):
        t = k * DT
        samples.append(_sample(t, pelvis=(t, x, 0.0), walking=walking))
        x += speed_at(t + DT / 2) * DT
    return samples


def test_pelvis_speed_swing_is_measured_per_steady_stride():
    state = _run(_walk(lambda t: 1.3 * (1 + 0.12 * math.sin(4 * math.pi * t / STRIDE)), 5.0))
    assert len(state.stride_variations) >= 3
    assert max(state.stride_variations) == pytest.approx(0.12, abs=0.01)
    assert np.mean(state.stride_speeds) == pytest.approx(1.3, abs=0.02)


def test_speeding_up_and_standing_are_no_strides():
    speeding_up = _run(_walk(lambda t: 0.3 + 0.5 * t, 3.0))
    assert speeding_up.stride_variations == ()
    standing = _run(_walk(lambda t: 1.3, 3.0, walking=False))
    assert standing.stride_variations == ()
    short_walk = _run(_walk(lambda t: 1.4 * math.sin(math.pi * min(t / STRIDE, 1)) ** 2, 1.5))
    assert short_walk.stride_variations == ()  # from standing to standing in one stride


def test_a_stride_from_speeding_up_into_slowing_down_is_not_steady():
    """Collaboration seed 8 at 91.2 s: a 1.8 m walk between two turns on the spot (1.34 m/s,
    0.6 s ramps, the pelvis surging ±8.5 % per stride). The stride that began 0.43 s into it
    ran from 1.02 m/s speeding up to 1.08 slowing down, 1.45 between: its ends agree, but
    it is no stride of steady walking."""
    turn, walk = STRIDE - 0.43, _travel_speed(1.772, 1.337)
    surge = lambda t: 1 + 0.085 * math.sin(4 * math.pi * (t - turn) / STRIDE)  # noqa: E731
    state = _run(_walk(lambda t: walk(t - turn) * surge(t), turn + 2.0))
    assert state.stride_variations == ()


def test_every_stride_at_walking_pace_counts_from_the_first():
    """A 4.5 m walk from standing to standing (1.34 m/s, 0.6 s ramps): its two strides at
    pace count, the first one after the speeding up too."""
    walk = _travel_speed(4.5, 1.34)
    surge = lambda t: 1 + 0.085 * math.sin(4 * math.pi * t / STRIDE)  # noqa: E731
    state = _run(_walk(lambda t: walk(t) * surge(t), 4.2))
    assert len(state.stride_variations) == 2
    assert max(state.stride_variations) == pytest.approx(0.085, abs=0.01)


def _travel_speed(distance: float, speed: float):
    """The pelvis speed along a walk of `distance` from standing to standing (of its time)."""

    def at(t: float) -> float:
        return (travel(t + 1e-4, distance, speed)[0] - travel(t - 1e-4, distance, speed)[0]) / 2e-4

    return at


def test_the_worst_of_each_measure_is_kept_with_when_and_where():
    state = _run(
        [
            _sample(1.0, static=((0.02, "thigh in pallet"),), tilts=((math.radians(5), "box"),)),
            _sample(2.0, static=((0.05, "hand in table"), (0.01, "pelvis in belt"))),
            _sample(3.0, gaps=((0.03, "carton 4"),), tilts=((math.radians(2), "box"),)),
        ]
    )
    metrics = realism_metrics(state)
    assert metrics["penetration_static"] == {"max": 0.05, "time": 2.0, "where": "hand in table"}
    assert metrics["hand_object_gap"]["max"] == 0.03
    assert metrics["carried_tilt_deg"]["max"] == pytest.approx(5.0)


def test_signed_distance_is_negative_inside_a_box():
    box = Solid("box", (0.3, 0.2, 0.1))
    assert box.signed_distance_to(np.zeros(3)) == pytest.approx(-0.05)
    assert box.signed_distance_to(np.array([0.25, 0.0, 0.0])) == pytest.approx(0.1)
    assert box.distance_to(np.zeros(3)) == 0.0


def _audit_of_person_standing_at(x, y) -> dict:
    scenario = load_scenario("base")
    scenario.human = HumanConfig(start=[x, y, 90.0])
    diagram = build_diagram(overridden(scenario, [("duration", 0.3)]))
    simulator = Simulator(diagram)
    simulator.AdvanceTo(0.3)
    return realism_metrics(diagram.GetOutputPort("realism").Eval(simulator.get_context()))


def test_a_person_standing_in_the_table_is_found_inside_it():
    """The base scenario's work table stands at (0, 0.9); its top is 1.2 m by 0.8 m."""
    inside = _audit_of_person_standing_at(0.0, 0.9)
    assert inside["penetration_static"]["max"] > 0.1
    assert inside["penetration_static"]["where"].endswith("in work_table")
    clear = _audit_of_person_standing_at(0.0, -1.5)
    assert clear["penetration_static"]["max"] < 0.005
    assert clear["foot_slip"]["max"] < 0.01


def test_the_report_page_marks_what_is_beyond_its_limit():
    state = _run([_sample(1.0, static=((0.05, "hand in table"),), gaps=((0.01, "box 1"),))])
    rows = {row[0]: row for row in realism_rows(realism_metrics(state))}
    assert rows["penetration_static"][1:] == [0.05, 0.01, "hand in table at 1.0 s", False]
    assert rows["hand_object_gap"][-1] is True


def test_a_carried_box_in_another_box_or_in_the_bench_is_found_inside_it():
    """Coexistence's cell at its start (a box of material, 0.08 m tall, its centre 0.94 m
    over the floor on the bench): one from the shelf held in both hands 3 cm down into it,
    then 2 cm down into the bench's top beside it, and held clear of both."""
    diagram = build_diagram(load_scenario("coexistence", [("seed", 0)]))
    simulator = Simulator(diagram)
    simulator.AdvanceTo(0.05)
    audit = diagram.GetSubsystemByName(REALISM_AUDIT)
    context = audit.GetMyContextFromRoot(simulator.get_context())
    objects = audit.GetInputPort("workpieces_status").Eval(context).objects
    (on_bench,) = (o for o in objects if o.support == "bench")
    taken = next(o for o in objects if o.type == "material" and o is not on_bench)
    others = tuple(o for o in objects if o is not taken)

    def carried_at(x: float, z: float, holder: str = BOTH_HANDS) -> dict:
        held = replace(taken, pose=RigidTransform([x, 3.77, z]), holder=holder, support=None)
        person = PersonPose(
            0.05,
            (0.0, 0.0),
            False,
            {"left": np.zeros(7), "right": np.zeros(7)},
            audit.GetInputPort("human_positions").Eval(context).copy(),
        )
        recorded = Recorded(None, 0.05, (*others, held), person)
        state = audited(AuditState(), audit.scene.sample(recorded), STRIDE)
        return realism_metrics(state)["penetration_carried"]

    into_box = carried_at(0.25, 0.94 + 0.08 - 0.03)
    assert into_box["max"] == pytest.approx(0.03, abs=1e-6)
    assert into_box["where"] == f"material {taken.id} in material {on_bench.id}"
    into_bench = carried_at(0.6, 0.94 - 0.02)
    assert into_bench["max"] == pytest.approx(0.02, abs=1e-6)
    assert into_bench["where"] == f"material {taken.id} in bench"
    assert carried_at(0.6, 0.94 + 0.1)["max"] == 0.0
    by_the_robot = carried_at(0.6, 0.94 - 0.02, ROBOT_HOLDER)
    assert by_the_robot["max"] == pytest.approx(0.02, abs=1e-6)
    assert by_the_robot["where"] == f"material {taken.id} in bench"


def test_a_part_the_robot_lets_go_of_in_the_table_is_over_the_limit(tmp_path, hrc_drake):
    """A user's cell let its parts go 3 cm into a table (the target given as the part's
    centre, not its top) and the run lifted each out: the audit measured only what the person
    held, and said nothing."""
    scenario = write_workspace(tmp_path, ROBOT_PUT_DOWN_INTO_THE_TABLE)
    status, _, err = hrc_drake("run", scenario, "--duration", 7, "--out", tmp_path / "run")
    assert status == 0, err
    report = json.loads((tmp_path / "run" / "report.json").read_text())
    held = report["realism"]["penetration_carried"]
    assert held["max"] == pytest.approx(0.03, abs=0.002)
    assert held["where"] == "part 1 in work_table"
    assert "penetration_carried" in {check.measure for check in over_limits(report["realism"])}
