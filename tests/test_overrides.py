"""Overrides, the one way a scenario is changed from outside its file: layered over the loaded
scenario by the file's own reader, so a value set from the command line, a sweep, a search or
a notebook reads exactly like the same value in the file."""

import pytest
from pydrake.common.yaml import yaml_dump_typed

from hrc_drake.scenario import load_scenario, overridden, resolve_scenario_path
from hrc_drake.yaml_check import InputError


@pytest.fixture(scope="module")
def walk_up():
    return load_scenario("walk_up")


def test_a_set_field_of_a_drake_struct_keeps_the_structs_other_settings(walk_up):
    changed = overridden(walk_up, [("plant.time_step", 0.0005)])
    assert changed.plant.time_step == 0.0005
    assert changed.plant.discrete_contact_approximation == "sap"
    assert walk_up.plant.time_step == 0.002  # the loaded scenario is left as it was


def test_mapping_entries_not_named_keep_their_values(walk_up):
    changed = overridden(
        walk_up,
        [("parameters.reach", "0.4"), ("trees.human.ports.walk_in.animation_distance", "1.9")],
    )
    assert changed.parameters == walk_up.parameters | {"reach": "0.4"}
    assert changed.trees["human"].file == walk_up.trees["human"].file
    assert changed.trees["human"].ports == {"walk_in": {"animation_distance": "1.9"}}
    assert changed.trees["robot"] == walk_up.trees["robot"]


def test_a_value_set_reads_like_the_same_value_in_the_file(walk_up, tmp_path):
    text = resolve_scenario_path("walk_up").read_text()
    edited = text.replace("duration: 20.0", "duration: 12.5").replace(
        'reach: "0.3"', 'reach: "0.45"'
    )
    assert edited.count("12.5") and "0.45" in edited
    (tmp_path / "walk_up.yaml").write_text(edited.replace("../trees/", f"{_trees()}/"))
    from_file = load_scenario(tmp_path / "walk_up.yaml")
    by_overrides = overridden(walk_up, [("duration", 12.5), ("parameters.reach", "0.45")])
    assert yaml_dump_typed(by_overrides) == yaml_dump_typed(from_file)


def test_an_entry_the_scenario_lacks_is_refused_where_new_entries_are_not_taken(walk_up):
    with pytest.raises(InputError, match="'locations' has no entry 'tabel'"):
        overridden(walk_up, [("locations.tabel.translation", 1.0)])


def _trees() -> str:
    return str(resolve_scenario_path("walk_up").resolve().parent.parent / "trees")
