"""Bad scenario files give one clear line naming the file, the line and the field."""

import subprocess
import sys

import pytest

from hrc_drake.paths import resource_dir
from hrc_drake.scenario import bundled_scenarios, load_scenario, resolve_scenario_path
from hrc_drake.scenario.findings import findings
from hrc_drake.yaml_check import InputError

BASE = resource_dir("scenarios") / "base.yaml"


def _variant(tmp_path, old: str, new: str):
    text = BASE.read_text()
    assert old in text, f"base.yaml no longer contains {old!r}"
    path = tmp_path / "bad.yaml"
    path.write_text(text.replace(old, new, 1))
    line = text[: text.index(old)].count("\n") + 1
    return path, line


def test_base_scenario_loads():
    scenario = load_scenario("base")
    assert scenario.name == "base"
    assert scenario.robot.variant == "lbr_iisy3_r760"
    assert scenario.duration > 0


@pytest.mark.parametrize("name", bundled_scenarios())
def test_a_bundled_scenario_has_no_finding(name):
    """validate's checks raise no false alarm on the scenarios that ship (and they have no
    mistake a run would find)."""
    assert findings(load_scenario(name), resolve_scenario_path(name)) == []


BAD_FILES = {
    "missing field": ("name: base\n", "", "name: required field is missing"),
    "wrong type": ("duration: 5.0", "duration: five", "duration: 'five' is not a float"),
    "unknown field": (
        "{time_step:",
        "{timestep:",
        "plant.timestep: unknown field (did you mean 'time_step'?)",
    ),
    "unknown variant": (
        "variant: lbr_iisy3_r760",
        "variant: lbr_iisy3_r770",
        "robot.variant: unknown robot variant 'lbr_iisy3_r770' (did you mean 'lbr_iisy3_r760'?)",
    ),
    "unknown model file": (
        "cell/work_table.sdf",
        "cell/work_tabel.sdf",
        "add_model.file: model file 'package://hrc_drake_models/cell/work_tabel.sdf' not found",
    ),
    "malformed yaml": ("seed: 0", "seed: [0", "malformed YAML"),
}


@pytest.mark.parametrize("case", BAD_FILES)
def test_bad_file_names_file_line_and_field(tmp_path, case):
    old, new, expected = BAD_FILES[case]
    path, line = _variant(tmp_path, old, new)
    with pytest.raises(InputError) as error:
        load_scenario(path)
    message = str(error.value)
    assert "\n" not in message
    assert message.startswith(f"{path}:")
    assert expected in message
    if case != "malformed yaml":  # a missing field points at the mapping that lacks it
        assert message.startswith(f"{path}:{line}:")


@pytest.mark.parametrize("case", ["unknown variant", "malformed yaml"])
def test_cli_reports_bad_file_in_one_line_and_exits_2(tmp_path, case):
    old, new, expected = BAD_FILES[case]
    path, _ = _variant(tmp_path, old, new)
    result = subprocess.run(
        [sys.executable, "-m", "hrc_drake.cli", "validate", str(path)],
        capture_output=True,
        text=True,
    )
    assert result.returncode == 2
    assert "Traceback" not in result.stderr
    assert result.stderr.count("\n") == 1
    assert expected in result.stderr


def test_cli_unknown_scenario_name_and_bad_argument_exit_2():
    unknown = subprocess.run(
        [sys.executable, "-m", "hrc_drake.cli", "run", "bsae"], capture_output=True, text=True
    )
    assert unknown.returncode == 2
    assert "did you mean 'base'?" in unknown.stderr
    bad_arg = subprocess.run(
        [sys.executable, "-m", "hrc_drake.cli", "run", "base", "--duration", "-1"],
        capture_output=True,
        text=True,
    )
    assert bad_arg.returncode == 2
    assert bad_arg.stderr.count("\n") == 1
    assert "Traceback" not in unknown.stderr + bad_arg.stderr
