"""Scenario -> one Drake Diagram (the `manipulation.station` / `hardware_sim` pattern).

The station diagram holds the dynamic plant (robot + tool + static cell), the robot's
inverse-dynamics controller, the source of the robot's desired state, SceneGraph and,
when asked, a Meshcat visualizer. It exports the ports a caller (runner, notebook, test)
needs, so measurement systems are added around it rather than inside it.
"""

import numpy as np
from pydrake.geometry import Meshcat, MeshcatVisualizer, MeshcatVisualizerParams, Role
from pydrake.multibody.parsing import ModelDirectives, Parser, ProcessModelDirectives
from pydrake.multibody.plant import AddMultibodyPlant, MultibodyPlant, MultibodyPlantConfig
from pydrake.systems.controllers import InverseDynamicsController
from pydrake.systems.framework import Diagram, DiagramBuilder
from pydrake.systems.primitives import ConstantVectorSource

from hrc_drake.iisy import BASE_FRAME, VARIANTS, add_iisy, add_tool
from hrc_drake.paths import add_model_package
from hrc_drake.scenario import NO_TOOL, RobotConfig, Scenario

ROBOT_MODEL = "iisy"
TOOL_MODEL = "tool"
VISUALIZER = "meshcat_visualizer"


def build_diagram(scenario: Scenario, meshcat: Meshcat | None = None) -> Diagram:
    """The whole scenario as one Diagram named after the scenario.

    Exported ports: `robot_state` (q, v of the arm), `robot_desired_state`,
    `query_object`, `body_poses`.
    """
    builder = DiagramBuilder()
    plant_config = MultibodyPlantConfig(
        time_step=scenario.time_step, discrete_contact_approximation="sap"
    )
    plant, scene_graph = AddMultibodyPlant(plant_config, builder)
    parser = _parser(plant)
    robot = add_robot(plant, parser, scenario.robot)
    ProcessModelDirectives(_directives(scenario), plant, parser)
    plant.Finalize()
    q0 = scenario.configuration(scenario.robot.initial_configuration)
    plant.SetDefaultPositions(robot, q0)

    controller = _add_controller(builder, scenario, plant, robot)
    desired = builder.AddNamedSystem(
        "robot_desired_state", ConstantVectorSource(np.concatenate([q0, np.zeros_like(q0)]))
    )
    builder.Connect(desired.get_output_port(), controller.get_input_port_desired_state())

    if meshcat is not None:
        _add_visualizer(builder, scene_graph, meshcat, scenario)

    builder.ExportOutput(plant.get_state_output_port(robot), "robot_state")
    builder.ExportOutput(desired.get_output_port(), "robot_desired_state")
    builder.ExportOutput(scene_graph.get_query_output_port(), "query_object")
    builder.ExportOutput(plant.get_body_poses_output_port(), "body_poses")
    diagram = builder.Build()
    diagram.set_name(scenario.name)
    return diagram


def add_robot(plant: MultibodyPlant, parser: Parser, robot: RobotConfig):
    """Adds the iisy (and its tool on the flange), base welded at the scenario's pose."""
    arm = add_iisy(plant, robot.variant, parser)
    plant.RenameModelInstance(arm, ROBOT_MODEL)
    base_pose = robot.base_pose.GetDeterministicValue()
    plant.WeldFrames(plant.world_frame(), plant.GetFrameByName(BASE_FRAME, arm), base_pose)
    if robot.tool != NO_TOOL:
        plant.RenameModelInstance(add_tool(plant, arm, parser), TOOL_MODEL)
    return arm


def make_control_plant(scenario: Scenario) -> MultibodyPlant:
    """The arm and tool alone, for inverse dynamics (the controller's model of the robot)."""
    control_plant = MultibodyPlant(time_step=scenario.time_step)
    add_robot(control_plant, _parser(control_plant), scenario.robot)
    control_plant.Finalize()
    return control_plant


def _add_controller(builder, scenario, plant, robot) -> InverseDynamicsController:
    variant = VARIANTS[scenario.robot.variant]
    controller = builder.AddNamedSystem(
        "robot_controller",
        InverseDynamicsController(
            make_control_plant(scenario),
            kp=variant.kp,
            ki=variant.ki,
            kd=variant.kd,
            has_reference_acceleration=False,
        ),
    )
    builder.Connect(plant.get_state_output_port(robot), controller.get_input_port_estimated_state())
    builder.Connect(controller.get_output_port_control(), plant.get_actuation_input_port(robot))
    return controller


def _add_visualizer(builder, scene_graph, meshcat, scenario) -> None:
    options = scenario.visualization
    meshcat.SetCameraPose(options.camera_position, options.camera_target)
    meshcat.SetProperty("/Grid", "visible", False)  # the cell has its own floor
    roles = [Role.kIllustration] + ([Role.kProximity] if options.show_collision else [])
    for role in roles:
        params = MeshcatVisualizerParams(
            publish_period=options.publish_period,
            role=role,
            prefix="visual" if role == Role.kIllustration else "collision",
        )
        visualizer = MeshcatVisualizer.AddToBuilder(builder, scene_graph, meshcat, params)
        if role == Role.kIllustration:
            visualizer.set_name(VISUALIZER)


def _parser(plant: MultibodyPlant) -> Parser:
    parser = Parser(plant)
    add_model_package(parser.package_map())
    return parser


def _directives(scenario: Scenario) -> ModelDirectives:
    directives = ModelDirectives()
    directives.directives = scenario.cell
    return directives
