"""`hrc-drake validate` on a scenario's safety sensors (hrc_drake.safety.sensors_checks): each
mistake is one line naming the file, the line and the field, and the ISO 13855 field check
states S = K·T + C with the numbers a hand calculation from the robot's stopping data gives.

Every case edits the bundled guarded cell (one scanner with speed-switched fields)."""

import re
import subprocess
import sys

import pytest
import yaml

from hrc_drake.paths import resource_dir
from hrc_drake.scenario import load_scenario
from hrc_drake.yaml_check import InputError

SCENARIO = resource_dir("scenarios") / "guarded_cell.yaml"
STOPPING = resource_dir("models") / "iisy" / "stopping" / "lbr_iisy3_r760.yaml"
CURTAIN = """\
    light_curtains:
      door: {{ends: [[-1.0, {y}], [1.0, {y}]], heights: [0.3, 1.5], resolution: 0.03,
             response_time: 0.02}}
"""


def edited(tmp_path, old: str, new: str):
    """The guarded cell with `old` replaced by `new`, and the line `new` starts on."""
    text = SCENARIO.read_text()
    assert old in text, f"guarded_cell.yaml no longer holds {old!r}"
    trees = SCENARIO.resolve().parent.parent / "trees"
    changed = text.replace(old, new, 1).replace("../trees/", f"{trees}/")
    path = tmp_path / "cell.yaml"
    path.write_text(changed)
    return path, text[: text.index(old)].count("\n") + 1


def error_of(path) -> str:
    with pytest.raises(InputError) as raised:
        load_scenario(path)
    message = str(raised.value)
    assert "\n" not in message
    return message


def worst_stop(speed: float) -> float:
    """The longest measured stop at `speed` of full speed, straight from the data file."""
    stops = yaml.safe_load(STOPPING.read_text())["stops"]
    return max(s["time"] for s in stops if s["speed"] == speed)


def test_the_guarded_cell_passes():
    scenario = load_scenario("guarded_cell")
    assert list(scenario.safety.sensors.scanners) == ["front"]


@pytest.mark.parametrize(
    ("old", "new", "field", "says"),
    [
        (
            "pose: [1.9, 0.2, 135.0]",
            "pose: [0.0, -2.5, 135.0]",
            "safety.sensors.scanners.front.pose",
            "the scanner at [0.00, -2.50, 0.30] is inside robot_pedestal",
        ),
        (
            "height: 0.3",
            "height: -0.05",
            "safety.sensors.scanners.front.height",
            "the scan plane lies on or below the floor",
        ),
        (
            "height: 0.3",
            "height: 0.2",
            "safety.sensors.scanners.front.height",
            "too low for a detection capability of 70 mm: ISO 13855 needs "
            "H ≥ 15 (d − 50 mm) = 0.300 m",
        ),
        (
            "height: 0.3",
            "height: 1.2",
            "safety.sensors.scanners.front.height",
            "ISO 13855 puts a horizontal detection zone at most 1.0 m high",
        ),
        (
            "range: 9.0",
            "range: 5.0",
            "safety.sensors.scanners.front.fields[0].protective",
            "beyond its range of 5.0 m",
        ),
        (
            "range: 9.0",
            "range: 9.0\n        resolution_deg: 1.0",
            "safety.sensors.scanners.front.fields[0].protective",
            "more than its detection capability of 70 mm",
        ),
        (
            "range: 9.0",
            "range: 9.0\n        scan_time: 0.1",
            "safety.sensors.scanners.front.response_time",
            "shorter than a scan",
        ),
        (
            "          - speed: 1.0\n",
            "          - speed: 0.9\n",
            "safety.sensors.scanners.front.fields",
            "no field set guards full speed",
        ),
        (
            "  ssm: true\n",
            "  ssm: true\n  v_h_rule: measured\n",
            "safety.v_h_rule",
            "a safety sensor measures no body speed",
        ),
    ],
    ids=[
        "scanner in the pedestal",
        "scan plane below the floor",
        "scan plane too low for d",
        "scan plane too high",
        "field beyond the range",
        "beams too far apart",
        "response faster than a scan",
        "no set for full speed",
        "measured person speed",
    ],
)
def test_a_mistake_names_file_line_and_field(tmp_path, old, new, field, says):
    path, line = edited(tmp_path, old, new)
    message = error_of(path)
    assert re.match(rf"{re.escape(str(path))}:\d+: {re.escape(field)}: ", message), message
    assert says in message


def test_a_protective_field_smaller_than_iso_13855s_minimum_distance(tmp_path):
    """S = K·T + C + Z_d for the robot at full speed: K = 1.6 m/s; T the scanner's 0.08 s,
    the monitor's and the command's 0.01 s each and the longest measured stop from full
    speed; C = 1200 mm − 0.4 × 300 mm; Z_d = 0.05 m. The bundled field holds it; one 0.5 m
    shorter at the front does not."""
    t = 0.08 + 0.01 + 0.01 + worst_stop(1.0)
    s = 1.6 * t + (1.2 - 0.4 * 0.3) + 0.05
    old = "[2.3, 0.7], [1.2, 1.2], [-1.2, 1.2], [-2.3, 0.7]"
    path, line = edited(tmp_path, old, "[2.3, 0.7], [1.2, 0.7], [-1.2, 0.7], [-2.3, 0.7]")
    message = error_of(path)
    assert message.startswith(f"{path}:{line}: safety.sensors.scanners.front.fields[0].protective:")
    assert f"S = K·T + C + Z_d = {s:.2f} m" in message
    assert f"T = {t:.3f} s" in message and "C 1.08 m" in message
    x, y = map(float, re.search(r"a person at \[(\S+), (\S+)\]", message).groups())
    assert 0.7 < y < 1.2, "the uncovered place is in front of the shortened field"


