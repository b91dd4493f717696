"""The person's body as the realism audit sees it (systems/realism_audit.py): their
collision regions with the bounding segments that find the objects near them, and their
sole points, posed from their joint positions in a plant context of the audit's own."""

import numpy as np
from pydrake.geometry import FramePoseVector

from hrc_drake.human.skeleton import SIDES
from hrc_drake.safety.geometry import bounding_segment, human_parts


class AuditedBody:
    """The person's collision regions and sole points, posed from their joint positions in a
    plant context of the audit's own."""

    def __init__(self, plant, inspector, instance):
        self._plant = plant
        self._inspector = inspector
        self.num_positions = plant.num_positions()
        self._context = None
        parts = human_parts(plant, inspector, instance)
        self.regions = {part.geometry: part.name for part in parts}
        self.geometries = [part.geometry for part in parts]
        bounds = [bounding_segment(inspector.GetShape(g)) for g in self.geometries]
        self.radii = np.array([radius for _, _, radius in bounds])
        self._bodies = sorted({self._body_of(g) for g in self.geometries})
        """The person's bodies that carry collision geometry, by index."""
        self._rows = [self._bodies.index(self._body_of(g)) for g in self.geometries]
        self._ends = np.array(
            [
                self._in_body(g, np.column_stack(b[:2]))
                for g, b in zip(self.geometries, bounds, strict=True)
            ]
        )
        """Each region's bounding segment's ends in its body's frame, as the columns of a
        3 × 2 matrix."""
        self._soles = {}
        for side in SIDES:
            foot = plant.GetBodyByName(f"{side}_foot", instance)
            (geometry,) = plant.GetCollisionGeometriesForBody(foot)
            length, _, height = inspector.GetShape(geometry).size()
            heel_and_toe = [[-length / 2, length / 2], [0.0, 0.0], [-height / 2, -height / 2]]
            row = self._bodies.index(foot.index())
            self._soles[side] = (row, self._in_body(geometry, np.array(heel_and_toe)))

    @property
    def source_id(self):
        return self._plant.get_source_id()

    def _body_of(self, geometry):
        return self._plant.GetBodyFromFrameId(self._inspector.GetFrameId(geometry)).index()

    def _in_body(self, geometry, points: np.ndarray) -> np.ndarray:
        """Points (3 × k) of the geometry's frame in its body's."""
        return _transformed(self._inspector.GetPoseInFrame(geometry), points)

    def posed(self, positions: np.ndarray) -> tuple[FramePoseVector, np.ndarray]:
        """The person's geometry poses for the scene and their bodies' world poses
        (n × 3 × 4) at these joint positions."""
        if self._context is None:
            self._context = self._plant.CreateDefaultContext()
        self._plant.SetPositions(self._context, positions)
        geometry = self._plant.get_geometry_pose_output_port().Eval(self._context)
        poses = self._plant.get_body_poses_output_port().Eval(self._context)
        return geometry, np.array([poses[b].GetAsMatrix34() for b in self._bodies])

    def segment_ends(self, bodies: np.ndarray) -> np.ndarray:
        """Each region's bounding segment's ends in the world (n × 2 × 3)."""
        posed = bodies[self._rows]
        return np.einsum("nij,njk->nki", posed[:, :, :3], self._ends) + posed[:, None, :, 3]

    def sole_points(self, bodies: np.ndarray) -> dict[str, np.ndarray]:
        points = {}
        for side, (row, heel_and_toe) in self._soles.items():
            heel, toe = (bodies[row, :, :3] @ heel_and_toe + bodies[row, :, 3:]).T
            points[f"{side}_heel"] = heel
            points[f"{side}_toe"] = toe
        return points


def _transformed(X, points: np.ndarray) -> np.ndarray:
    """X @ points (3 × k) in numpy: RigidTransform's own @ passes through pydrake's Python
    shape-matching wrapper, a fifth of the audit's time."""
    m = X.GetAsMatrix34()
    return m[:, :3] @ points + m[:, 3:]
