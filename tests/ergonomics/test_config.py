"""The scenario's ergonomic settings meet the same checks as every field: a bad value is
one line naming the file (or option), the line and the field."""

from pathlib import Path

import pytest

from hrc_drake.scenario import load_scenario
from hrc_drake.yaml_check import InputError

CELL = Path(__file__).resolve().parents[1] / "station" / "cell.yaml"


@pytest.mark.parametrize(
    "field, value, says",
    [
        ("human.percentile", 0.5, "must lie within 1.0..99.0"),
        ("human.sex", "other", "unknown value 'other'; known: female, male"),
        ("ergonomics.coupling", "great", "unknown value 'great'; known: fair, good, poor"),
        ("ergonomics.period", 0.0, "must be positive"),
    ],
)
def test_bad_ergonomic_settings_are_refused(field, value, says):
    with pytest.raises(InputError, match=f"--set {field}=.*{says}"):
        load_scenario(CELL, [(field, value)])


def test_an_unknown_coupling_of_an_object_type_names_its_line(tmp_path):
    text = CELL.read_text().replace("capacity: 4}", "capacity: 4, attributes: {coupling: firm}}")
    scenario = tmp_path / "cell.yaml"
    scenario.write_text(text)
    with pytest.raises(InputError) as refused:
        load_scenario(scenario)
    message = str(refused.value)
    assert str(scenario) in message and "workpieces.types.part.attributes.coupling" in message
    assert "unknown coupling 'firm'; known: good, fair, poor" in message
