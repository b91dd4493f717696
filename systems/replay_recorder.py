"""ReplayRecorder: what replay.html animates, sampled at the visualizer's rate.

Drake's MeshcatVisualizer records every frame of the scene at every publish, hidden workpiece
slots and the static cell included, as JSON-like keys of doubles. The recorder keeps the same
samples as arrays instead (`hrc_drake.evaluation.recording.Recording`), so that
`hrc_drake.evaluation.replay` can keep only the keys that change what is seen. Besides the
frames' world poses it samples, when the station has them, the robot's safety state (from the
monitor's speed scale), the safety sensors' fields and detections (from the monitor's view
of them) and who holds which workpiece (from the workpieces' status), so the replay can show
them and tests can find them.

Frames are named as MeshcatVisualizer names them: `/drake/<prefix>/<frame name>` with `::`
turned into `/`, for every frame with geometry of the visualizer's role.
"""

import numpy as np
from pydrake.common.value import AbstractValue
from pydrake.geometry import QueryObject, Role
from pydrake.systems.framework import LeafSystem

from hrc_drake.evaluation.recording import (
    Recording,
    detections,
    meshcat_path,
    safety_state,
    sensor_samples,
)
from hrc_drake.ports import message_value, value_or_none
from hrc_drake.workpieces.messages import WorkpiecesStatus


class ReplayRecorder(LeafSystem):
    """Inputs: `query_object` (the world scene), and optionally `safety_status` and
    `workpieces_status` (an unconnected one is not sampled). `prefixes` maps each Meshcat
    prefix a visualizer draws under to its geometry role."""

    def __init__(self, period: float, prefixes: dict[str, Role]):
        super().__init__()
        self._prefixes = dict(prefixes)
        self._frames = None
        self.recording = Recording()
        self._query = self.DeclareAbstractInputPort(
            "query_object", AbstractValue.Make(QueryObject())
        )
        self._safety = self.DeclareAbstractInputPort("safety_status", message_value())
        self._workpieces = self.DeclareAbstractInputPort("workpieces_status", message_value())
        self.DeclarePeriodicPublishEvent(period, 0.0, self._sample)

    def _frame_paths(self, inspector) -> list[tuple[object, str]]:
        """(frame id, Meshcat path) of every frame a visualizer draws, per prefix."""
        return [
            (frame, meshcat_path(prefix, inspector.GetName(frame)))
            for prefix, role in self._prefixes.items()
            for frame in inspector.GetAllFrameIds()
            if frame != inspector.world_frame_id()
            and inspector.NumGeometriesForFrameWithRole(frame, role) > 0
        ]

    def _sample(self, context) -> None:
        query = self._query.Eval(context)
        if self._frames is None:
            self._frames = self._frame_paths(query.inspector())
        recording = self.recording
        recording.times.append(context.get_time())
        for frame, path in self._frames:
            pose = query.GetPoseInWorld(frame)
            row = np.concatenate([pose.translation(), pose.rotation().ToQuaternion().wxyz()])
            recording.poses.setdefault(path, []).append(row)
        safety = value_or_none(self._safety, context)
        if safety is not None:
            recording.safety.append(safety_state(safety))
        if safety is not None and safety.sensing is not None:
            recording.sensors.append(sensor_samples(safety.sensing))
            recording.detections.append(detections(safety.sensing))
        workpieces = value_or_none(self._workpieces, context)
        if workpieces is not None:
            recording.held.append(self._held(query.inspector(), workpieces))

    def _held(self, inspector, status: WorkpiecesStatus) -> dict[str, str]:
        """{Meshcat path of the held object (first prefix): holder}."""
        prefix = next(iter(self._prefixes))
        return {
            meshcat_path(prefix, inspector.GetName(inspector.GetFrameId(o.geometry_id))): o.holder
            for o in status.objects
            if o.holder is not None and o.geometry_id is not None
        }
