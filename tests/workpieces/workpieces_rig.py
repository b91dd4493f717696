"""A small workcell diagram for the workpieces tests: a discrete SAP plant with cell models
(and one free part, so the plant computes contact every step), SceneGraph, Workpieces, and
scripted sources for the issuers' commands and the holders' poses."""

import bisect
import math
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from pydrake.common.eigen_geometry import Quaternion
from pydrake.common.schema import Transform
from pydrake.common.value import AbstractValue
from pydrake.common.yaml import yaml_load_typed
from pydrake.math import RigidTransform, RollPitchYaw
from pydrake.multibody.parsing import Parser
from pydrake.multibody.plant import AddMultibodyPlant, MultibodyPlantConfig
from pydrake.systems.analysis import Simulator
from pydrake.systems.framework import DiagramBuilder, LeafSystem

from hrc_drake.areas import Area
from hrc_drake.messages import NO_COMMANDS
from hrc_drake.paths import MODEL_PACKAGE, add_model_package
from hrc_drake.seeding import stream
from hrc_drake.systems.workpieces import add_workpieces
from hrc_drake.wiring import WORKPIECES_SYSTEM
from hrc_drake.workpieces.config import ConveyorConfig, ObjectType, PlacedObject, WorkpiecesConfig
from hrc_drake.workpieces.messages import ROBOT_HOLDER, Attach, Detach, HandPoses
from hrc_drake.yaml_check import check_node, compose

WORK_TABLE_XY = (0.0, 0.9)
TABLE_TOP = 0.9
CONVEYOR_Y = -1.5
BELT_TOP = 0.85
PART = ObjectType(shape="box", size=[0.12, 0.08, 0.05], mass=0.4, capacity=6)
PART_HEIGHT = 0.05
TOOL_DOWN = RollPitchYaw(math.pi, 0.0, 0.0)
CELL = {
    "floor": RigidTransform(),
    "work_table": RigidTransform([*WORK_TABLE_XY, 0.0]),
    "conveyor": RigidTransform([0.0, CONVEYOR_Y, 0.0]),
}


class TimedValue(LeafSystem):
    """An abstract output that is a function of time only (a script)."""

    def __init__(self, value_at: Callable[[float], object], model: object):
        super().__init__()
        self.DeclareAbstractOutputPort(
            "value",
            lambda: AbstractValue.Make(model),
            lambda context, output: output.set_value(value_at(context.get_time())),
            prerequisites_of_calc={self.time_ticket()},
        )


def script(timed_commands: list[tuple[float, object]]) -> Callable[[float], object]:
    """The latest command whose time has come, or none yet."""

    def latest(t: float):
        sent = [command for time, command in timed_commands if time <= t]
        return sent[-1] if sent else NO_COMMANDS

    return latest


def path(knots: list[tuple[float, tuple[float, float, float], RollPitchYaw]]) -> Callable:
    """A pose path through (time, position, orientation) knots, at rest at every knot (cubic
    ease in and out, slerp for the rotation), held before the first and after the last."""
    times = [t for t, _, _ in knots]
    poses = [RigidTransform(rpy, list(p)) for _, p, rpy in knots]

    def pose_at(t: float) -> RigidTransform:
        i = min(max(bisect.bisect_right(times, t), 1), len(times) - 1)
        s = min(max((t - times[i - 1]) / (times[i] - times[i - 1]), 0.0), 1.0)
        s = s * s * (3.0 - 2.0 * s)
        X0, X1 = poses[i - 1], poses[i]
        q = X0.rotation().ToQuaternion().slerp(s, X1.rotation().ToQuaternion())
        p = (1.0 - s) * X0.translation() + s * X1.translation()
        return RigidTransform(Quaternion(q.wxyz() / np.linalg.norm(q.wxyz())), p)

    return pose_at


def hands_path(left: Callable, right: Callable, rate: float = 60.0) -> Callable:
    """Hand poses sampled at `rate` and held, stamped with their sample time, as HumanActor
    gives them."""

    def sampled(t: float) -> HandPoses:
        sample_time = math.floor(t * rate + 1e-9) / rate
        return HandPoses(left(sample_time), right(sample_time), sample_time)

    return sampled


def part_on_table(x: float = 0.0, y: float = WORK_TABLE_XY[1], **attributes) -> PlacedObject:
    pose = Transform(translation=[x, y, TABLE_TOP + PART_HEIGHT / 2])
    return PlacedObject(type="part", pose=pose, attributes=attributes)


