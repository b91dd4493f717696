"""Scenario -> one Drake Diagram (the `manipulation.station` / `hardware_sim` pattern).

The station holds the dynamic plant (robot + tool + static cell) under its inverse-dynamics
controller and RobotMotion; the kinematic person (HumanActor); the Workpieces; the
SafetyMonitor; one BehaviorTreeSystem per agent; SceneGraph; and, when asked, a Meshcat
visualizer with the ReplayRecorder that replay.html is made from. Each part is present when
the scenario asks for it: no `human:` section, no person and no monitor; no workpiece types,
no Workpieces; no `trees:`, no behavior trees.

Two SceneGraphs: the dynamic plant keeps its own for contact (robot and cell only), and
the world scene, named `scene_graph`, holds a kinematic mirror of the robot and cell
(posed from the plant's state), the person and the workpieces. The safety monitor,
Meshcat and the `query_object` output see the world scene; the plant's 1 kHz steps never
pay for the person's or the objects' geometry.

Command inputs that no tree drives are exported as `<system>.<port>` (e.g.
`robot_motion.robot_command`), so tests and notebooks can command the actors directly.
Outputs are exported by name: `robot_state`, `robot_status`, `robot_desired_state`,
`query_object`, `body_poses`, and when present `human_status`, `workpieces_status`,
`safety_status`, `safety_signals`, `realism` (the person's realism audit),
`<agent>_tree_status`, `<agent>_task_events`.
"""

import numpy as np
from pydrake.geometry import Meshcat, MeshcatVisualizer, MeshcatVisualizerParams, Role, SceneGraph
from pydrake.multibody.plant import AddMultibodyPlant, MultibodyPlant, MultibodyPlantConfig
from pydrake.systems.framework import Diagram, DiagramBuilder
from pydrake.systems.rendering import MultibodyPositionToGeometryPose

from hrc_drake.agent_trees import load_agent_tree
from hrc_drake.evaluation.replay import dress_scene
from hrc_drake.human.builder import add_human
from hrc_drake.human.clip_files import clip_catalog
from hrc_drake.human.navigation import NavigationMap, cell_obstacles, robot_keep_out
from hrc_drake.iisy import TCP_FRAME, VARIANTS
from hrc_drake.nodes.context import HUMAN, ROBOT, SAFETY, STATUS_INPUTS, WORKPIECES
from hrc_drake.scenario import AGENTS, NO_TOOL, Scenario
from hrc_drake.seeding import stream
from hrc_drake.station_models import (
    TOOL_MODEL,
    add_station_models,
    model_parser,
)
from hrc_drake.systems.behavior_tree import BehaviorTreeSystem, command_port, status_port
from hrc_drake.systems.realism_audit import add_realism_audit
from hrc_drake.systems.replay_recorder import ReplayRecorder
from hrc_drake.systems.robot_controller import add_robot_controller
from hrc_drake.systems.robot_motion import add_robot_motion
from hrc_drake.systems.safety_monitor import add_safety_monitor
from hrc_drake.systems.workpieces import HumanHands, add_workpieces

VISUALIZER = "meshcat_visualizer"
RECORDER = "replay_recorder"
VISUAL_PREFIX = "visual"
HUMAN_NAME = "human"
GRIPPER_ISSUER = "robot_gripper"


def tree_issuer(agent: str) -> str:
    """How the actors name the commands of `agent`'s behavior tree."""
    return f"{agent}_tree"


def build_diagram(scenario: Scenario, meshcat: Meshcat | None = None) -> Diagram:
    """The whole scenario as one Diagram named after the scenario (see module docstring)."""
    builder = DiagramBuilder()
    plant, physics = AddMultibodyPlant(
        MultibodyPlantConfig(time_step=scenario.time_step, discrete_contact_approximation="sap"),
        builder,
    )
    physics.set_name("physics_scene_graph")
    arm, _ = add_station_models(plant, model_parser(plant), scenario)
    plant.Finalize()
    plant.SetDefaultPositions(arm, scenario.configuration(scenario.robot.initial_configuration))
    controller = add_robot_controller(builder, scenario, plant, arm)
    scene_graph, mirror = _add_world_scene(builder, plant, scenario)

    human, human_plant = _add_person(builder, scene_graph, mirror, scenario)
    workpieces = _add_workpieces(builder, scene_graph, plant, mirror, scenario, human)
    motion = add_robot_motion(
        builder, scenario, plant, arm, controller, scenario.robot.motion, workpieces
    )
    safety = _add_safety(builder, scene_graph, mirror, human_plant, motion, workpieces, scenario)
    audit = _add_audit(builder, scene_graph, mirror, human, human_plant, workpieces, scenario)
    if human is not None:
        for reader in filter(None, (motion, safety)):
            builder.Connect(
                human.GetOutputPort("human_status"), reader.GetInputPort("human_status")
            )
    actors = {ROBOT: motion, HUMAN: human, WORKPIECES: workpieces, SAFETY: safety}
    trees = [_add_tree(builder, scenario, agent, actors) for agent in scenario.trees]
    if meshcat is not None:
        _add_visualizer(builder, scene_graph, meshcat, scenario, actors)

    _export_outputs(builder, plant, arm, scene_graph, actors, trees)
    if audit is not None:
        builder.ExportOutput(audit.GetOutputPort("realism"), "realism")
    _export_open_inputs(builder, [motion, human, workpieces])
    diagram = builder.Build()
    diagram.set_name(scenario.name)
    return diagram


