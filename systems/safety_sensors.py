"""SafetySensors: the cell's laser scanners and light curtains, each taking a reading of the
world scene every scan (hrc_drake.safety.sensors_reading): its beams cast against the
person's body, the cell's furniture, the robot and the objects (hrc_drake.safety.
sensors_raycast), with noise from the run's seed.

Output `sensor_readings` ({sensor name: its recent readings, oldest first}) holds every
reading the monitor may still be told of: a sensor reports a reading its latency (response
time less one scan) after taking it, and the monitor picks the one due
(`sensors_reading.reported`). Computed from state only.
"""

from functools import partial

import numpy as np
from pydrake.common.value import AbstractValue
from pydrake.geometry import QueryObject, Role
from pydrake.systems.framework import EventStatus, LeafSystem

from hrc_drake.ports import message_value
from hrc_drake.safety.sensors import SensorsConfig
from hrc_drake.safety.sensors_raycast import solids
from hrc_drake.safety.sensors_reading import kept, take_reading
from hrc_drake.seeding import stream
from hrc_drake.wiring import SAFETY_SENSORS


class SafetySensors(LeafSystem):
    def __init__(self, inspector, config: SensorsConfig, person, fixed, seed: int):
        """`person`: the person's geometries (what the sensors report); `fixed`: geometries
        that never move (their poses are looked up once); `seed`: the run's."""
        super().__init__()
        self._sensors = config.all()
        geometries = list(inspector.GetAllGeometryIds(Role.kProximity))
        self._solids = solids([inspector.GetShape(g) for g in geometries])
        self._person = np.array([g in set(person) for g in geometries])
        frames = [inspector.GetFrameId(g) for g in geometries]
        self._frames = list(dict.fromkeys(frames))
        self._frame_of = np.array([self._frames.index(f) for f in frames])
        self._X_FG = np.array([inspector.GetPoseInFrame(g).GetAsMatrix4() for g in geometries])
        still = {f for g, f in zip(geometries, frames, strict=True) if g in set(fixed)}
        self._moving = [k for k, f in enumerate(self._frames) if f not in still]
        self._frame_poses: np.ndarray | None = None
        self._query = self.DeclareAbstractInputPort(
            "query_object", AbstractValue.Make(QueryObject())
        )
        self._histories = {
            name: self.DeclareAbstractState(AbstractValue.Make(())) for name in self._sensors
        }
        self.DeclareAbstractOutputPort(
            "sensor_readings",
            message_value,
            self._output,
            prerequisites_of_calc={self.all_state_ticket()},
        )
        for name, sensor in self._sensors.items():
            noise = stream(seed, f"{SAFETY_SENSORS}/{name}")
            update = partial(self._scan, name, noise)
            self.DeclarePeriodicUnrestrictedUpdateEvent(sensor.scan_time, 0.0, update)

    def get_query_object_input_port(self):
        return self._query

    def _output(self, context, output) -> None:
        output.set_value(
            {name: context.get_abstract_state(k).get_value() for name, k in self._histories.items()}
        )

    def _scan(self, name: str, noise, context, state) -> EventStatus:
        sensor = self._sensors[name]
        time = context.get_time()
        scan = round(time / sensor.scan_time)
        reading = take_reading(
            sensor, time, self._solids, self._poses(context), self._person, noise, scan
        )
        history = state.get_mutable_abstract_state(self._histories[name])
        history.set_value(kept(history.get_value(), reading, sensor.latency))
        return EventStatus.Succeeded()

    def _poses(self, context) -> np.ndarray:
        """World poses (geometries × 3 × 4) of every geometry, from their frames' (those of
        the fixed geometries looked up once)."""
        query = self._query.Eval(context)
        if self._frame_poses is None:
            self._frame_poses = np.array(
                [query.GetPoseInWorld(f).GetAsMatrix4() for f in self._frames]
            )
        frame_poses = self._frame_poses.copy()
        for k in self._moving:
            frame_poses[k] = query.GetPoseInWorld(self._frames[k]).GetAsMatrix4()
        return (frame_poses[self._frame_of] @ self._X_FG)[:, :3, :]


def add_safety_sensors(builder, scene_graph, config: SensorsConfig, person, fixed, seed: int):
    """Adds the sensors named `safety_sensors`, reading the world scene."""
    sensors = builder.AddNamedSystem(
        SAFETY_SENSORS,
        SafetySensors(scene_graph.model_inspector(), config, person, fixed, seed),
    )
    builder.Connect(scene_graph.get_query_output_port(), sensors.get_query_object_input_port())
    return sensors
