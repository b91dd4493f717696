"""Run metrics, figures and report.html from monitor outputs (synthetic, worked by hand)."""

import json

import numpy as np
import pytest

from hrc_drake.evaluation.metrics import (
    bt_metrics,
    person_metrics,
    safety_metrics,
    task_metrics,
    utilisation_metrics,
)
from hrc_drake.evaluation.record import Footprint
from hrc_drake.evaluation.run_report import write_run_html
from hrc_drake.evaluation.timeline import (
    heatmap_figure,
    plot_heatmap,
    plot_timeline,
    timeline_figure,
)
from hrc_drake.messages import TaskEvent
from hrc_drake.motion.messages import IDLE, MOVING
from hrc_drake.safety.messages import (
    SIGNALS,
    ContactRecord,
    SafetyStatus,
    SafetyTotals,
    ViolationEpisode,
)
from hrc_drake.safety.pfl import QUASI_STATIC, assess_contact
from hrc_drake.safety.ssm import ZONES


def signals(**columns) -> np.ndarray:
    n = len(next(iter(columns.values())))
    data = np.zeros((len(SIGNALS), n))
    for name, values in columns.items():
        data[SIGNALS.index(name)] = values
    return data


TIMES = np.arange(5) * 1.0
BUSY = [(0.0, MOVING)]
"""RobotMotion's mode over the run: a move under way throughout."""
ROBOT = signals(
    robot_speed=[0.5, 0.5, 0.0, 0.0, 0.0],
    zone=[ZONES.index(z) for z in ("free", "free", "stopped", "free", "free")],
)


def test_robot_utilisation_splits_the_run():
    # intervals of 1 s: moving, moving, stopped, waiting
    assert utilisation_metrics(TIMES, ROBOT, 0.01, BUSY) == {
        "moving": 0.5,
        "waiting": 0.25,
        "stopped": 0.25,
        "stopped_with_person_at": [0.0, 0.0],
    }


def test_a_robot_stopped_with_nothing_to_do_waits():
    """Stopped by the monitor while idle (its tree waiting), the robot lost nothing: that
    time is waiting, not stopped; stopped while a move was under way, it is stopped."""
    idle_then_busy = [(0.0, IDLE), (2.5, MOVING)]
    assert utilisation_metrics(TIMES, ROBOT, 0.01, [(0.0, IDLE)]) == {
        "moving": 0.5,
        "waiting": 0.5,
        "stopped": 0.0,
    }
    run = signals(robot_speed=[0.0] * 5, zone=[ZONES.index("stopped")] * 5)
    metrics = utilisation_metrics(TIMES, run, 0.01, idle_then_busy)
    assert (metrics["waiting"], metrics["stopped"]) == (0.75, 0.25)


def test_where_the_person_stood_while_the_robot_was_stopped_is_where_they_stood_longest():
    # 1 s intervals: stopped with the person by the robot for 3 s (about (1.05, 0.52)),
    # then 2 s across the cell, then free
    stopped, free = ZONES.index("stopped"), ZONES.index("free")
    run = signals(
        zone=[stopped] * 5 + [free] * 2,
        person_x=[1.0, 1.05, 1.1, 3.0, 3.05, 0.0, 0.0],
        person_y=[0.5, 0.55, 0.5, 2.0, 2.0, 0.0, 0.0],
    )
    metrics = utilisation_metrics(np.arange(7) * 1.0, run, 0.01, BUSY)
    assert metrics["stopped"] == pytest.approx(5 / 6)
    assert metrics["stopped_with_person_at"] == [1.05, 0.517]


def test_person_walks_three_metres_and_waits_two_seconds():
    person = signals(
        person_x=[0.0, 1.0, 2.0, 2.0, 2.0],
        person_y=[0.0, 0.0, 0.0, 0.0, 1.0],
        walking_speed=[1.0, 1.0, 1.0, 0.0, 0.0],
    )
    assert person_metrics(TIMES, person) == {"walking_distance": 3.0, "waiting_time": 2.0}


def test_throughput_per_hour():
    events = [TaskEvent(10.0, "part_finished"), TaskEvent(20.0, "part_finished")]
    events.append(TaskEvent(30.0, "part_rejected", "robot"))
    metrics = task_metrics(events, duration=60.0)
    assert metrics["events"] == {"part_finished": 2, "part_rejected": 1}
    assert metrics["throughput_per_hour"] == {"part_finished": 120.0, "part_rejected": 60.0}


