"""The person in a small diagram: SceneGraph, the person, scripted commands and, when asked,
furniture from our cell models (the floor, a table), which the person walks round; what the
person's body goes into is measured in SceneGraph, as the realism audit measures it."""

import numpy as np
from pydrake.geometry import Box, GeometryInstance, ProximityProperties, Role, SceneGraph
from pydrake.math import RigidTransform, RollPitchYaw
from pydrake.multibody.parsing import Parser
from pydrake.multibody.plant import AddMultibodyPlantSceneGraph, MultibodyPlant
from pydrake.systems.analysis import Simulator
from pydrake.systems.framework import DiagramBuilder, LeafSystem

from hrc_drake.human.anthropometry import DEFAULT_HEIGHT, DEFAULT_MASS
from hrc_drake.human.body import human_body, parse_human
from hrc_drake.human.navigation import NavigationMap, cell_obstacles
from hrc_drake.messages import NO_COMMANDS
from hrc_drake.modelgen.cell import BODY
from hrc_drake.paths import MODEL_PACKAGE, add_model_package
from hrc_drake.ports import message_value
from hrc_drake.systems.human_actor import add_human

SAMPLE = 1.0 / 60.0
COLLISION_SHAPES = 21
"""The body's collision shapes: one per ISO/TS 15066 region's body part, the forearms two
each (thinning to the wrist, docs/human-body.md)."""


class ScriptedCommands(LeafSystem):
    """Emits the latest command whose time has come (like a behavior tree's command port)."""

    def __init__(self, schedule):
        LeafSystem.__init__(self)
        self._schedule = sorted(schedule, key=lambda item: item[0])
        self.DeclareAbstractOutputPort("command", message_value, self._calc)

    def _calc(self, context, output):
        latest = NO_COMMANDS
        for time, command in self._schedule:
            if context.get_time() >= time:
                latest = command
        output.set_value(latest)


def furniture(model: str, x: float, y: float, yaw_deg: float = 0.0):
    """One of our cell models (hrc_drake.modelgen.cell) standing at (x, y), turned by yaw."""
    return model, RigidTransform(RollPitchYaw(0.0, 0.0, np.radians(yaw_deg)), [x, y, 0.0])


FLOOR = furniture("floor", 0.0, 0.0)


def _add_cell(builder, scene_graph, cell) -> MultibodyPlant | None:
    """The furniture welded in place in a plant of its own, registered with `scene_graph`."""
    if not cell:
        return None
    plant = builder.AddSystem(MultibodyPlant(0.0))
    plant.set_name("cell")
    plant.RegisterAsSourceForSceneGraph(scene_graph)
    parser = Parser(plant)
    add_model_package(parser.package_map())
    parser.SetAutoRenaming(True)
    for model, X_WB in cell:
        (instance,) = parser.AddModels(url=f"package://{MODEL_PACKAGE}/cell/{model}.sdf")
        plant.WeldFrames(plant.world_frame(), plant.GetFrameByName(BODY, instance), X_WB)
    plant.Finalize()
    builder.Connect(
        plant.get_geometry_pose_output_port(),
        scene_graph.get_source_pose_port(plant.get_source_id()),
    )
    return plant


def _add_boxes(scene_graph, boxes) -> None:
    """Boxes (size, X_WB) standing in the scene, as objects on a table stand."""
    source = scene_graph.RegisterSource("objects")
    for k, (size, X_WB) in enumerate(boxes):
        instance = GeometryInstance(X_WB, Box(*size), f"object_{k}")
        instance.set_proximity_properties(ProximityProperties())
        scene_graph.RegisterAnchoredGeometry(source, instance)