def _add_world_scene(builder, plant, scenario):
    """The SceneGraph everyone else sees: a kinematic mirror of the robot and cell, posed
    from the dynamic plant's state, with the person and the workpieces beside it.

    The dynamic plant keeps a SceneGraph of its own for contact. Its every step re-poses
    only its own geometry; the person's and the workpieces' frames are re-posed only when
    someone queries this scene (the safety monitor at 100 Hz, Meshcat when it draws).
    Nothing here takes part in physics, so no collision filters are needed between them.
    """
    scene_graph = builder.AddNamedSystem("scene_graph", SceneGraph())
    mirror = MultibodyPlant(0.0)
    mirror.set_name("station_mirror")
    mirror.RegisterAsSourceForSceneGraph(scene_graph)
    add_station_models(mirror, model_parser(mirror), scenario)
    mirror.Finalize()
    to_pose = builder.AddNamedSystem(
        "station_mirror_geometry", MultibodyPositionToGeometryPose(mirror, True)
    )
    builder.Connect(plant.get_state_output_port(), to_pose.get_input_port())
    builder.Connect(
        to_pose.get_output_port(), scene_graph.get_source_pose_port(mirror.get_source_id())
    )
    return scene_graph, mirror


def _add_person(builder, scene_graph, mirror, scenario):
    """The person, walking round the cell's static geometry (the mirror's)."""
    if scenario.human is None:
        return None, None
    x, y, yaw_deg = scenario.human.start
    robot_xy = scenario.robot.base_pose.GetDeterministicValue().translation()[:2]
    human, human_plant = add_human(
        builder,
        scene_graph,
        scenario.human.height,
        scenario.human.mass,
        name=HUMAN_NAME,
        start_pose=(x, y, np.radians(yaw_deg)),
        issuers=tuple(tree_issuer(agent) for agent in AGENTS),
        navigation=NavigationMap(
            cell_obstacles(mirror, scene_graph.model_inspector()),
            keep_out=[robot_keep_out(robot_xy, VARIANTS[scenario.robot.variant].reach)],
        ),
        clips=clip_catalog(scenario.human.clips),
    )
    return human, human_plant


def _add_workpieces(builder, scene_graph, plant, mirror, scenario, human):
    """Workpieces rest on the mirror's cell surfaces and follow the dynamic plant's tool."""
    if not scenario.workpieces.types:
        return None
    tool_frame = None
    if scenario.robot.tool != NO_TOOL:
        tool_frame = plant.GetFrameByName(TCP_FRAME, plant.GetModelInstanceByName(TOOL_MODEL))
    workpieces = add_workpieces(
        builder,
        scene_graph,
        mirror,
        scenario.workpieces,
        seed=stream(scenario.seed, "workpieces"),
        tool_frame=tool_frame,
        areas={name: scenario.area(name) for name in scenario.areas},
        issuers=(*(tree_issuer(agent) for agent in AGENTS), GRIPPER_ISSUER),
    )
    if human is not None:
        hands = builder.AddNamedSystem("human_hands", HumanHands())
        builder.Connect(human.GetOutputPort("human_status"), hands.get_input_port())
        builder.Connect(hands.get_output_port(), workpieces.GetInputPort("human_hands"))
    return workpieces


def _add_safety(builder, scene_graph, mirror, human_plant, motion, workpieces, scenario):
    if human_plant is None or not scenario.safety.enabled:
        return None
    safety = add_safety_monitor(
        builder,
        scene_graph,
        mirror,
        human_plant,
        human_plant.GetModelInstanceByName(HUMAN_NAME),
        scenario.safety,
        scenario.robot.variant,
        carriable=workpieces.geometry_ids if workpieces is not None else (),
        command_latency=scenario.robot.motion.update_period,
    )
    builder.Connect(safety.GetOutputPort("speed_scale"), motion.GetInputPort("speed_scale"))
    builder.Connect(motion.GetOutputPort("path_rate"), safety.GetInputPort("robot_path_rate"))
    if workpieces is not None:
        builder.Connect(
            workpieces.GetOutputPort("workpieces_status"),
            safety.get_workpieces_status_input_port(),
        )
    return safety