def test_an_event_the_trees_name_that_never_happened_counts_zero():
    """A user's robot never finished a kit in a run, and the summary said nothing of kits."""
    events = [TaskEvent(10.0, "part_finished")]
    metrics = task_metrics(events, duration=60.0, names=("kit_done", "part_finished"))
    assert metrics["events"] == {"kit_done": 0, "part_finished": 1}
    assert metrics["throughput_per_hour"] == {"kit_done": 0.0, "part_finished": 60.0}


def test_absent_sources_give_empty_sections():
    assert safety_metrics(None, 0.01) == {}
    assert task_metrics([], 10.0) == {"events": {}, "throughput_per_hour": {}}
    assert bt_metrics(None) == {}
    assert utilisation_metrics(np.zeros(0), signals(zone=[]), 0.01, []) == {}


def test_safety_section_from_final_status():
    # chest hit at 1 m/s by m_R = 9 kg: F = 428.571 N against 280 N (transient), 428.571 N/cm²
    # against 240 N/cm²; a hand pinned at rest by the person pressing in: no robot force
    chest = assess_contact("chest", "link_6", 1.0, 9.0, 1.0)
    hand = assess_contact("hand", "link_2", 0.2, 9.0, 1.0, QUASI_STATIC, robot_moving=False)
    totals = SafetyTotals(
        min_separation=-0.05,
        min_separation_region="chest",
        min_separation_link="link_6",
        stops=2,
        violation_time=0.25,
        violation_episodes=(ViolationEpisode(1.0, 1.25, "chest", "link_6", 0.2, 0.5),),
        contact_records=(
            ContactRecord(1.2, 1.3, chest, robot_moving=True, violation=True),
            ContactRecord(4.0, 4.5, hand, robot_moving=False, violation=False),
        ),
    )
    metrics = safety_metrics(SafetyStatus(totals=totals), 0.01)
    assert metrics["min_separation"]["region"] == "chest"
    violations = metrics["ssm_violations"]
    assert (violations["count"], violations["duration"], violations["moving_speed"]) == (
        1,
        0.25,
        0.01,
    )
    assert violations["worst_deficit"] == pytest.approx(0.3)
    assert violations["episodes"] == [
        {
            "start": 1.0,
            "end": 1.25,
            "region": "chest",
            "part": "link_6",
            "separation": 0.2,
            "protective": 0.5,
            "deficit": 0.3,
        }
    ]
    contacts = metrics["contacts"]
    assert (contacts["count"], contacts["robot_moving"], contacts["robot_at_rest"]) == (2, 1, 1)
    assert contacts["violations"] == 1 and contacts["worst_region"] == "chest"
    assert contacts["max_force_ratio"] == pytest.approx(428.571 / 280, abs=1e-4)
    assert contacts["max_pressure_ratio"] == pytest.approx(428.571 / 240, abs=1e-4)
    first, second = contacts["list"]
    assert (first["region"], first["part"], first["kind"], first["robot_moving"]) == (
        "chest",
        "link_6",
        "transient",
        True,
    )
    assert (first["force_limit"], first["pressure_limit"], first["start"]) == (280, 240, 1.2)
    assert (second["kind"], second["robot_moving"], second["force_limit"]) == (
        "quasi-static",
        False,
        140,
    )
    json.dumps(metrics)  # plain JSON, no infinities


def test_no_person_seen_is_null_not_infinity():
    metrics = safety_metrics(SafetyStatus(), 0.01)
    assert metrics["min_separation"]["distance"] is None


def test_figures_and_report_html(tmp_path):
    times = np.linspace(0.0, 4.0, 401)
    x = 3.0 - 0.6 * times
    data = signals(
        separation=x - 0.3,
        protective=np.full_like(times, 0.8),
        scale=np.clip((x - 1.0) / 1.0, 0, 1),
        robot_speed=np.clip(x - 1.0, 0, 1),
        walking_speed=np.full_like(times, 0.6),
        violation=(x < 1.2).astype(float),
        person_x=x,
        person_y=np.zeros_like(times),
    )
    states = {"person": [(0.0, "walking"), (3.0, "idle")], "robot": [(0.0, "moving")]}
    timeline = plot_timeline(
        tmp_path / "timeline.png", times, data, states, [TaskEvent(2.0, "part_finished")]
    )
    heatmap = plot_heatmap(tmp_path / "heatmap.png", times, data)
    replay = tmp_path / "replay.html"
    files = {"timeline": timeline, "heatmap": heatmap, "replay": replay}
    html = write_run_html(tmp_path / "report.html", {"scenario": "x", "seed": 3}, files)
    for path in (timeline, heatmap):
        assert path.read_bytes().startswith(b"\x89PNG")
    text = html.read_text()
    assert 'href="replay.html"' in text and 'src="timeline.png"' in text
    assert "<td>seed</td><td>3</td>" in text