class Run:
    """A small diagram: SceneGraph, the person, a scripted command source, `cell` furniture
    (see `furniture`) that the person walks round and `objects` (boxes: size and pose) that
    the person knows of only as the commands tell; what the body's `segments` go into is
    measured (`deepest`, `overlap`)."""

    def __init__(self, schedule, start_pose=(0.0, 0.0, 0.0), cell=(), segments=("",), objects=()):
        builder = DiagramBuilder()
        scene_graph = builder.AddSystem(SceneGraph())
        cell_plant = _add_cell(builder, scene_graph, cell)
        _add_boxes(scene_graph, objects)
        navigation = None
        if cell_plant is not None:
            obstacles = cell_obstacles(cell_plant, scene_graph.model_inspector())
            navigation = NavigationMap(obstacles)
        self.actor, self.plant = add_human(
            builder, scene_graph, start_pose=start_pose, navigation=navigation
        )
        script = builder.AddSystem(ScriptedCommands(schedule))
        builder.Connect(script.get_output_port(), self.actor.GetInputPort("human_tree_command"))
        self.scene_graph = scene_graph
        self.simulator = Simulator(builder.Build())
        self.context = self.actor.GetMyContextFromRoot(self.simulator.get_mutable_context())
        self.body = self.actor.body
        self._human_geometry = set(self.plant_geometries())
        self.furnished = bool(cell) or bool(objects)
        self.segments = tuple(segments)
        self.overlap = (0.0, "", 0.0)

    def plant_geometries(self):
        inspector = self.scene_graph.model_inspector()
        return [
            g
            for g in inspector.GetAllGeometryIds()
            if inspector.GetProximityProperties(g) is not None
            and inspector.BelongsToSource(g, self.plant.get_source_id())
        ]

    def status(self):
        return self.actor.GetOutputPort("human_status").Eval(self.context)

    def positions(self):
        return self.actor.GetOutputPort("human_positions").Eval(self.context).copy()

    def advance(self, t):
        self.simulator.AdvanceTo(t)
        return self.status()

    def deepest(self) -> tuple[float, str]:
        """How deep (m) the person's body (its `segments`: those whose collision geometry
        names start with one of them; all by default) goes into the furniture now, and
        where: the deepest overlap of a segment's collision shape with the cell's geometry."""
        sg_context = self.scene_graph.GetMyContextFromRoot(self.simulator.get_context())
        query = self.scene_graph.get_query_output_port().Eval(sg_context)
        inspector = query.inspector()
        worst = (0.0, "")
        for pair in query.ComputePointPairPenetration():
            ours = [g for g in (pair.id_A, pair.id_B) if g in self._human_geometry]
            if len(ours) != 1 or pair.depth <= worst[0]:
                continue
            if not inspector.GetName(ours[0]).split("::")[-1].startswith(self.segments):
                continue
            other = pair.id_B if ours[0] == pair.id_A else pair.id_A
            where = f"{inspector.GetName(ours[0])} in {inspector.GetName(other)}"
            worst = (pair.depth, where)
        return worst

    def record(self, until):
        """Statuses and canonical joint positions after every update until `until` (read
        halfway between updates: read at an update's own time, rounding decides whether it
        has run yet, and a pose held over one reading doubles the next step). With furniture,
        `overlap` keeps the deepest the body went into it meanwhile: (depth, where, when)."""
        start = self.simulator.get_context().get_time()
        times = np.arange(start, until, SAMPLE) + 1.5 * SAMPLE
        statuses, poses = [], []
        for t in times:
            self.simulator.AdvanceTo(t)
            statuses.append(self.status())
            poses.append(self.positions()[self.body.plant_index])
            if self.furnished:
                depth, where = self.deepest()
                if depth > self.overlap[0]:
                    self.overlap = (depth, where, t)
        return statuses, np.array(poses)


class Posed:
    """The person's collision shapes posed at q in a SceneGraph of their own, with boxes
    (size, X_WB) standing in for held objects: how far apart they are."""

    def __init__(self, q, boxes=()):
        builder = DiagramBuilder()
        plant, scene_graph = AddMultibodyPlantSceneGraph(builder, 0.0)
        parse_human(plant, DEFAULT_HEIGHT, DEFAULT_MASS)
        plant.Finalize()
        _add_boxes(scene_graph, boxes)
        inspector = scene_graph.model_inspector()
        self.boxes = [
            inspector.GetGeometryIdByName(scene_graph.world_frame_id(), Role.kProximity, name)
            for name in (f"object_{k}" for k in range(len(boxes)))
        ]
        diagram = builder.Build()
        context = diagram.CreateDefaultContext()
        plant.SetPositions(plant.GetMyContextFromRoot(context), human_body().plant_positions(q))
        self.query = scene_graph.get_query_output_port().Eval(
            scene_graph.GetMyContextFromRoot(context)
        )

    def distance(self, box: int, segments) -> float:
        """Signed distance (m) from box number `box` to the body's `segments` (collision
        geometry names start with one of them, e.g. "abdomen")."""
        inspector = self.query.inspector()
        return min(
            self.query.ComputeSignedDistancePairClosestPoints(self.boxes[box], g).distance
            for g in inspector.GetAllGeometryIds(Role.kProximity)
            if inspector.GetName(g).split("::")[-1].startswith(tuple(segments))
        )
