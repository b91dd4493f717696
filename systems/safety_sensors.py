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
from hrc_drake.safety.sensors_reading import contour, kept, take_reading
from hrc_drake.seeding import stream
from hrc_drake.wiring import SAFETY_SENSORS


class SafetySensors(LeafSystem):
    def __init__(self, inspector, config: SensorsConfig, person, fixed, seed: int):
        """`person`: the person's geometries (what the sensors report); `fixed`: geometries
        that never move (where each sensor's beams end on them is computed once); `seed`:
        the run's."""
        super().__init__()
        self._sensors = config.all()
        geometries = list(inspector.GetAllGeometryIds(Role.kProximity))
        still = {inspector.GetFrameId(g) for g in fixed}
        moving = [g for g in geometries if inspector.GetFrameId(g) not in still]
        self._still = [g for g in geometries if g not in moving]
        self._still_shapes = solids([inspector.GetShape(g) for g in self._still])
        self._shapes = solids([inspector.GetShape(g) for g in moving])
        self._person = np.array([g in set(person) for g in moving])
        frames = [inspector.GetFrameId(g) for g in moving]
        self._frames = list(dict.fromkeys(frames))
        self._frame_of = np.array([self._frames.index(f) for f in frames], dtype=int)
        self._X_FG = np.array([inspector.GetPoseInFrame(g).GetAsMatrix4() for g in moving])
        self._X_FG = self._X_FG.reshape(-1, 4, 4)
        self._contours: dict[str, np.ndarray] = {}
        """per sensor, where its beams end on the cell (computed at its first scan)"""
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
        query = self._query.Eval(context)
        reading = take_reading(
            sensor,
            time,
            self._shapes,
            self._poses(query),
            self._person,
            noise,
            scan,
            self._contour(name, query),
        )
        history = state.get_mutable_abstract_state(self._histories[name])
        history.set_value(kept(history.get_value(), reading, sensor.latency))
        return EventStatus.Succeeded()

    def _contour(self, name: str, query) -> np.ndarray:
        """Where the sensor's beams end on the cell, which never moves: computed once."""
        if name not in self._contours:
            poses = np.array([query.GetPoseInWorld(g).GetAsMatrix34() for g in self._still])
            poses = poses.reshape(-1, 3, 4)
            self._contours[name] = contour(self._sensors[name], self._still_shapes, poses)
        return self._contours[name]

    def _poses(self, query) -> np.ndarray:
        """World poses (shapes × 3 × 4) of the geometries that move, from their frames'."""
        frame_poses = np.array([query.GetPoseInWorld(f).GetAsMatrix4() for f in self._frames])
        return (frame_poses.reshape(-1, 4, 4)[self._frame_of] @ self._X_FG)[:, :3, :]


def add_safety_sensors(builder, scene_graph, config: SensorsConfig, person, fixed, seed: int):
    """Adds the sensors named `safety_sensors`, reading the world scene."""
    sensors = builder.AddNamedSystem(
        SAFETY_SENSORS,
        SafetySensors(scene_graph.model_inspector(), config, person, fixed, seed),
    )
    builder.Connect(scene_graph.get_query_output_port(), sensors.get_query_object_input_port())
    return sensors
