"""The models of a station: the robot (arm + tool, welded at its base pose) and the static
cell. The simulation plant, the controller's plant and the planner's collision model are
all built from these, so they agree."""

from pydrake.multibody.parsing import ModelDirectives, Parser, ProcessModelDirectives
from pydrake.multibody.plant import MultibodyPlant

from hrc_drake.iisy import BASE_FRAME, add_iisy, add_tool
from hrc_drake.paths import add_model_package
from hrc_drake.scenario import NO_TOOL, RobotConfig, Scenario
from hrc_drake.wiring import ROBOT_MODEL, TOOL_MODEL


def model_parser(plant: MultibodyPlant) -> Parser:
    """A parser that resolves `package://hrc_drake_models/...` offline."""
    parser = Parser(plant)
    add_model_package(parser.package_map())
    return parser


def add_robot(plant: MultibodyPlant, parser: Parser, robot: RobotConfig):
    """Adds the iisy (and its tool on the flange), base welded at the scenario's pose."""
    arm = add_iisy(plant, robot.variant, parser)
    plant.RenameModelInstance(arm, ROBOT_MODEL)
    base_pose = robot.base_pose.GetDeterministicValue()
    plant.WeldFrames(plant.world_frame(), plant.GetFrameByName(BASE_FRAME, arm), base_pose)
    if robot.tool != NO_TOOL:
        plant.RenameModelInstance(add_tool(plant, arm, parser), TOOL_MODEL)
    return arm


def add_station_models(plant: MultibodyPlant, parser: Parser, scenario: Scenario):
    """The robot and the scenario's static cell; returns the arm and the robot's model
    instances (arm, then tool if any). Does not finalize."""
    add_model_package(parser.package_map())
    arm = add_robot(plant, parser, scenario.robot)
    directives = ModelDirectives()
    directives.directives = scenario.cell
    ProcessModelDirectives(directives, plant, parser)
    names = [ROBOT_MODEL] + ([TOOL_MODEL] if scenario.robot.tool != NO_TOOL else [])
    return arm, [plant.GetModelInstanceByName(name) for name in names]


def make_control_plant(scenario: Scenario) -> MultibodyPlant:
    """The arm and tool alone, for inverse dynamics (the controller's model of the robot)."""
    control_plant = MultibodyPlant(time_step=scenario.time_step)
    add_robot(control_plant, model_parser(control_plant), scenario.robot)
    control_plant.Finalize()
    return control_plant
