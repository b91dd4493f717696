"""What a run and a sweep tell the reader first: the realism audit's verdict (within its
limits, or the measure farthest beyond its limit with what, where and when), sweep
aggregates that count a run without an event as 0 and say over how many runs a figure is,
and how many runs of a sweep broke the standard or the realism limits."""

import json
from pathlib import Path

import pytest

from hrc_drake.cli.simulate import key_metrics
from hrc_drake.evaluation.realism import LIMITS, realism_rows, realism_verdict
from hrc_drake.evaluation.sweep_report import summarize
from tests.corpus.corpus_helpers import write_workspace


def realism(**worst) -> dict:
    """A report's `realism` section: every measure 0 but those given as (max, time, what)."""
    section = {
        name: {"max": 0.0, "time": 0.0, key: ""}
        for name, key in (
            ("penetration_static", "where"),
            ("penetration_objects", "where"),
            ("penetration_carried", "where"),
            ("hand_object_gap", "object"),
            ("carried_tilt_deg", "object"),
            ("foot_slip", "point"),
        )
    }
    for name, (value, time, what) in worst.items():
        key = next(k for k in section[name] if k not in ("max", "time"))
        section[name] = {"max": value, "time": time, key: what}
    section["pelvis_speed"] = {
        "strides": 12,
        "mean_speed": 1.3,
        "variation_median": 0.07,
        "variation_max": 0.09,
    }
    return section


OVER = realism(
    penetration_static=(0.163, 36.2, "pelvis in work_table"),
    foot_slip=(0.038, 12.0, "right_heel"),
    carried_tilt_deg=(20.0, 50.5, "box 3"),
)


def test_the_verdict_leads_with_the_measure_farthest_beyond_its_limit():
    """16 times its limit beats 3.8 times and 1.3 times, whatever the units."""
    assert realism_verdict(OVER) == [
        "3 of 7 measures over their limits; worst: body in the cell's geometry 16.3 cm "
        "(limit 1 cm): pelvis in work_table at 36.2 s",
        "also: standing foot slid 3.8 cm (limit 1 cm): right_heel at 12.0 s",
        "also: carried object tilted 20.0° (limit 15°): box 3 at 50.5 s",
    ]


def test_a_measure_just_over_its_limit_is_shown_over_it():
    """A user's hand 1.04 cm into a rack was printed "1.0 cm (limit 1 cm)" as the worst of
    the measures over their limits: the figure shows as many decimals as it takes."""
    just_over = realism(penetration_static=(0.01045, 42.0, "right_hand in flow_rack"))
    assert realism_verdict(just_over) == [
        "1 of 7 measures over their limits; worst: body in the cell's geometry 1.04 cm "
        "(limit 1 cm): right_hand in flow_rack at 42.0 s"
    ]


def test_within_the_limits_says_so_and_without_a_person_nothing():
    at_limits = realism(**{name: (limit, 1.0, "x") for name, limit in LIMITS.items()})
    assert realism_verdict(at_limits) == ["within its limits (7 measures)"]
    assert realism_verdict({}) == []


def test_a_measure_without_anything_to_measure_is_named_not_counted():
    """Short walks round corners may have no stride of steady walking: the pelvis speed's
    swing is then not measured, and neither the verdict nor the report page counts it
    within its limit."""
    unwalked = realism()
    unwalked["pelvis_speed"] = {
        "strides": 0,
        "mean_speed": 0.0,
        "variation_median": 0.0,
        "variation_max": 0.0,
    }
    assert realism_verdict(unwalked) == [
        "within its limits (6 measures); not measured: pelvis speed swing within a stride "
        "(no stride of steady walking to measure it on)"
    ]
    assert realism_rows(unwalked)[-1][-1] == "not measured"
    over = dict(unwalked, foot_slip=OVER["foot_slip"])
    assert realism_verdict(over) == [
        "1 of 6 measures over their limits; worst: standing foot slid 3.8 cm (limit 1 cm): "
        "right_heel at 12.0 s; not measured: pelvis speed swing within a stride (no stride "
        "of steady walking to measure it on)"
    ]


