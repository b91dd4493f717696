"""Test scenarios and their station (plant, cell, controller, RobotMotion), commanded
through the inputs the builder exports when no behavior tree drives the robot."""

import dataclasses
from dataclasses import dataclass, field

import numpy as np
from pydrake.common.yaml import yaml_load_typed
from pydrake.math import RigidTransform
from pydrake.systems.analysis import Simulator
from pydrake.systems.framework import EventStatus

from hrc_drake.builder import build_diagram
from hrc_drake.messages import FINISHED
from hrc_drake.scenario import Scenario

PEDESTAL_TOP = 0.8
TABLE_Y = {"lbr_iisy3_r760": 0.65, "lbr_iisy11_r1300": 0.9, "lbr_iisy15_r930": 0.75}
"""Work table centre in front of each variant (its top is 0.9 m high, 0.8 m deep)."""

CELL = """
  - add_model: {{name: floor, file: package://hrc_drake_models/cell/floor.sdf}}
  - add_weld: {{parent: world, child: floor::body}}
  - add_model: {{name: pedestal, file: package://hrc_drake_models/cell/robot_pedestal.sdf}}
  - add_weld: {{parent: world, child: pedestal::body}}
  - add_model: {{name: work_table, file: package://hrc_drake_models/cell/work_table.sdf}}
  - add_weld:
      parent: world
      child: work_table::body
      X_PC: {{translation: [0.0, {table_y}, 0.0]}}
"""

BOX = """
  - add_model: {{name: obstacle, file: package://hrc_drake_models/cell/box_small.sdf}}
  - add_weld:
      parent: world
      child: obstacle::body
      X_PC: {{translation: [{x}, {y}, 1.0], rotation: !Rpy {{deg: [0, 0, 90]}}}}
"""


def make_scenario(variant: str = "lbr_iisy3_r760", box_at: tuple | None = None) -> Scenario:
    """The robot on its pedestal with a work table in front; optionally a box on the table."""
    cell = CELL.format(table_y=TABLE_Y[variant])
    if box_at is not None:
        cell += BOX.format(x=box_at[0], y=box_at[1])
    text = f"""
name: motion_test_{variant}
robot:
  variant: {variant}
  base_pose: {{translation: [0.0, 0.0, {PEDESTAL_TOP}]}}
  configurations_deg:
    ready: [0, -45, 90, 0, 45, 0]
cell:{cell}"""
    return yaml_load_typed(schema=Scenario, data=text)


@dataclass
class Station:
    diagram: object
    simulator: Simulator
    motion: object
    plant: object

    @property
    def context(self):
        return self.simulator.get_context()

    def command(self, command) -> None:
        self.diagram.GetInputPort("robot_motion.robot_tree_command").FixValue(self.context, command)

    def set_safety_scale(self, scale: float) -> None:
        self.diagram.GetInputPort("robot_motion.speed_scale").FixValue(self.context, [scale])

    def status(self):
        return self.diagram.GetOutputPort("robot_status").Eval(self.context)

    def q(self) -> np.ndarray:
        return self.diagram.GetOutputPort("robot_state").Eval(self.context)[:6].copy()

    def velocity_norm(self) -> float:
        """Largest joint speed (rad/s) of the simulated arm."""
        return float(np.abs(self.diagram.GetOutputPort("robot_state").Eval(self.context)[6:]).max())

    def tool_pose(self) -> RigidTransform:
        return self.motion.planner.model.tool_pose(self.q())

    def run_until_finished(self, seq: int, timeout: float = 10.0, on_step=None) -> str:
        """Advances in 10 ms steps until command `seq` finished; returns its outcome."""
        end = self.context.get_time() + timeout
        while self.context.get_time() < end:
            self.simulator.AdvanceTo(self.context.get_time() + 0.01)
            if on_step is not None:
                on_step(self)
            outcome = self.status().results.outcome_of(seq)
            if outcome in FINISHED:
                return outcome
        return "timeout"


@dataclass
class Trace:
    """Per-plant-step samples of a run: time, tool position, desired q̇ and q̈, status."""

    t: list = field(default_factory=list)
    tool: list = field(default_factory=list)
    velocity: list = field(default_factory=list)
    acceleration: list = field(default_factory=list)
    speed_scale: list = field(default_factory=list)
    outcomes: list = field(default_factory=list)
    modes: list = field(default_factory=list)
    final: str = ""

    def arrays(self):
        return {k: np.array(v) for k, v in self.__dict__.items() if isinstance(v, list)}


def record(station: Station, seq: int, actions=None, timeout: float = 10.0) -> Trace:
    """Runs until command `seq` finishes, sampling every plant step; `actions` maps
    simulation times to callables(station) applied once that time is reached."""
    trace = Trace()
    pending = sorted((actions or {}).items())
    model = station.motion.planner.model
    desired_state = station.diagram.GetOutputPort("robot_desired_state")
    desired_acceleration = station.diagram.GetOutputPort("robot_desired_acceleration")

    def monitor(context):
        desired = desired_state.Eval(context)
        status = station.status()
        trace.t.append(context.get_time())
        trace.tool.append(model.tool_pose(station.q()).translation())
        trace.velocity.append(desired[6:].copy())
        trace.acceleration.append(desired_acceleration.Eval(context).copy())
        trace.speed_scale.append(status.speed_scale)
        trace.outcomes.append(status.results.outcome_of(seq))
        trace.modes.append(status.mode)
        return EventStatus.Succeeded()

    station.simulator.set_monitor(monitor)
    try:
        for at, action in pending:
            station.simulator.AdvanceTo(at)
            action(station)
        trace.final = station.run_until_finished(seq, timeout)
    finally:
        station.simulator.clear_monitor()
    return trace


def build_station(scenario: Scenario, workpieces=None) -> Station:
    """The scenario's station; with a WorkpiecesConfig, also the workpieces and the vacuum."""
    if workpieces is not None:
        scenario = dataclasses.replace(scenario, workpieces=workpieces)
    parts = []
    diagram = build_diagram(scenario, attach=lambda _, station: parts.append(station))
    simulator = Simulator(diagram)
    simulator.Initialize()
    return Station(diagram, simulator, parts[0].robot_motion, parts[0].plant)


def distance_to_polyline(points: np.ndarray, polyline: np.ndarray) -> np.ndarray:
    """Distance of each point to the polyline through `polyline`'s rows."""
    a, b = polyline[:-1], polyline[1:]
    ab = b - a
    length_squared = np.maximum((ab * ab).sum(axis=1), 1e-18)
    distances = []
    for p in points:
        t = np.clip(((p - a) * ab).sum(axis=1) / length_squared, 0.0, 1.0)
        distances.append(np.linalg.norm(a + t[:, None] * ab - p, axis=1).min())
    return np.array(distances)
