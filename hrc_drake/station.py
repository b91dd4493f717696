"""The models of a station: the robot (arm + tool, welded at its base pose) and the static
cell, described by a StationSpec. The simulation plant (the robot alone), the world scene's
mirror, the controller's plant and the planner's collision model are all built from one
spec, so they agree; none of them needs the rest of the scenario."""

from dataclasses import dataclass, field

import numpy as np
from pydrake.math import RigidTransform
from pydrake.multibody.parsing import (
    GetScopedFrameByName,
    ModelDirective,
    ModelDirectives,
    Parser,
    ProcessModelDirectives,
)
from pydrake.multibody.plant import (
    ApplyMultibodyPlantConfig,
    MultibodyPlant,
    MultibodyPlantConfig,
)
from pydrake.multibody.tree import ModelInstanceIndex

from hrc_drake.iisy import BASE_FRAME, TOOL_BODY, VARIANTS, add_iisy, add_tool
from hrc_drake.paths import add_bundled_model, add_model_package, bundled_model_file
from hrc_drake.wiring import ROBOT_MODEL, TOOL_MODEL

NO_TOOL = "none"
TOOLS = (TOOL_BODY, NO_TOOL)
HOME = "home"


@dataclass(frozen=True)
class StationSpec:
    """Which iisy stands where with which tool, the static cell around it, and the robot's
    named joint configurations (degrees; `home` defaults to the variant's)."""

    variant: str
    base_pose: RigidTransform = field(default_factory=RigidTransform)
    tool: str = TOOL_BODY
    cell: tuple[ModelDirective, ...] = ()
    configurations_deg: dict[str, list[float]] = field(default_factory=dict)
    initial_configuration: str = HOME

    @property
    def has_tool(self) -> bool:
        return self.tool != NO_TOOL

    @property
    def configuration_names(self) -> set[str]:
        return {HOME, *self.configurations_deg}

    def configuration(self, name: str) -> np.ndarray:
        """A named joint configuration in radians."""
        if name in self.configurations_deg:
            return np.radians(self.configurations_deg[name])
        if name != HOME:
            raise KeyError(f"unknown configuration '{name}'")
        return np.array(VARIANTS[self.variant].home)

    @property
    def initial_positions(self) -> np.ndarray:
        return self.configuration(self.initial_configuration)


def model_parser(plant: MultibodyPlant) -> Parser:
    """A parser that resolves `package://hrc_drake_models/...` offline."""
    parser = Parser(plant)
    add_model_package(parser.package_map())
    return parser


def add_robot(plant: MultibodyPlant, parser: Parser, spec: StationSpec):
    """Adds the iisy (and its tool on the flange), base welded at the spec's pose."""
    arm = add_iisy(plant, spec.variant, parser)
    plant.RenameModelInstance(arm, ROBOT_MODEL)
    plant.WeldFrames(plant.world_frame(), plant.GetFrameByName(BASE_FRAME, arm), spec.base_pose)
    if spec.has_tool:
        plant.RenameModelInstance(add_tool(plant, arm, parser), TOOL_MODEL)
    return arm


def add_station_models(plant: MultibodyPlant, parser: Parser, spec: StationSpec):
    """The robot and the static cell; returns the arm and the robot's model instances (arm,
    then tool if any). Does not finalize."""
    add_model_package(parser.package_map())
    arm = add_robot(plant, parser, spec)
    if _bundled_and_welded(spec.cell):
        _add_bundled_cell(plant, parser, spec.cell)
    else:
        directives = ModelDirectives()
        directives.directives = list(spec.cell)
        ProcessModelDirectives(directives, plant, parser)
    names = [ROBOT_MODEL] + ([TOOL_MODEL] if spec.has_tool else [])
    return arm, [plant.GetModelInstanceByName(name) for name in names]


def _bundled_and_welded(cell: tuple[ModelDirective, ...]) -> bool:
    """Whether every directive adds a bundled model (by name, nothing else set) or welds a
    frame of a model added before it: what `_add_bundled_cell` does as Drake would."""
    added: set[str] = set()
    for directive in cell:
        model, weld = directive.add_model, directive.add_weld
        if model is not None and model.name and bundled_model_file(model.file) is not None:
            if model.default_joint_positions or model.default_free_body_pose:
                return False
            added.add(model.name)
        elif weld is None or weld.child.partition("::")[0] not in added:
            return False
    return True


def _add_bundled_cell(plant: MultibodyPlant, parser: Parser, cell) -> None:
    """The cell as ProcessModelDirectives adds it (the models in order, each weld with its
    X_PC), the models parsed from their text (`add_bundled_model`: a tenth of the time, and
    a diagram parses its station three times)."""
    for directive in cell:
        if directive.add_model is not None:
            model = directive.add_model
            add_bundled_model(parser, bundled_model_file(model.file), model.name)
            continue
        weld = directive.add_weld
        X_PC = RigidTransform() if weld.X_PC is None else weld.X_PC.GetDeterministicValue()
        parent, child = (GetScopedFrameByName(plant, name) for name in (weld.parent, weld.child))
        plant.WeldFrames(parent, child, X_PC)


def make_dynamic_plant(
    spec: StationSpec, config: MultibodyPlantConfig
) -> tuple[MultibodyPlant, ModelInstanceIndex]:
    """The plant a simulation steps the robot's dynamics in: the arm and tool (finalized, at
    the spec's initial positions) with no cell and no geometry, so a step poses nothing and
    asks for no contact; returns it and the arm.

    No contact force can act on the robot in a run: the planner keeps it clear of the cell
    and of itself (its collision checker has every pair of the station's models; validate
    and the layout check the reach). With the cell's geometry in it, each step posed the
    robot's and ran the broad phase against the cell's: 0.9x the bare robot's whole cost
    (`benchmarks/plant_contact.py`). Whoever looks at the cell sees the world scene."""
    plant = MultibodyPlant(config.time_step)
    ApplyMultibodyPlantConfig(config, plant)
    arm = add_robot(plant, model_parser(plant), spec)
    plant.Finalize()
    plant.SetDefaultPositions(arm, spec.initial_positions)
    return plant, arm


def make_control_plant(spec: StationSpec, time_step: float) -> MultibodyPlant:
    """The arm and tool alone, for inverse dynamics (the controller's model of the robot)."""
    control_plant = MultibodyPlant(time_step=time_step)
    add_robot(control_plant, model_parser(control_plant), spec)
    control_plant.Finalize()
    return control_plant
