"""The `workpieces:` section reads with yaml_load_typed; problems name the field."""

import dataclasses

import pytest
from pydrake.geometry import SceneGraph

from hrc_drake.seeding import stream
from hrc_drake.systems.workpieces import Workpieces
from hrc_drake.wiring import WORKPIECES_SYSTEM
from hrc_drake.workpieces.config import (
    ConveyorConfig,
    GridLayout,
    ObjectType,
    PlacedObject,
    WorkpiecesConfig,
    problems,
)
from hrc_drake.yaml_check import InputError, check_node, compose
from tests.workpieces.workpieces_rig import EXAMPLE, Section, load_example


def test_the_example_loads_without_problems():
    config = load_example()
    assert problems(config) == []
    assert config.types["carton"].attributes == {
        "graspable": True,
        "fragile": False,
        "label": "A-113",
    }
    assert config.types["can"].shape == "cylinder"
    assert config.grids[0].attribute_probabilities == {"defective": 0.2, "graspable": 0.9}
    assert config.conveyors["outfeed"].at_end == "queue"
    assert config.objects[0].pose.GetDeterministicValue().translation()[2] == 0.96


def test_a_misspelt_field_names_file_line_and_field(tmp_path):
    bad = tmp_path / "bad.yaml"
    text = EXAMPLE.read_text()
    line = text[: text.index("occupancy:")].count("\n") + 1
    bad.write_text(text.replace("occupancy:", "ocupancy:"))
    where = rf"bad.yaml:{line}: workpieces.grids\[0\].ocupancy: unknown field"
    with pytest.raises(InputError, match=where):
        check_node(bad, compose(bad, bad.read_text()), Section)


def config_with_problem(**changes) -> WorkpiecesConfig:
    config = WorkpiecesConfig(types={"box": ObjectType()})
    return dataclasses.replace(config, **changes)


@pytest.mark.parametrize(
    "config, path, message",
    [
        (
            config_with_problem(types={"box": ObjectType(shape="sphere")}),
            ("types", "box", "shape"),
            "unknown shape 'sphere'",
        ),
        (
            config_with_problem(types={"box": ObjectType(shape="cylinder", size=[0.1, 0.1, 0.1])}),
            ("types", "box", "size"),
            "a cylinder needs 2 positive lengths",
        ),
        (
            config_with_problem(objects=[PlacedObject(type="crate")]),
            ("objects", 0, "type"),
            "unknown object type 'crate'",
        ),
        (
            config_with_problem(grids=[GridLayout(type="box", rows=4, columns=3)]),
            ("types", "box", "capacity"),
            "capacity 10 is less than the 12 initial objects",
        ),
        (
            config_with_problem(grids=[GridLayout(type="box", occupancy=1.5)]),
            ("grids", 0, "occupancy"),
            "a probability must lie in [0, 1]",
        ),
        (
            config_with_problem(grids=[GridLayout(type="box", attribute_counts={"heavy": -1})]),
            ("grids", 0, "attribute_counts", "heavy"),
            "must not be negative",
        ),
        (
            config_with_problem(
                grids=[
                    GridLayout(
                        type="box",
                        attribute_counts={"heavy": 1},
                        attribute_probabilities={"heavy": 0.5},
                    )
                ]
            ),
            ("grids", 0, "attribute_counts", "heavy"),
            "is also in attribute_probabilities",
        ),
        (
            config_with_problem(
                grids=[GridLayout(type="box", rows=2, attribute_counts={"a": 1, "b": 2})]
            ),
            ("grids", 0, "attribute_counts"),
            "3 counted objects exceed the 2 places",
        ),
        (
            config_with_problem(conveyors={"c": ConveyorConfig(start=[0, 0, 1], end=[1, 0, 0.9])}),
            ("conveyors", "c", "end"),
            "the belt must be horizontal",
        ),
        (
            config_with_problem(
                conveyors={"c": ConveyorConfig(start=[0, 0, 1], end=[1, 0, 1], at_end="drop")}
            ),
            ("conveyors", "c", "at_end"),
            "unknown end action 'drop'",
        ),
        (config_with_problem(period=0.0), ("period",), "must be positive"),
    ],
)
def test_problems_name_the_field(config, path, message):
    found = problems(config)
    assert found and found[0][0] == path and found[0][1].startswith(message)


def test_the_system_refuses_a_config_with_problems():
    config = config_with_problem(objects=[PlacedObject(type="crate")])
    with pytest.raises(ValueError, match=r"workpieces.objects\[0\].type: unknown object type"):
        Workpieces(config, SceneGraph(), stream(0, WORKPIECES_SYSTEM))