def test_timeline_labels_only_where_they_fit_the_rest_in_the_legend():
    import matplotlib.pyplot as plt

    times = np.linspace(0.0, 60.0, 601)
    data = signals(separation=np.full_like(times, 2.0), scale=np.ones_like(times))
    tree = "Main::1/CarryBoxToConveyor::5/WalkTo::7/ActorMovement::9"
    states = {
        "robot": [(0.0, "idle"), (20.0, "moving"), (20.3, "idle")],
        "human tree": [(0.0, tree), (10.0, tree.replace("WalkTo::7", "Pick::8")), (30.0, "")],
    }
    fig = timeline_figure(times, data, states, [TaskEvent(20.0, "part_finished")])
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    activity_axes, legend_axes = fig.axes[3], fig.axes[4]
    labels = {text.get_text(): text for text in activity_axes.texts}
    assert set(labels) == {"idle", "CarryBoxToConveyor"}  # one span per activity
    for text in labels.values():
        assert activity_axes.bbox.contains(*text.get_window_extent(renderer).p0)
        assert activity_axes.bbox.contains(*text.get_window_extent(renderer).p1)
    legend = [t.get_text() for t in legend_axes.get_legend().get_texts()]
    assert legend == ["robot: moving", "event: part_finished"]
    plt.close(fig)


def test_report_html_summarises_the_trees_and_folds_their_nodes(tmp_path):
    nodes = {
        f"Main::1/Activity{i}::{i + 2}" + "/Leaf::9" * (i % 3): {
            "ticks": 10 * i,
            "successes": i,
            "failures": 0,
            "time_running": float(i),
        }
        for i in range(300)
    }
    metrics = {"scenario": "x", "seed": 1, "safety": {"stops": 2}, "bt": {"robot": nodes}}
    text = write_run_html(tmp_path / "report.html", metrics, {}).read_text()
    shown, folded = text.split("<details>")
    assert shown.count("<tr>") <= 20  # the metrics and the 10 longest-running activities
    assert "<td>Main/Activity297</td>" in shown and "<td>Main/Activity296</td>" not in shown
    assert folded.count("<tr>") == len(nodes) + 1
    assert "<td>stops</td><td>2</td>" in shown


TABLE = Footprint("work_table", ((-0.6, 0.3), (0.6, 0.3), (0.6, 1.1), (-0.6, 1.1)))
SHELF = Footprint("shelf", ((-2.8, 3.7), (-2.0, 3.7), (-2.0, 4.1), (-2.8, 4.1)))


def test_the_heat_map_draws_the_furniture_a_walk_went_through():
    """The person walks across the table from (0.05, 2) to (0.05, -0.5): both panels draw the
    table's outline and name it, the walk's cells inside the outline are coloured, and the
    map reaches out to the shelf the person never came near."""
    import matplotlib.pyplot as plt
    from matplotlib.patches import Polygon

    times = np.linspace(0.0, 2.5, 251)
    data = signals(
        person_x=np.full_like(times, 0.05),
        person_y=2.0 - times,
        separation=np.full_like(times, 1.0),
    )
    fig = heatmap_figure(times, data, (TABLE, SHELF))
    for ax in fig.axes[:2]:  # the two panels (then their colour bars)
        outlines = [p.get_xy()[:4].tolist() for p in ax.patches if isinstance(p, Polygon)]
        assert [list(c) for c in TABLE.outline] in outlines
        assert [list(c) for c in SHELF.outline] in outlines
        assert {t.get_text() for t in ax.texts} == {"work_table", "shelf"}
        x0, x1, y0, y1 = ax.images[0].get_extent()
        assert x0 <= -2.8 and y1 >= 4.1
        heat = ax.images[0].get_array()
        rows = (np.arange(heat.shape[0]) + 0.5) * (y1 - y0) / heat.shape[0] + y0
        column = int((0.05 - x0) / (x1 - x0) * heat.shape[1])
        inside = (rows > 0.3) & (rows < 1.1)
        assert np.all(np.isfinite(heat[inside, column]))  # the walk shows in the table
    plt.close(fig)
