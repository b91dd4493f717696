"""Every cell model parses with valid geometry and has its documented frames on its surfaces."""

import numpy as np
import pytest
from pydrake.multibody.parsing import Parser
from pydrake.multibody.plant import AddMultibodyPlantSceneGraph
from pydrake.systems.framework import DiagramBuilder

from hrc_drake.modelgen.cell import BODY, CELL_OBJECTS
from hrc_drake.paths import MODEL_PACKAGE, add_model_package

LOOSE = ("bottom", "top", "grasp")
FRAMES = {
    "floor": ("top",),
    "work_table": ("top",),
    "side_table": ("top",),
    "robot_pedestal": ("top",),
    "conveyor": ("top", "infeed", "outfeed"),
    "euro_pallet": ("top",),
    "bin": ("top", "rim"),
    "shelf": ("board_0", "board_1", "board_2", "board_3"),
    "fence": (),
    "part_small": LOOSE,
    "part_medium": LOOSE,
    "box_small": LOOSE,
    "box_large": LOOSE,
}
TOP_HEIGHTS = {
    "work_table": 0.9,
    "side_table": 0.75,
    "robot_pedestal": 0.8,
    "conveyor": 0.85,
    "euro_pallet": 0.144,
}
FACING_DOWN = ("bottom", "grasp")
"""Frames whose -z points out of the object; the others' +z does (`rim` is in the air)."""


class Cell:
    """One cell model in a plant with a SceneGraph, its body welded at the world origin."""

    def __init__(self, name: str):
        builder = DiagramBuilder()
        self.plant, self.scene_graph = AddMultibodyPlantSceneGraph(builder, time_step=0.001)
        parser = Parser(self.plant)
        add_model_package(parser.package_map())
        (self.instance,) = parser.AddModels(url=f"package://{MODEL_PACKAGE}/cell/{name}.sdf")
        self.body = self.plant.GetBodyByName(BODY, self.instance)
        self.plant.WeldFrames(self.plant.world_frame(), self.body.body_frame())
        self.plant.Finalize()
        diagram = builder.Build()
        self.context = diagram.CreateDefaultContext()
        self.plant_context = self.plant.GetMyContextFromRoot(self.context)
        self.query = self.scene_graph.get_query_output_port().Eval(
            self.scene_graph.GetMyContextFromRoot(self.context)
        )

    def pose(self, frame: str):
        return self.plant.GetFrameByName(frame, self.instance).CalcPoseInWorld(self.plant_context)

    def signed_distance(self, p_W) -> float:
        return min(d.distance for d in self.query.ComputeSignedDistanceToPoint(p_W))


@pytest.fixture(scope="module", params=sorted(CELL_OBJECTS))
def cell(request) -> tuple[str, Cell]:
    return request.param, Cell(request.param)


def test_every_model_is_documented():
    assert set(FRAMES) == set(CELL_OBJECTS)


def test_has_collision_geometry_and_valid_inertia(cell):
    _, cell = cell
    assert cell.plant.GetCollisionGeometriesForBody(cell.body)
    assert cell.body.default_spatial_inertia().IsPhysicallyValid()


def test_documented_frames_lie_on_surfaces(cell):
    name, cell = cell
    for frame in FRAMES[name]:
        X_WF = cell.pose(frame)
        outward = X_WF.rotation().matrix()[:, 2] * (-1 if frame in FACING_DOWN else 1)
        if frame != "rim":
            p_WF = X_WF.translation()
            assert cell.signed_distance(p_WF + 1e-3 * outward) > 0, frame
            assert cell.signed_distance(p_WF - 1e-3 * outward) < 0, frame


@pytest.mark.parametrize("name", sorted(TOP_HEIGHTS))
def test_support_heights(name):
    assert Cell(name).pose("top").translation()[2] == pytest.approx(TOP_HEIGHTS[name])


def test_fixtures_stand_on_the_floor(cell):
    name, cell = cell
    if name != "floor" and "bottom" not in FRAMES[name]:
        assert cell.signed_distance(np.array([0.0, 0.0, -1e-3])) > 0
