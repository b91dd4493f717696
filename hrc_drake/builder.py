"""Scenario -> one Drake Diagram (the `manipulation.station` / `hardware_sim` pattern).

The station holds the dynamic plant (robot + tool + static cell) under its inverse-dynamics
controller and RobotMotion; the kinematic person (HumanActor); the Workpieces; the
SafetyMonitor; one BehaviorTreeSystem per agent; SceneGraph; and, when asked, a Meshcat
visualizer with the ReplayRecorder that replay.html is made from. Each part is present when
the scenario asks for it: no `human:` section, no person and no monitor; no workpiece types,
no Workpieces (and with neither, no realism audit); no `trees:`, no behavior trees. Which
tree commands which actor, and the names of every port and system, come from
`hrc_drake.wiring`.

One SceneGraph, the world scene named `scene_graph`: a kinematic mirror of the robot and
cell (posed from the plant's state), the person and the workpieces. The safety monitor,
Meshcat and the `query_object` output see it, when they ask. The dynamic plant simulates
the robot alone, without geometry (`station.make_dynamic_plant`): its steps pose nothing
and query no contact.

Command inputs that no tree drives are exported as `<system>.<port>` (e.g.
`robot_motion.robot_tree_command`), so tests and notebooks can command the actors directly.
Outputs are exported by name: `robot_state`, `robot_status`, `robot_desired_state`,
`robot_desired_acceleration`,
`query_object`, `body_poses`, and when present `human_status`, `workpieces_status`,
`safety_status`, `safety_signals`, `realism` (the realism audit: the person's and the
objects', or the objects' alone in a cell without a person),
`<agent>_tree_status`, `<agent>_task_events`.

Whoever needs more of the station than its exported ports (the runner's loggers and tree
logs, say) passes `attach`: it is called with the DiagramBuilder and the Station (its parts)
before the diagram is built, and adds and connects what it needs.
"""

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from pydrake.geometry import Meshcat, MeshcatVisualizer, MeshcatVisualizerParams, Role, SceneGraph
from pydrake.multibody.plant import MultibodyPlant
from pydrake.multibody.tree import ModelInstanceIndex
from pydrake.systems.framework import Diagram, DiagramBuilder
from pydrake.systems.primitives import Demultiplexer
from pydrake.systems.rendering import MultibodyPositionToGeometryPose

from hrc_drake.evaluation.replay import camera_of, dress_scene
from hrc_drake.evaluation.replay_sensors import draw_sensors
from hrc_drake.human.clip_files import clip_catalog
from hrc_drake.human.navigation import cell_navigation, cell_obstacles
from hrc_drake.iisy import TCP_FRAME, VARIANTS
from hrc_drake.scenario import HumanConfig, Scenario
from hrc_drake.seeding import stream
from hrc_drake.station import add_station_models, make_dynamic_plant, model_parser
from hrc_drake.systems.adapters import add_human_hands
from hrc_drake.systems.behavior_tree import BehaviorTreeSystem
from hrc_drake.systems.human_actor import HumanActor, add_human
from hrc_drake.systems.realism_audit import RealismAudit, add_realism_audit
from hrc_drake.systems.replay_recorder import ReplayRecorder
from hrc_drake.systems.robot_controller import RobotController, add_robot_controller
from hrc_drake.systems.robot_motion import RobotMotion, add_robot_motion
from hrc_drake.systems.safety_monitor import SafetyMonitor, add_safety_monitor
from hrc_drake.systems.safety_sensors import SafetySensors, add_safety_sensors
from hrc_drake.systems.workpieces import Workpieces, add_workpieces
from hrc_drake.wiring import (
    COMMANDED_BY,
    DYNAMIC_PLANT,
    HUMAN,
    HUMAN_MODEL,
    RECORDER,
    ROBOT,
    ROBOT_MOTION,
    SAFETY,
    SCENE_GRAPH,
    STATION_MIRROR,
    STATION_MIRROR_GEOMETRY,
    TOOL_MODEL,
    VISUAL_PREFIX,
    VISUALIZER,
    WORKPIECES,
    WORKPIECES_SYSTEM,
    command_input,
    command_output,
    status_port,
    tree_issuer,
    tree_system,
)


