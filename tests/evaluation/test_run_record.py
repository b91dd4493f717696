"""A run is its record evaluated: `run` gives the same metrics and files as `simulate`,
`evaluate` and `write_run_directory` one after the other, and the record holds what the
run did."""

from xml.etree import ElementTree

import numpy as np
import pytest

from hrc_drake.evaluation.report import evaluate, write_run_directory
from hrc_drake.layout import layout_of, write_layout
from hrc_drake.paths import resource_dir
from hrc_drake.runner import prepare_run_directory, run, run_setup, simulate
from hrc_drake.scenario import load_scenario
from hrc_drake.wiring import AGENTS

SAME_BYTES = (
    "report.json",
    "safety.npz",
    "bt_robot.jsonl",
    "bt_robot.btlog",
    "bt_human.btlog",
    "layout.png",
)
"""What a run decides, and its layout (its replay, figures and diagram are drawn from the
same record)."""


@pytest.fixture(scope="module")
def scenario():
    return load_scenario("walk_up", [("seed", 2), ("duration", 3.0)])


@pytest.fixture(scope="module")
def split(scenario, tmp_path_factory):
    """The run done in steps: simulate into a record, evaluate it, draw the cell's layout,
    write its directory."""
    out = tmp_path_factory.mktemp("split")
    prepare_run_directory(out)
    record = simulate(scenario, log_dir=out)
    metrics = evaluate(record)
    layout = {"layout": write_layout(layout_of(scenario, None), out / "layout.png")}
    return record, metrics, write_run_directory(out, record, metrics, layout)


def test_run_gives_the_metrics_and_files_of_its_steps(scenario, split, tmp_path):
    report = run(scenario, out_dir=tmp_path)
    _, metrics, files = split
    assert metrics == report.metrics
    assert set(files) == set(report.files) - {"replay"}  # run draws the replay in a Meshcat
    out = files["report"].parent
    for name in SAME_BYTES:
        assert (out / name).read_bytes() == (tmp_path / name).read_bytes(), name


def test_the_record_holds_what_the_run_did(scenario, split):
    record, metrics, _ = split
    assert record.setup == run_setup(scenario)
    assert record.fault is None and record.wall_time > 0
    assert record.robot_times[0] == 0.0 and record.robot_times[-1] == pytest.approx(3.0)
    assert record.robot_states.shape == (12, record.robot_times.size)
    assert record.signals.shape[1] == record.signal_times.size > 0
    assert record.safety_parts and record.safety_status is not None
    assert set(record.node_statistics) == set(scenario.trees) <= set(AGENTS)
    assert set(record.states) >= {"robot", "person", "robot tree"}
    times = [event.time for event in record.events]
    assert times == sorted(times)
    assert sum(metrics["tasks"]["events"].values()) == len(record.events)
    assert record.event_names == ("part_moved",)  # the robot's tree Emits it
    assert "part_moved" in metrics["tasks"]["events"]  # counted, happened or not
    assert record.recording is None and record.meshcat is None


def test_a_record_evaluates_the_same_every_time(split):
    record, metrics, _ = split
    assert evaluate(record) == metrics
    start = record.robot_states[: len(record.setup.initial_positions), 0]
    np.testing.assert_allclose(start, record.setup.initial_positions, atol=1e-12)


def test_the_record_holds_the_furniture_the_person_walks_round(split):
    """walk_up welds the work table (its top 1.2 m by 0.8 m, models/cell/work_table.sdf) at
    (0, 0.7): its footprint, robot pedestal and robot base are what the heat map draws."""
    record, _, _ = split
    top = ElementTree.parse(resource_dir("models") / "cell" / "work_table.sdf").find(
        ".//collision[@name='top']/geometry/box/size"
    )
    width, depth, _ = map(float, top.text.split())
    table = np.array(
        [c for piece in record.furniture if piece.name == "work_table" for c in piece.outline]
    )
    np.testing.assert_allclose(
        [*table.min(axis=0), *table.max(axis=0)],
        [-width / 2, 0.7 - depth / 2, width / 2, 0.7 + depth / 2],
        atol=1e-9,
    )
    assert {piece.name for piece in record.furniture} == {"work_table", "robot_pedestal", "iisy"}