def test_the_run_summary_prints_the_verdict():
    lines = key_metrics({"realism": OVER})
    assert lines[-3].startswith("realism: 3 of 7 measures over their limits; worst: body in")
    assert lines[-2:] == [
        "  also: standing foot slid 3.8 cm (limit 1 cm): right_heel at 12.0 s",
        "  also: carried object tilted 20.0° (limit 15°): box 3 at 50.5 s",
    ]
    assert key_metrics({"realism": realism()}) == ["realism: within its limits (7 measures)"]


def test_the_run_summary_gives_hourly_rates_to_three_figures():
    """A user's 70 s run printed "call: 1 (51.4286/h)"."""
    events = {"call": 1, "part": 30, "rare": 1}
    per_hour = {"call": 360 / 7, "part": 30 * 360 / 7, "rare": 0.123456}
    lines = key_metrics({"tasks": {"events": events, "throughput_per_hour": per_hour}})
    assert lines == ["call: 1 (51.4/h)", "part: 30 (1543/h)", "rare: 1 (0.123/h)"]


def row(seed: int, events: dict, margin: float | None, section: dict) -> dict:
    """A sweep's row of a successful run: its task events, margin and realism audit."""
    metrics = {
        "tasks": {
            "events": events,
            "throughput_per_hour": {name: 60.0 * n for name, n in events.items()},
        },
        "realism": section,
    }
    if margin is not None:
        metrics["margin"] = {"value": margin, "violation": margin < 0}
    key = f"seed={seed}"
    return {"key": key, "seed": seed, "set": {}, "status": "ok", "error": "", "metrics": metrics}


ROWS = [
    row(0, {"inspect_conveyor": 1, "part_finished": 3}, 0.3, OVER),
    row(1, {"part_finished": 2}, -0.1, realism()),
    row(2, {"part_finished": 4}, None, realism()),  # the robot never moved near the person
    row(3, {"part_finished": 3}, 0.2, realism(foot_slip=(0.02, 3.0, "left_toe"))),
]


def test_a_run_without_an_event_counts_it_as_zero():
    """inspect_conveyor happened once in four runs: 0.25 per run, median 0, not '1 [1, 1]'."""
    group = summarize(ROWS, "cell", "cell.yaml")["groups"][""]
    assert group["runs"] == 4
    stats = group["metrics"]["tasks.events.inspect_conveyor"]
    assert (stats["count"], stats["mean"], stats["p50"], stats["p100"]) == (4, 0.25, 0.0, 1.0)
    rate = group["metrics"]["tasks.throughput_per_hour.inspect_conveyor"]
    assert (rate["count"], rate["mean"]) == (4, 15.0)


def test_a_figure_some_runs_lack_says_over_how_many_runs_it_is():
    group = summarize(ROWS, "cell", "cell.yaml")["groups"][""]
    margin = group["metrics"]["margin.value"]
    assert margin["count"] == 3 and margin["p0"] == pytest.approx(-0.1)


def test_the_sweep_counts_runs_that_break_the_standard_and_the_realism_limits():
    group = summarize(ROWS, "cell", "cell.yaml")["groups"][""]
    assert group["violating_runs"] == 1
    assert group["realism"] == {
        "audited": 4,
        "over_limits": 2,
        "measures": {"carried_tilt_deg": 1, "foot_slip": 2, "penetration_static": 1},
    }


AT = {"region": "chest", "part": "carried object", "time": 110.1}


