"""SafetyMonitor: ISO/TS 15066 speed and separation monitoring and contact assessment.

Periodically (default 100 Hz) it measures, from the shared SceneGraph's QueryObject, the
signed distance between every body region of the person and every robot part (links,
tool, carried object), the approach speeds at the closest points (from poses over time),
and judges them (`hrc_drake.safety.judge`). Outputs, all computed from state:

- `speed_scale` (size 1): for RobotMotion; 1 when far, 0 = monitored stop (also before
  the first measurement); 1 always when SSM is disabled (the monitor then only measures).
- `safety_status`: a `hrc_drake.safety.messages.SafetyStatus` for trees and reports.
- `safety_signals`: the status as a vector (`SIGNALS`) for loggers, timelines, heat maps.

Optional input `workpieces_status` (Workpieces' status): the object the robot's gripper
holds becomes a robot part (its geometry is watched like a link's, reported as
`carried object`) and its mass is added to the payload. The person's hand on that object
while the robot stands still is a hand-over grasp, not a contact.

Optional input `human_status` (HumanActor's status): its time is when the person's pose was
sampled, so the person's speeds are measured between their own pose samples.

Input `robot_path_rate` (size 1, RobotMotion's `path_rate`): the fraction of full speed the
robot moves at along its path, which its stopping time depends on. Unconnected, a moving
robot is taken to move at full speed.

While the person is far (`Judge.next_period`: full speed stays safe even if the next
measurement came that much later and the person ran at the fastest speed of any rule), the
monitor measures less often than every `period`: every `far_period`, or every multiple of
`period` below it that is still safe; the updates in between only check whether the object
in the gripper changed (which measures at once).

A contact is quasi-static when the touched body region is pinned against the cell (the
bodies welded to the world) or another robot part; see `ProximityMeter.pinned`.

With safety sensors (`safety.sensors`), input `sensor_readings` (the SafetySensors'
readings) is what the speed scale follows: the nearest detection of the person and the
scanners' fields (`hrc_drake.safety.sensors_view`), each sensor's reading as it reports it,
its response time after the scene. The body's true distances are still measured: the
status's separation, S_p and violations are the real body's (S_p with the slowest sensor's
response time), so a person the sensors miss shows as a violation.
"""

import math
from dataclasses import dataclass

import numpy as np
from pydrake.common.value import AbstractValue
from pydrake.geometry import GeometryId, QueryObject
from pydrake.systems.framework import EventStatus, LeafSystem

from hrc_drake.motion.options import MotionOptions
from hrc_drake.ports import message_value, value_or_none
from hrc_drake.safety.config import SafetyConfig
from hrc_drake.safety.geometry import Part, body_parts, human_parts
from hrc_drake.safety.judge import Judge
from hrc_drake.safety.messages import CARRIED, SafetyStatus
from hrc_drake.safety.pfl import robot_effective_mass
from hrc_drake.safety.proximity import ProximityMeter
from hrc_drake.safety.sensors_view import SensorView, view
from hrc_drake.safety.ssm import SsmModel
from hrc_drake.safety.stopping import StopModel
from hrc_drake.wiring import ROBOT_MODEL, SAFETY_MONITOR, TOOL_MODEL
from hrc_drake.workpieces.messages import ROBOT_HOLDER

NOTHING_HELD = -1.0
"""The held object's id in the monitor's schedule when the gripper holds nothing."""


@dataclass(frozen=True)
class RobotModel:
    """The robot as the monitor sees it: its geometry parts and its masses (kg)."""

    parts: list[Part]
    moving_mass: float
    tool_mass: float
    carriable: tuple[GeometryId, ...] = ()
    """Geometries of objects the gripper may hold (the workpieces' slots)."""
    fixed: tuple[GeometryId, ...] = ()
    """Geometries of the cell that never move (bodies welded to the world)."""


