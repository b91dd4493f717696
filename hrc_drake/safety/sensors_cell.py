"""The station's fixed geometry as the safety sensors' checks (hrc_drake.safety.
sensors_checks) need it: the cell's shapes for the beams, the floor outlines of its
furniture (what a person walks round), the robot's base and reach with the tool; built once
per robot, tool, base and cell in a process (parsing takes a while)."""

from dataclasses import dataclass

import numpy as np
from pydrake.multibody.plant import AddMultibodyPlant, MultibodyPlantConfig
from pydrake.systems.framework import DiagramBuilder
from shapely.geometry import Polygon

from hrc_drake.human.navigation import cell_obstacles
from hrc_drake.iisy import FLANGE_FRAME, TCP_FRAME, VARIANTS
from hrc_drake.safety.sensors_raycast import Solids, solids
from hrc_drake.station import StationSpec, add_station_models, model_parser
from hrc_drake.wiring import ROBOT_MODEL, TOOL_MODEL


@dataclass(frozen=True)
class Cell:
    """The station's fixed geometry: its query, shapes and names for the beams, the floor
    outlines of its furniture, and the robot's base and reach (with the tool)."""

    query: object
    shapes: Solids
    poses: np.ndarray
    names: list[str]
    obstacles: list[Polygon]
    base: np.ndarray
    reach: float
    keep: tuple
    """the diagram and context the query reads"""


def cell_of(station: StationSpec) -> Cell:
    key = repr((station.variant, station.tool, station.cell, station.base_pose.GetAsMatrix34()))
    if key not in _CELLS:
        _CELLS[key] = _built_cell(station)
    return _CELLS[key]


_CELLS: dict[str, Cell] = {}


def _built_cell(station: StationSpec) -> Cell:
    builder = DiagramBuilder()
    plant, scene_graph = AddMultibodyPlant(MultibodyPlantConfig(), builder)
    add_station_models(plant, model_parser(plant), station)
    plant.Finalize()
    diagram = builder.Build()
    context = diagram.CreateDefaultContext()
    query = scene_graph.get_query_output_port().Eval(scene_graph.GetMyContextFromRoot(context))
    inspector = scene_graph.model_inspector()
    robot = {ROBOT_MODEL, TOOL_MODEL}
    fixed = [
        geometry
        for body in plant.GetBodiesWeldedTo(plant.world_body())
        if plant.GetModelInstanceName(body.model_instance()) not in robot
        for geometry in plant.GetCollisionGeometriesForBody(body)
    ]
    obstacles = [o.outline for o in cell_obstacles(plant, inspector) if o.name not in robot]
    return Cell(
        query=query,
        shapes=solids([inspector.GetShape(g) for g in fixed]),
        poses=np.array([query.GetPoseInWorld(g).GetAsMatrix34() for g in fixed]),
        names=[inspector.GetName(g).split("::")[0] for g in fixed],
        obstacles=obstacles,
        base=station.base_pose.translation()[:2],
        reach=VARIANTS[station.variant].reach + _tool_length(plant, station),
        keep=(diagram, context),
    )


def _tool_length(plant, station: StationSpec) -> float:
    if not station.has_tool:
        return 0.0
    context = plant.CreateDefaultContext()
    tool = plant.GetModelInstanceByName(TOOL_MODEL)
    arm = plant.GetModelInstanceByName(ROBOT_MODEL)
    flange = plant.GetFrameByName(FLANGE_FRAME, arm).CalcPoseInWorld(context)
    tcp = plant.GetFrameByName(TCP_FRAME, tool).CalcPoseInWorld(context)
    return float(np.linalg.norm(tcp.translation() - flange.translation()))


def inside(cell: Cell, point: np.ndarray) -> str:
    """The name of the cell's model `point` lies inside ("" if none)."""
    for result in cell.query.ComputeSignedDistanceToPoint(point, 0.0):
        if result.distance < 0.0:
            return cell.query.inspector().GetName(result.id_G).split("::")[0]
    return ""