def test_the_slow_field_set_is_checked_with_the_slower_stop(tmp_path):
    """At 30 % speed the robot stops sooner, so the inside of the fence suffices as the
    protective field; one that leaves the front half of the cell out does not."""
    old = "            protective: [[-2.0, -3.7], [2.0, -3.7], [2.0, 0.3], [-2.0, 0.3]]"
    new = "            protective: [[-2.0, -3.7], [2.0, -3.7], [2.0, -1.5], [-2.0, -1.5]]"
    path, line = edited(tmp_path, old, new)
    message = error_of(path)
    assert message.startswith(f"{path}:{line}: safety.sensors.scanners.front.fields[1].protective:")
    assert "at 30% speed" in message


def test_a_light_curtain_closer_than_its_minimum_distance(tmp_path):
    """A 30 mm curtain: C = 8 (30 − 14) mm; T its 0.02 s, 0.02 s of monitor and command and
    the stop from full speed; 2000 mm/s × T + C is above 500 mm, so S = 1600 mm/s × T + C.
    At the cell's opening it stands far enough from the reach, 0.8 m in it does not."""
    t = 0.02 + 0.02 + worst_stop(1.0)
    s = 1.6 * t + 8 * (0.030 - 0.014)
    anchor = "    reduced_speed: 0.3\n"
    path, _ = edited(tmp_path, anchor, anchor + CURTAIN.format(y=0.3))
    load_scenario(path)
    path, line = edited(tmp_path, anchor, anchor + CURTAIN.format(y=-0.5))
    message = error_of(path)
    assert message.startswith(f"{path}:{line + 2}: safety.sensors.light_curtains.door.ends:")
    assert f"S = K·T + C = {s:.2f} m" in message


def test_a_light_curtain_beam_blocked_by_the_cell(tmp_path):
    anchor = "    reduced_speed: 0.3\n"
    path, _ = edited(tmp_path, anchor, anchor + CURTAIN.format(y=-1.8))
    message = error_of(path)
    assert "safety.sensors.light_curtains.door.heights: the beam" in message
    assert "is blocked by the cell's work_table" in message


def test_a_value_from_the_command_line_is_named_by_its_option():
    with pytest.raises(InputError) as raised:
        load_scenario("guarded_cell", [("safety.sensors.scanners.front.height", -0.2)])
    assert str(raised.value).startswith("--set safety.sensors.scanners.front.height=-0.2: ")


def test_validate_exits_2_with_one_line(tmp_path):
    path, line = edited(tmp_path, "height: 0.3", "height: -0.05")
    result = subprocess.run(
        [sys.executable, "-m", "hrc_drake.cli", "validate", str(path)],
        capture_output=True,
        text=True,
    )
    assert result.returncode == 2
    assert result.stderr.count("\n") == 1 and "Traceback" not in result.stderr
    assert f"{path}:{line}: safety.sensors.scanners.front.height:" in result.stderr


def test_validate_lists_every_sensor_mistake_at_once(tmp_path):
    """A scan plane too high and a range the fields reach beyond: two lines from one
    validate, each with its line and field, where loading for a run refuses the first."""
    path, line = edited(
        tmp_path, "height: 0.3\n        range: 9.0", "height: 1.2\n        range: 2.0"
    )
    result = subprocess.run(
        [sys.executable, "-m", "hrc_drake.cli", "validate", str(path)],
        capture_output=True,
        text=True,
    )
    assert result.returncode == 2
    fields = re.findall(rf"hrc-drake: error: {re.escape(str(path))}:(\d+): (\S+):", result.stderr)
    assert (str(line), "safety.sensors.scanners.front.height") in fields, result.stderr
    assert "safety.sensors.scanners.front.fields[0].protective" in {f for _, f in fields}
    assert error_of(path).startswith(f"{path}:{line}: safety.sensors.scanners.front.height:")


def test_validate_checks_the_fields_at_each_robot_a_search_may_choose(tmp_path):
    """validate lists the sensors' own findings apart from loading, yet a search's choice of
    a bigger robot, whose longer stop the fields do not cover, is still one line naming the
    choice (as a run of the search refuses it)."""
    anchor = "    side: {bind: parameters.visit_area"
    search = "    robot: {bind: robot.variant, choices: [lbr_iisy3_r760, lbr_iisy11_r1300]}\n"
    path, line = edited(tmp_path, anchor, search + anchor)
    result = subprocess.run(
        [sys.executable, "-m", "hrc_drake.cli", "validate", str(path)],
        capture_output=True,
        text=True,
    )
    assert result.returncode == 2
    assert result.stderr.startswith(
        f"hrc-drake: error: {path}:{line}: falsify.parameters.robot.choices[1]: "
        "robot.variant=lbr_iisy11_r1300: too small for ISO 13855's minimum distance"
    ), result.stderr