@pytest.mark.parametrize(
    "margin, line",
    [
        (
            {"value": 0.1417, "ssm": 0.1417, "contact_ratio": 0.0, "at": AT},
            "safety margin: 0.142 m (chest / carried object at 110.1 s)",
        ),
        (
            {"value": -5.1024, "ssm": 0.1417, "contact_ratio": 11.2048, "at": AT},
            "safety margin: -5.102 m, set by a contact at 11.2048 × its limit; "
            "SSM margin 0.142 m (chest / carried object at 110.1 s)",
        ),
        (
            {"value": 0.3, "ssm": None, "contact_ratio": 0.4},
            "safety margin: 0.300 m, set by a contact at 0.4 × its limit",
        ),
    ],
    ids=["separation", "contact", "contact only"],
)
def test_the_summary_says_what_set_the_safety_margin(margin, line):
    """A user's palletizing cell: 'safety margin: -5.10 m (chest / carried object at
    110.1 s)' under 'SSM violations: 0' read as a miscalculation; the -5.10 came from a
    contact 11.2 times its limit, not from that place. The line says which set it."""
    assert key_metrics({"margin": margin}) == [line]


PERSON_WAITING_BY_THE_ROBOT = """<root BTCPP_format="4" main_tree_to_execute="Human">
  <BehaviorTree ID="Human">
    <Sequence>
      <ActorMovement target="by_the_robot"/>
      <Repeat num_cycles="-1"><ActorAnimation animation_name="idle"/></Repeat>
    </Sequence>
  </BehaviorTree>
</root>
"""


def test_a_robot_stopped_most_of_the_run_says_where_the_person_stood(tmp_path, hrc_drake):
    """A user's robot stood stopped 113.7 s of a 120 s run while the person waited for it
    within its reach; the summary gave the stopped time and no hint of why."""
    scenario = write_workspace(tmp_path)
    text = scenario.read_text().replace(
        "  robot: {file: robot.xml, period: 0.05}\n",
        "  robot: {file: robot.xml, period: 0.05}\n  human: {file: human.xml, period: 0.1}\n",
    )
    text = text.replace(
        "  door:",
        "  by_the_robot: {translation: [0.6, -0.1, 0.0], rotation: !Rpy {deg: [0, 0, 180]}}\n"
        "  door:",
    )
    scenario.write_text(text)
    (tmp_path / "human.xml").write_text(PERSON_WAITING_BY_THE_ROBOT)
    robot = (tmp_path / "robot.xml").read_text()
    (tmp_path / "robot.xml").write_text(
        robot.replace(
            '<SubTree ID="Reach" at="pick_spot"/>\n      <SubTree ID="Reach" at="pick_spot"/>',
            '<Repeat num_cycles="-1"><Sequence><SubTree ID="Reach" at="pick_spot"/>'
            '<RobotMove target="0.1;0.42;1.0"/></Sequence></Repeat>',
        )
    )
    status, out, err = hrc_drake("run", scenario, "--duration", 12, "--out", tmp_path / "run")
    assert status == 0, err
    hint = next(line for line in out.splitlines() if "the robot was stopped" in line)
    stopped = float(hint.split("stopped ")[1].split(" %")[0])
    assert stopped > 70, hint
    assert "the person near it, most of that time at (0.60, -0.10)" in hint


def test_a_robot_stopped_with_nothing_to_do_gets_no_hint(hrc_drake, tmp_path):
    """The robot's tree waits the whole run while the person stands beside it: the monitor
    holds it stopped, but it lost nothing. The summary said it "was stopped 100 % of the
    run" because of the person (#26)."""
    cell = Path(__file__).parent / "cells" / "robot_waits" / "cell.yaml"
    status, out, err = hrc_drake("run", cell, "--out", tmp_path / "run")
    assert status == 0, err
    assert "stopped 10.0 s" in out  # the monitor's own figure: it did hold the robot
    assert "the robot was stopped" not in out
    report = json.loads((tmp_path / "run" / "report.json").read_text())
    assert report["utilisation"]["robot"] == {"moving": 0.0, "waiting": 1.0, "stopped": 0.0}