def config_with(**changes) -> WorkpiecesConfig:
    """The tests' configuration: parts, and a queueing belt along the cell's conveyor."""
    belt = ConveyorConfig(start=[-1.0, CONVEYOR_Y, BELT_TOP], end=[1.0, CONVEYOR_Y, BELT_TOP])
    config = WorkpiecesConfig(types={"part": PART}, conveyors={"belt": belt})
    for name, value in changes.items():
        setattr(config, name, value)
    return config


EXAMPLE = Path(__file__).with_name("workpieces_example.yaml")


@dataclass
class Section:
    """A scenario file reduced to its `workpieces:` section."""

    workpieces: WorkpiecesConfig = field(default_factory=WorkpiecesConfig)


def load_example() -> WorkpiecesConfig:
    text = EXAMPLE.read_text()
    check_node(EXAMPLE, compose(EXAMPLE, text), Section)
    return yaml_load_typed(schema=Section, data=text).workpieces


@dataclass
class Rig:
    simulator: Simulator
    diagram: object
    workpieces: object
    scene_graph: object
    plant: object

    def advance(self, t: float):
        """Simulates until `t` and returns the workpieces' status there."""
        self.simulator.AdvanceTo(t)
        return self.status()

    def status(self):
        context = self.workpieces.GetMyContextFromRoot(self.simulator.get_context())
        return self.workpieces.GetOutputPort("workpieces_status").Eval(context)

    def query(self):
        context = self.scene_graph.GetMyContextFromRoot(self.simulator.get_context())
        return self.scene_graph.get_query_output_port().Eval(context)


def build_rig(
    config: WorkpiecesConfig,
    commands: dict[str, list[tuple[float, object]]] | None = None,
    tool: Callable[[float], RigidTransform] | None = None,
    hands: Callable[[float], HandPoses] | None = None,
    seed: int = 0,
    areas: dict[str, Area] | None = None,
) -> Rig:
    builder = DiagramBuilder()
    plant_config = MultibodyPlantConfig(time_step=1e-3, discrete_contact_approximation="sap")
    plant, scene_graph = AddMultibodyPlant(plant_config, builder)
    _add_cell(plant)
    plant.Finalize()
    seed_stream = stream(seed, WORKPIECES_SYSTEM)
    workpieces = add_workpieces(builder, scene_graph, plant, config, seed_stream, areas=areas)
    for issuer, timed in (commands or {}).items():
        source = builder.AddSystem(TimedValue(script(timed), NO_COMMANDS))
        builder.Connect(source.get_output_port(), workpieces.GetInputPort(f"{issuer}_command"))
    holders = {"tool_pose": (tool, RigidTransform()), "human_hands": (hands, None)}
    for port, (value_at, model) in holders.items():
        if value_at is not None:
            source = builder.AddSystem(TimedValue(value_at, model or value_at(0.0)))
            builder.Connect(source.get_output_port(), workpieces.GetInputPort(port))
    diagram = builder.Build()
    simulator = Simulator(diagram)
    simulator.Initialize()
    return Rig(simulator, diagram, workpieces, scene_graph, plant)


def _add_cell(plant) -> None:
    parser = Parser(plant)
    add_model_package(parser.package_map())
    for name, X_WB in CELL.items():
        (model,) = parser.AddModels(url=f"package://{MODEL_PACKAGE}/cell/{name}.sdf")
        plant.WeldFrames(plant.world_frame(), plant.GetFrameByName("body", model), X_WB)
    (free_part,) = parser.AddModels(url=f"package://{MODEL_PACKAGE}/cell/part_small.sdf")
    body = plant.GetBodyByName("body", free_part)
    plant.SetDefaultFloatingBaseBodyPose(body, RigidTransform([3.0, 3.0, 0.015]))


X, Y = WORK_TABLE_XY
PART_TOP = TABLE_TOP + PART_HEIGHT
TURNED = RollPitchYaw(np.pi, 0.0, np.pi / 2)
GRIP = [(0.3, Attach(seq=1, holder=ROBOT_HOLDER, max_mass=3.0))]


def carry_to(destination, release_at: float = 3.2):
    """Tool path: down onto the part at the table centre, grip, lift, turn, carry, release."""
    tool = path(
        [
            (0.0, (X, Y, PART_TOP), TOOL_DOWN),
            (0.5, (X, Y, PART_TOP), TOOL_DOWN),
            (1.5, (X + 0.2, Y + 0.1, 1.3), TURNED),
            (2.8, destination, TURNED),
            (4.0, destination, TURNED),
        ]
    )
    commands = {"robot_gripper": [*GRIP, (release_at, Detach(seq=2, holder=ROBOT_HOLDER))]}
    return tool, commands
