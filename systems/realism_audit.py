"""RealismAudit: samples the person in the world scene and keeps the realism audit.

Inputs: `query_object` (the world SceneGraph), `human_status` (HumanStatus) and
`workpieces_status` (optional). Output `realism` (hrc_drake.evaluation.realism.AuditState),
from state only. A periodic unrestricted update at the person's rate takes one sample:
penetrations come from SceneGraph (the person against the cell's static geometry through
the broad phase; against objects, which are filtered out of contact queries, through pair
queries after a bounding-capsule test), sole points from the feet's collision boxes. Its
period is a multiple of the person's (`human.audit_every`), so every sample is one of the
person's poses.
"""

import math

import numpy as np
from pydrake.common.value import AbstractValue
from pydrake.geometry import QueryObject
from pydrake.multibody.tree import BodyIndex
from pydrake.systems.framework import LeafSystem

from hrc_drake.evaluation.realism import AuditState, Sample, audited
from hrc_drake.human.skeleton import SIDES
from hrc_drake.ports import message_value, value_or_none
from hrc_drake.safety.geometry import bounding_segment, human_parts
from hrc_drake.wiring import REALISM_AUDIT
from hrc_drake.workpieces.geometry import Solid, moved
from hrc_drake.workpieces.messages import BOTH_HANDS, LEFT_HAND, PERSON_HOLDERS, RIGHT_HAND

HOLDING_HANDS = {LEFT_HAND: ("left",), RIGHT_HAND: ("right",), BOTH_HANDS: SIDES}


class RealismAudit(LeafSystem):
    """Keeps the worst penetration, hand gap, tilt, foot slip and stride speed swing."""

    def __init__(
        self,
        inspector,
        human_plant,
        human_instance,
        static_geometry: dict,
        solids: dict[str, Solid],
        period: float,
        stride_time: float,
    ):
        super().__init__()
        self.period = period
        parts = human_parts(human_plant, inspector, human_instance)
        self._regions = {part.geometry: part.name for part in parts}
        self._static = dict(static_geometry)
        self._solids = dict(solids)
        self._stride_time = stride_time
        self._bounds = {
            part.geometry: bounding_segment(inspector.GetShape(part.geometry)) for part in parts
        }
        self._ends = {
            g: np.column_stack([start, end]) for g, (start, end, _) in self._bounds.items()
        }
        """Each region's bounding segment's ends as the columns of a 3 × 2 matrix."""
        self._radii = np.array([radius for _, _, radius in self._bounds.values()])
        self._object_radii = {name: _bounding_radius(solid) for name, solid in self._solids.items()}
        self._soles = {}
        for side in SIDES:
            foot = human_plant.GetBodyByName(f"{side}_foot", human_instance)
            (geometry,) = human_plant.GetCollisionGeometriesForBody(foot)
            length, _, height = inspector.GetShape(geometry).size()
            heel_and_toe = [[-length / 2, length / 2], [0.0, 0.0], [-height / 2, -height / 2]]
            self._soles[side] = (geometry, np.array(heel_and_toe))
        self._query = self.DeclareAbstractInputPort(
            "query_object", AbstractValue.Make(QueryObject())
        )
        self._human = self.DeclareAbstractInputPort("human_status", message_value())
        self._objects = self.DeclareAbstractInputPort("workpieces_status", message_value())
        self._state = self.DeclareAbstractState(AbstractValue.Make(AuditState()))
        self.DeclarePeriodicUnrestrictedUpdateEvent(period, 0.0, self._update)
        self.DeclareStateOutputPort("realism", self._state)

    def _update(self, context, state) -> None:
        status = value_or_none(self._human, context)
        if status is None or not status.left_hand:
            return
        query = self._query.Eval(context)
        objects = value_or_none(self._objects, context)
        objects = objects.objects if objects is not None else ()
        held = [o for o in objects if o.holder in PERSON_HOLDERS]
        sample = Sample(
            time=context.get_time(),
            static_depths=self._static_depths(query),
            object_depths=self._object_depths(
                query, [o for o in objects if o.holder not in PERSON_HOLDERS]
            ),
            hand_gaps=tuple(
                gap for o in held for gap in self._hand_gaps(o, status, context.get_time())
            ),
            tilts=tuple((_tilt(o.pose), f"{o.type} {o.id}") for o in held),
            sole_points=self._sole_points(query),
            pelvis=(status.time, *status.base_pose[:2]),
            walking=status.state == "MOVEMENT",
        )
        audit = context.get_abstract_state(self._state).get_value()
        state.get_mutable_abstract_state(self._state).set_value(
            audited(audit, sample, self._stride_time)
        )

    def _static_depths(self, query) -> tuple:
        depths = []
        for pair in query.ComputePointPairPenetration():
            for own, other in ((pair.id_A, pair.id_B), (pair.id_B, pair.id_A)):
                if own in self._regions and other in self._static:
                    depths.append((pair.depth, f"{self._regions[own]} in {self._static[other]}"))
        return tuple(depths)

    def _object_depths(self, query, objects) -> tuple:
        """Exact distances only for the pairs whose bounding shapes overlap."""
        near = [o for o in objects if o.geometry_id is not None]
        if not near:
            return ()
        geometries = list(self._bounds)
        ends = np.array([_transformed(query.GetPoseInWorld(g), self._ends[g]) for g in geometries])
        ends = ends.transpose(0, 2, 1)  # (geometry, start or end, xyz)
        centers = np.array([o.pose.translation() for o in near])
        reach = self._radii[:, None] + np.array([self._object_radii[o.type] for o in near])
        close = _point_segment_distances(centers, ends[:, 0], ends[:, 1]) <= reach
        depths = []
        for i, k in zip(*np.nonzero(close), strict=True):
            obj = near[k]
            distance = query.ComputeSignedDistancePairClosestPoints(
                geometries[i], obj.geometry_id
            ).distance
            if distance < 0:
                where = f"{self._regions[geometries[i]]} in {obj.type} {obj.id}"
                depths.append((-distance, where))
        return tuple(depths)

    def _hand_gaps(self, obj, status, now: float) -> list:
        """Each holding hand's distance to the object's surface, both at the time of the
        person's pose (the object's pose moved back to it along its velocity)."""
        solid = self._solids[obj.type]
        X_OW = moved(obj.pose, obj.velocity, status.time - now).inverse()
        hands = {"left": status.left_hand, "right": status.right_hand}
        return [
            (
                abs(solid.signed_distance_to(X_OW @ np.array(hands[side][:3]))),
                f"{obj.type} {obj.id}",
            )
            for side in HOLDING_HANDS[obj.holder]
        ]

    def _sole_points(self, query) -> dict[str, np.ndarray]:
        points = {}
        for side, (geometry, heel_and_toe) in self._soles.items():
            heel, toe = _transformed(query.GetPoseInWorld(geometry), heel_and_toe).T
            points[f"{side}_heel"] = heel
            points[f"{side}_toe"] = toe
        return points