@dataclass(frozen=True)
class Station:
    """The parts of a station, as `attach` hooks see them; None where the scenario has no
    such part."""

    plant: MultibodyPlant
    arm: ModelInstanceIndex
    controller: RobotController
    scene_graph: SceneGraph
    robot_motion: RobotMotion
    desired_motion: Demultiplexer
    """RobotMotion's desired state (output 0) and acceleration (output 1), as the
    controller reads them."""
    human: HumanActor | None
    workpieces: Workpieces | None
    safety: SafetyMonitor | None
    realism_audit: RealismAudit | None
    trees: dict[str, BehaviorTreeSystem]
    recorder: ReplayRecorder | None
    sensors: SafetySensors | None = None

    @property
    def status_sources(self) -> dict:
        """The system behind every status source that the station has."""
        return _status_sources(self.robot_motion, self.human, self.workpieces, self.safety)


def _status_sources(robot_motion, human, workpieces, safety) -> dict:
    found = {ROBOT: robot_motion, HUMAN: human, WORKPIECES: workpieces, SAFETY: safety}
    return {source: system for source, system in found.items() if system is not None}


def _status_output(sources: dict, source: str):
    return sources[source].GetOutputPort(status_port(source))


Attach = Callable[[DiagramBuilder, Station], None]


def build_diagram(
    scenario: Scenario, meshcat: Meshcat | None = None, attach: Attach | None = None
) -> Diagram:
    """The whole scenario as one Diagram named after the scenario (see module docstring)."""
    builder = DiagramBuilder()
    spec = scenario.station
    plant, arm = make_dynamic_plant(spec, scenario.plant)
    builder.AddNamedSystem(DYNAMIC_PLANT, plant)
    controller = add_robot_controller(builder, spec, plant, arm)
    scene_graph, mirror = _add_world_scene(builder, plant, scenario)

    human, human_plant = _add_person(builder, scene_graph, mirror, scenario)
    workpieces = _add_workpieces(builder, scene_graph, plant, mirror, scenario, human)
    motion, desired = add_robot_motion(
        builder,
        spec,
        stream(scenario.seed, ROBOT_MOTION),
        plant,
        arm,
        controller,
        scenario.robot.motion,
        workpieces,
    )
    safety = _add_safety(builder, scene_graph, mirror, human_plant, motion, workpieces, scenario)
    sensors = _add_sensors(builder, scene_graph, mirror, human_plant, safety, scenario)
    audit = _add_audit(builder, scene_graph, mirror, human, human_plant, workpieces, scenario)
    if human is not None:
        for reader in filter(None, (motion, safety)):
            builder.Connect(
                human.GetOutputPort(status_port(HUMAN)), reader.GetInputPort(status_port(HUMAN))
            )
    sources = _status_sources(motion, human, workpieces, safety)
    trees = {agent: _add_tree(builder, scenario, agent, sources) for agent in scenario.trees}
    recorder = None
    if meshcat is not None:
        recorder = _add_visualizer(builder, scene_graph, mirror, meshcat, scenario, sources)
    station = Station(
        plant,
        arm,
        controller,
        scene_graph,
        motion,
        desired,
        human,
        workpieces,
        safety,
        audit,
        trees,
        recorder,
        sensors,
    )
    _export_outputs(builder, station)
    _export_open_inputs(builder, [motion, human, workpieces])
    if attach is not None:
        attach(builder, station)
    diagram = builder.Build()
    diagram.set_name(scenario.name)
    return diagram