class SafetyMonitor(LeafSystem):
    def __init__(
        self,
        inspector,
        human: list[Part],
        robot: RobotModel,
        config: SafetyConfig,
        variant: str,
        command_latency: float,
    ):
        """`command_latency`: how long a new speed scale takes to reach the robot (its
        update period)."""
        super().__init__()
        carried_parts = [Part(g, CARRIED) for g in robot.carriable]
        self._meter = ProximityMeter(
            inspector, human, robot.parts + carried_parts, robot.fixed, config.clamping_gap
        )
        self._active_parts = _active_parts(self._meter, robot.parts, carried_parts)
        self.part_names = tuple(dict.fromkeys(part.name for part in self._meter.robot))
        """What the `part` entry of `safety_signals` numbers."""
        stop = StopModel.of_variant(variant)
        sensors = config.sensors.all()
        self._judge = Judge(
            config,
            SsmModel.from_config(config.truth(), stop, command_latency),
            robot_effective_mass(robot.moving_mass, robot.tool_mass),
            sensed={
                name: SsmModel.from_config(config.seen_through(sensor), stop, command_latency)
                for name, sensor in sensors.items()
            },
        )
        self._query = self.DeclareAbstractInputPort(
            "query_object", AbstractValue.Make(QueryObject())
        )
        self._workpieces = self.DeclareAbstractInputPort("workpieces_status", message_value())
        self._human = self.DeclareAbstractInputPort("human_status", message_value())
        self._path_rate = self.DeclareVectorInputPort("robot_path_rate", 1)
        self._readings = self.DeclareAbstractInputPort("sensor_readings", message_value())
        self._scale = self.DeclareDiscreteState(np.zeros(1))  # no motion before a measurement
        # with sensors, none has reported yet
        initial = SafetyStatus(sensing=tuple(map(SensorView, sensors)) if sensors else None)
        self._signals = self.DeclareDiscreteState(initial.signals((np.nan, np.nan), -1))
        self._status = self.DeclareAbstractState(AbstractValue.Make(initial))
        self._memory = self.DeclareDiscreteState(np.full(self._meter.memory_size, np.nan))
        self._due = self.DeclareDiscreteState(np.array([0.0, NOTHING_HELD]))
        """When the next measurement is due, and the id of the object held at the last."""
        self._period = config.period
        self.DeclareStateOutputPort("speed_scale", self._scale)
        self.DeclareStateOutputPort("safety_signals", self._signals)
        self.DeclareStateOutputPort("safety_status", self._status)
        self.DeclarePeriodicUnrestrictedUpdateEvent(config.period, 0.0, self._update)

    def get_query_object_input_port(self):
        return self._query

    def get_workpieces_status_input_port(self):
        return self._workpieces

    def get_human_status_input_port(self):
        return self._human

    def _update(self, context, state) -> EventStatus:
        held = self._held_object(context)
        time = context.get_time()
        held_id = held.id if held is not None else NOTHING_HELD
        due, held_before = context.get_discrete_state(self._due).value()
        if time < due - self._period / 2 and held_id == held_before:
            return EventStatus.DidNothing()
        before: SafetyStatus = context.get_abstract_state(self._status).get_value()
        geometry = held.geometry_id if held is not None else None
        reading = self._meter.measure(
            self._query.Eval(context),
            self._last_memory(context),
            time,
            self._active_parts.get(geometry, self._active_parts[None]),
            self._person_time(context),
        )
        payload = held.mass if held is not None else 0.0
        path_rate = self._robot_path_rate(context, reading.robot_speed)
        sensing = self._sensing(context, time, reading.robot, path_rate)
        status = self._judge.status(time, reading, before, payload, path_rate, sensing)
        part = self.part_names.index(status.link) if status.link else -1
        state.get_mutable_abstract_state(self._status).set_value(status)
        state.get_mutable_discrete_state(self._memory).set_value(reading.memory)
        state.get_mutable_discrete_state(self._scale).set_value([status.scale])
        signals = status.signals(reading.person_xy, part)
        state.get_mutable_discrete_state(self._signals).set_value(signals)
        due = time + self._judge.next_period(status)
        state.get_mutable_discrete_state(self._due).set_value([due, held_id])
        return EventStatus.Succeeded()

    def _sensing(self, context, time: float, robot_capsules, path_rate: float):
        """The sensors' views of the person (None without sensors); nothing read from an
        unconnected `sensor_readings` (no sensor has reported)."""
        sensors = self._judge.config.sensors
        if not sensors.present:
            return None
        readings = value_or_none(self._readings, context) or {}
        return view(sensors, readings, time, robot_capsules, path_rate)

    def _robot_path_rate(self, context, robot_speed: float) -> float:
        if self._path_rate.HasValue(context):
            return float(self._path_rate.Eval(context)[0])
        return 1.0 if robot_speed > self._judge.config.moving_speed else 0.0

    def _last_memory(self, context) -> np.ndarray | None:
        """The meter's memory of the last update (None before the first): a vector state, as
        Drake copies it in C++ where an abstract one costs a Python deepcopy per update."""
        memory = context.get_discrete_state(self._memory).value()
        return None if math.isnan(memory[0]) else memory

    def _person_time(self, context) -> float | None:
        """When the person's current pose was sampled (None: no HumanActor tells)."""
        status = value_or_none(self._human, context)
        return status.time if status is not None else None

    def _held_object(self, context):
        """The workpiece the robot's gripper holds (an ObjectStatus), if any."""
        status = value_or_none(self._workpieces, context)
        return status.held_by(ROBOT_HOLDER) if status is not None else None