def _transformed(X, points: np.ndarray) -> np.ndarray:
    """X @ points (3 × k) in numpy: RigidTransform's own @ passes through pydrake's Python
    shape-matching wrapper, a fifth of the audit's time."""
    m = X.GetAsMatrix34()
    return m[:, :3] @ points + m[:, 3:]


def _tilt(X_WO) -> float:
    return math.acos(min(max(float(X_WO.rotation().matrix()[2, 2]), -1.0), 1.0))


def _bounding_radius(solid: Solid) -> float:
    return (
        float(np.linalg.norm(solid.size)) / 2 if solid.shape == "box" else math.hypot(*solid.size)
    )


def _point_segment_distances(points, starts, ends) -> np.ndarray:
    """Distance from every point (k, 3) to every segment (n, 3 each): an (n, k) array."""
    along = ends - starts
    offsets = points[None, :, :] - starts[:, None, :]
    lengths = np.maximum(np.einsum("nj,nj->n", along, along), 1e-12)
    s = np.clip(np.einsum("nkj,nj->nk", offsets, along) / lengths[:, None], 0.0, 1.0)
    return np.linalg.norm(offsets - s[:, :, None] * along[:, None, :], axis=2)


def static_geometry(plant, inspector) -> dict:
    """Every collision geometry of the plant's anchored bodies, named after its model."""
    found = {}
    for body_index in range(plant.num_bodies()):
        body = plant.get_body(BodyIndex(body_index))
        if plant.IsAnchored(body):
            for geometry in plant.GetCollisionGeometriesForBody(body):
                found[geometry] = plant.GetModelInstanceName(body.model_instance())
    return found


def add_realism_audit(
    builder,
    scene_graph,
    mirror,
    human_plant,
    human_instance,
    human,
    workpieces,
    solids,
    period,
    stride_time,
) -> RealismAudit:
    """Adds the audit named `realism_audit`, wired to the world scene, the person and the
    workpieces (when there are any)."""
    inspector = scene_graph.model_inspector()
    audit = builder.AddNamedSystem(
        REALISM_AUDIT,
        RealismAudit(
            inspector,
            human_plant,
            human_instance,
            static_geometry(mirror, inspector),
            solids,
            period,
            stride_time,
        ),
    )
    builder.Connect(scene_graph.get_query_output_port(), audit.GetInputPort("query_object"))
    builder.Connect(human.GetOutputPort("human_status"), audit.GetInputPort("human_status"))
    if workpieces is not None:
        builder.Connect(
            workpieces.GetOutputPort("workpieces_status"), audit.GetInputPort("workpieces_status")
        )
    return audit