def _add_world_scene(builder, plant, scenario):
    """The SceneGraph everyone else sees: a kinematic mirror of the robot and cell, posed
    from the dynamic plant's state, with the person and the workpieces beside it.

    Its frames are re-posed only when someone queries this scene (the safety monitor at
    100 Hz, Meshcat when it draws). Nothing here takes part in physics, so no collision
    filters are needed between them.
    """
    scene_graph = builder.AddNamedSystem(SCENE_GRAPH, SceneGraph())
    mirror = MultibodyPlant(0.0)
    mirror.set_name(STATION_MIRROR)
    mirror.RegisterAsSourceForSceneGraph(scene_graph)
    add_station_models(mirror, model_parser(mirror), scenario.station)
    mirror.Finalize()
    to_pose = builder.AddNamedSystem(
        STATION_MIRROR_GEOMETRY, MultibodyPositionToGeometryPose(mirror, True)
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
    return add_human(
        builder,
        scene_graph,
        *scenario.human.size(),
        start_pose=(x, y, np.radians(yaw_deg)),
        period=scenario.human.period,
        navigation=cell_navigation(
            mirror,
            scene_graph.model_inspector(),
            robot_xy,
            VARIANTS[scenario.robot.variant].reach,
            scenario.human.size()[0],
        ),
        clips=clip_catalog(scenario.human.clips),
    )


def _add_workpieces(builder, scene_graph, plant, mirror, scenario, human):
    """Workpieces rest on the mirror's cell surfaces and follow the dynamic plant's tool."""
    if not scenario.workpieces.types:
        return None
    tool_frame = None
    if scenario.station.has_tool:
        tool_frame = plant.GetFrameByName(TCP_FRAME, plant.GetModelInstanceByName(TOOL_MODEL))
    workpieces = add_workpieces(
        builder,
        scene_graph,
        mirror,
        scenario.workpieces,
        seed=stream(scenario.seed, WORKPIECES_SYSTEM),
        tool_frame=tool_frame,
        areas={name: scenario.area(name) for name in scenario.areas},
    )
    if human is not None:
        builder.Connect(add_human_hands(builder, human), workpieces.GetInputPort("human_hands"))
    return workpieces


def _add_safety(builder, scene_graph, mirror, human_plant, motion, workpieces, scenario):
    if human_plant is None or not scenario.safety.enabled:
        return None
    safety = add_safety_monitor(
        builder,
        scene_graph,
        mirror,
        human_plant,
        human_plant.GetModelInstanceByName(HUMAN_MODEL),
        scenario.safety,
        scenario.robot.variant,
        carriable=workpieces.geometry_ids if workpieces is not None else (),
        command_latency=scenario.robot.motion.period,
    )
    builder.Connect(safety.GetOutputPort("speed_scale"), motion.GetInputPort("speed_scale"))
    builder.Connect(motion.GetOutputPort("path_rate"), safety.GetInputPort("robot_path_rate"))
    if workpieces is not None:
        builder.Connect(
            workpieces.GetOutputPort(status_port(WORKPIECES)),
            safety.get_workpieces_status_input_port(),
        )
    return safety


def _add_sensors(builder, scene_graph, mirror, human_plant, safety, scenario):
    """The safety sensors the monitor sees the person through, reading the world scene:
    they report the person's geometry, and the mirror's anchored bodies never move."""
    config = scenario.safety.sensors
    if safety is None or not config.present:
        return None
    instance = human_plant.GetModelInstanceByName(HUMAN_MODEL)
    person = [
        geometry
        for body in human_plant.GetBodyIndices(instance)
        for geometry in human_plant.GetCollisionGeometriesForBody(human_plant.get_body(body))
    ]
    fixed = [
        geometry
        for body in mirror.GetBodiesWeldedTo(mirror.world_body())
        for geometry in mirror.GetCollisionGeometriesForBody(body)
    ]
    sensors = add_safety_sensors(builder, scene_graph, config, person, fixed, scenario.seed)
    builder.Connect(
        sensors.GetOutputPort("sensor_readings"), safety.GetInputPort("sensor_readings")
    )
    return sensors


def _add_audit(builder, scene_graph, mirror, human, human_plant, workpieces, scenario):
    """The realism audit, sampled at every `audit_every`-th of the person's poses; in a cell
    without a person, of the objects alone (at a default person's rate), when it has any."""
    if human is None and workpieces is None:
        return None
    solids = workpieces.cell.solids() if workpieces is not None else {}
    return add_realism_audit(
        builder,
        scene_graph,
        mirror,
        human,
        human_plant,
        workpieces,
        solids,
        period=(scenario.human or HumanConfig()).audit_period,
    )


def _add_tree(builder, scenario, agent: str, sources: dict) -> BehaviorTreeSystem:
    """The agent's tree, reading every status source and commanding the actors it may
    (hrc_drake.wiring.COMMANDED_BY) through their inputs for its issuer."""
    tree, handle = scenario.agent_tree(agent)
    system = builder.AddNamedSystem(
        tree_system(agent),
        BehaviorTreeSystem(
            tree, handle, stream(scenario.seed, f"tree/{agent}"), scenario.trees[agent].period
        ),
    )
    for source in sources:
        builder.Connect(_status_output(sources, source), system.GetInputPort(status_port(source)))
    for actor in COMMANDED_BY[agent]:
        if actor in sources:
            builder.Connect(
                system.GetOutputPort(command_output(actor)),
                sources[actor].GetInputPort(command_input(tree_issuer(agent))),
            )
    return system


def _export_outputs(builder, station: Station) -> None:
    builder.ExportOutput(station.plant.get_state_output_port(station.arm), "robot_state")
    builder.ExportOutput(station.scene_graph.get_query_output_port(), "query_object")
    builder.ExportOutput(station.plant.get_body_poses_output_port(), "body_poses")
    sources = station.status_sources
    for source in sources:
        builder.ExportOutput(_status_output(sources, source), status_port(source))
    desired = station.desired_motion
    builder.ExportOutput(desired.get_output_port(0), "robot_desired_state")
    builder.ExportOutput(desired.get_output_port(1), "robot_desired_acceleration")
    if station.safety is not None:
        builder.ExportOutput(station.safety.GetOutputPort("safety_signals"), "safety_signals")
    if station.realism_audit is not None:
        builder.ExportOutput(station.realism_audit.GetOutputPort("realism"), "realism")
    for agent, tree in station.trees.items():
        builder.ExportOutput(tree.GetOutputPort("tree_status"), f"{agent}_tree_status")
        builder.ExportOutput(tree.GetOutputPort("task_events"), f"{agent}_task_events")


def _export_open_inputs(builder, systems) -> None:
    for system in (s for s in systems if s is not None):
        for i in range(system.num_input_ports()):
            port = system.get_input_port(i)
            if not builder.IsConnectedOrExported(port):
                builder.ExportInput(port, f"{system.get_name()}.{port.get_name()}")


def _add_visualizer(
    builder, scene_graph, mirror, meshcat, scenario, sources
) -> ReplayRecorder | None:
    """Meshcat draws the world scene (seen by the scenario's camera, or one framing the
    mirror's cell); with `record`, a ReplayRecorder samples it (and the safety state and
    held workpieces) for replay.html at the visualizer's rate."""
    options = scenario.visualization
    obstacles = cell_obstacles(mirror, scene_graph.model_inspector())
    base = scenario.robot.base_pose.GetDeterministicValue()
    dress_scene(meshcat, *camera_of(scenario, obstacles), base)
    if SAFETY in sources and scenario.safety.sensors.present:
        draw_sensors(meshcat, scenario.safety.sensors)
    roles = {VISUAL_PREFIX: Role.kIllustration}
    if options.show_collision:
        roles["collision"] = Role.kProximity
    for prefix, role in roles.items():
        params = MeshcatVisualizerParams(publish_period=options.period, role=role, prefix=prefix)
        visualizer = MeshcatVisualizer.AddToBuilder(builder, scene_graph, meshcat, params)
        if role == Role.kIllustration:
            visualizer.set_name(VISUALIZER)
    if not options.record:
        return None
    recorder = builder.AddNamedSystem(RECORDER, ReplayRecorder(options.period, roles))
    builder.Connect(scene_graph.get_query_output_port(), recorder.GetInputPort("query_object"))
    for source in (SAFETY, WORKPIECES):
        if source in sources:
            builder.Connect(
                _status_output(sources, source), recorder.GetInputPort(status_port(source))
            )
    return recorder