def _active_parts(meter: ProximityMeter, robot: list[Part], carried: list[Part]) -> dict:
    """The watched robot parts for each held object's geometry (None: nothing held): the
    arm and tool always, a carried object while it is held."""
    always = np.arange(len(robot))
    held = {None: meter.active(always)}
    for k, part in enumerate(carried, start=len(robot)):
        held[part.geometry] = meter.active(np.append(always, k))
    return held


def robot_model(plant, arm, tool=None, carriable=()) -> RobotModel:
    """The arm (and tool) of `plant`: geometry parts and moving mass (bodies not welded to
    the world)."""
    welded = plant.GetBodiesWeldedTo(plant.world_body())
    fixed = {body.index() for body in welded}
    moving = [plant.get_body(b) for b in plant.GetBodyIndices(arm) if b not in fixed]
    tools = [plant.get_body(b) for b in plant.GetBodyIndices(tool)] if tool is not None else []
    parts = body_parts(plant, [arm] + ([tool] if tool is not None else []))
    robot_geometries = {part.geometry for part in parts}
    cell = [
        geometry
        for body in welded
        for geometry in plant.GetCollisionGeometriesForBody(body)
        if geometry not in robot_geometries
    ]
    return RobotModel(
        parts=parts,
        moving_mass=sum(body.default_mass() for body in moving),
        tool_mass=sum(body.default_mass() for body in tools),
        carriable=tuple(carriable),
        fixed=tuple(cell),
    )


def add_safety_monitor(
    builder,
    scene_graph,
    plant,
    human_plant,
    human_instance,
    config: SafetyConfig,
    variant: str,
    carriable: tuple = (),
    command_latency: float = MotionOptions.period,
) -> SafetyMonitor:
    """Adds the monitor named `safety` and connects its QueryObject input.

    `plant` holds the robot as model instances ROBOT_MODEL and TOOL_MODEL (if present); the person's
    geometry belongs to `human_instance` of `human_plant`; `carriable` are the geometries of
    objects the gripper may hold. The caller connects `speed_scale` to RobotMotion and, when
    objects can be carried, the workpieces' status to `workpieces_status`, and RobotMotion's
    `path_rate` to `robot_path_rate` (`command_latency`: its update period).
    """
    arm = plant.GetModelInstanceByName(ROBOT_MODEL)
    tool = (
        plant.GetModelInstanceByName(TOOL_MODEL)
        if plant.HasModelInstanceNamed(TOOL_MODEL)
        else None
    )
    inspector = scene_graph.model_inspector()
    monitor = builder.AddNamedSystem(
        SAFETY_MONITOR,
        SafetyMonitor(
            inspector,
            human_parts(human_plant, inspector, human_instance),
            robot_model(plant, arm, tool, carriable),
            config,
            variant,
            command_latency,
        ),
    )
    builder.Connect(scene_graph.get_query_output_port(), monitor.get_query_object_input_port())
    return monitor