def _add_audit(builder, scene_graph, mirror, human, human_plant, workpieces, scenario):
    """The realism audit of the person, sampled at the person's own rate."""
    if human is None:
        return None
    solids = workpieces.cell.solids() if workpieces is not None else {}
    return add_realism_audit(
        builder,
        scene_graph,
        mirror,
        human_plant,
        human_plant.GetModelInstanceByName(HUMAN_NAME),
        human,
        workpieces,
        solids,
        period=human.period,
        stride_time=human.stride_time,
    )


def _add_tree(builder, scenario, agent: str, actors: dict) -> BehaviorTreeSystem:
    """The agent's tree, reading every actor's status and commanding the actors it may:
    the robot's tree the robot, the person's tree the person, both trees the workpieces and
    (to call the person) the person."""
    tree, context = load_agent_tree(scenario, agent)
    system = builder.AddNamedSystem(
        f"bt_{agent}",
        BehaviorTreeSystem(
            tree, context, stream(scenario.seed, f"tree/{agent}"), scenario.trees[agent].period
        ),
    )
    for source in STATUS_INPUTS:
        if actors[source] is not None:
            builder.Connect(
                _status_output(source, actors[source]), system.GetInputPort(status_port(source))
            )
    commanded = [
        (HUMAN, f"{tree_issuer(agent)}_command"),
        (WORKPIECES, f"{tree_issuer(agent)}_command"),
    ]
    if agent == ROBOT:
        commanded.append((ROBOT, "robot_command"))
    for actor, port in commanded:
        if actors[actor] is not None:
            builder.Connect(
                system.GetOutputPort(command_port(actor)), actors[actor].GetInputPort(port)
            )
    return system


def _status_output(actor_name: str, system):
    return system.GetOutputPort(status_port(actor_name))


def _export_outputs(builder, plant, arm, scene_graph, actors, trees) -> None:
    builder.ExportOutput(plant.get_state_output_port(arm), "robot_state")
    builder.ExportOutput(scene_graph.get_query_output_port(), "query_object")
    builder.ExportOutput(plant.get_body_poses_output_port(), "body_poses")
    motion = actors[ROBOT]
    builder.ExportOutput(motion.GetOutputPort("robot_status"), "robot_status")
    builder.ExportOutput(motion.GetOutputPort("desired_state"), "robot_desired_state")
    for name in (HUMAN, WORKPIECES, SAFETY):
        if actors[name] is not None:
            builder.ExportOutput(_status_output(name, actors[name]), status_port(name))
    if actors[SAFETY] is not None:
        builder.ExportOutput(actors[SAFETY].GetOutputPort("safety_signals"), "safety_signals")
    for tree in trees:
        builder.ExportOutput(tree.GetOutputPort("tree_status"), f"{tree.agent}_tree_status")
        builder.ExportOutput(tree.GetOutputPort("task_events"), f"{tree.agent}_task_events")


def _export_open_inputs(builder, systems) -> None:
    for system in (s for s in systems if s is not None):
        for i in range(system.num_input_ports()):
            port = system.get_input_port(i)
            if not builder.IsConnectedOrExported(port):
                builder.ExportInput(port, f"{system.get_name()}.{port.get_name()}")


def _add_visualizer(builder, scene_graph, meshcat, scenario, actors) -> None:
    """Meshcat draws the world scene; with `record`, a ReplayRecorder samples it (and the
    safety state and held workpieces) for replay.html at the visualizer's rate."""
    options = scenario.visualization
    dress_scene(
        meshcat,
        options.camera_position,
        options.camera_target,
        scenario.robot.base_pose.GetDeterministicValue(),
    )
    roles = {VISUAL_PREFIX: Role.kIllustration}
    if options.show_collision:
        roles["collision"] = Role.kProximity
    for prefix, role in roles.items():
        params = MeshcatVisualizerParams(
            publish_period=options.publish_period, role=role, prefix=prefix
        )
        visualizer = MeshcatVisualizer.AddToBuilder(builder, scene_graph, meshcat, params)
        if role == Role.kIllustration:
            visualizer.set_name(VISUALIZER)
    if not options.record:
        return
    recorder = builder.AddNamedSystem(RECORDER, ReplayRecorder(options.publish_period, roles))
    builder.Connect(scene_graph.get_query_output_port(), recorder.GetInputPort("query_object"))
    for name in (SAFETY, WORKPIECES):
        if actors[name] is not None:
            builder.Connect(
                _status_output(name, actors[name]), recorder.GetInputPort(status_port(name))
            )
