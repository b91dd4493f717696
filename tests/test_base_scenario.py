"""The bundled base scenario: the iisy holds its pose; the run directory is complete."""

import base64
import json
import re

import pytest

from hrc_drake.builder import build_diagram
from hrc_drake.runner import run
from hrc_drake.scenario import load_scenario


@pytest.fixture(scope="module")
def base_run(tmp_path_factory):
    out = tmp_path_factory.mktemp("base_run")
    return run(load_scenario("base"), duration=5.0, out_dir=out)


def test_robot_holds_initial_configuration_under_gravity(base_run):
    assert base_run.metrics["duration"] == 5.0
    assert base_run.metrics["robot"]["max_deviation_from_initial_rad"] < 1e-3


def test_hold_is_the_controllers_work():
    """The arm is held by gravity-compensating torque, not by a model that cannot fall."""
    from pydrake.systems.analysis import Simulator

    built = []
    diagram = build_diagram(load_scenario("base"), attach=lambda _, station: built.append(station))
    simulator = Simulator(diagram)
    simulator.AdvanceTo(0.2)
    controller = built[0].controller
    context = controller.GetMyContextFromRoot(simulator.get_context())
    torque = controller.GetOutputPort("generalized_force").Eval(context)
    assert abs(torque[1]) > 1.0  # A2 carries the arm against gravity


def test_replay_is_standalone_and_animated(base_run):
    html = base_run.files["replay"].read_text()
    assert not re.search(r"<script[^>]*\ssrc=", html), "replay.html must not load scripts"
    # Meshcat embeds its scene commands as base64 msgpack blobs.
    blobs = re.findall(r"base64,([A-Za-z0-9+/=]+)", html)
    commands = b"".join(base64.b64decode(blob) for blob in blobs)
    assert b"set_animation" in commands
    assert b"/iisy/" in commands


def test_diagram_svg_names_plant_controller_and_scene_graph(base_run):
    svg = base_run.files["diagram"].read_text()
    assert svg.lstrip().startswith("<?xml") or "<svg" in svg
    for name in ("plant", "robot_controller", "scene_graph"):
        assert name in svg


def test_report_is_deterministic_json(base_run, tmp_path):
    report = json.loads(base_run.files["report"].read_text())
    assert report["scenario"] == "base"
    assert report["seed"] == 0
    again = run(load_scenario("base"), duration=5.0, out_dir=tmp_path)
    assert again.files["report"].read_bytes() == base_run.files["report"].read_bytes()
