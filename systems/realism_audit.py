"""RealismAudit: records the person and the objects during the run; its `realism` output
is the realism audit of what it recorded, worked out when it is read (after the run). In a
cell with objects and no person it records the objects alone, and audits what the robot
holds (a part it sets into another went unmeasured in a robot-only cell, #26).

Inputs: `human_status` (HumanStatus) and `human_positions` (the person's plant's joint
positions), in a cell with a person, and `workpieces_status` (optional). Output `realism`
(hrc_drake.evaluation.realism.AuditState), from state only. A periodic unrestricted update
keeps one sample (references to the immutable statuses and a copy of the joint positions);
its period is a multiple of the person's (`human.audit_every`), so every sample is one of
the person's poses, as the world scene holds it at that instant.

Reading `realism` poses each sample in a scene of its own (the world SceneGraph's geometry
in a context of the audit's, `AuditScene`): penetrations come from SceneGraph (the person
against the cell's static geometry through the broad phase; against objects, which are
filtered out of contact queries, through pair queries after a bounding-capsule test), sole
points from the feet's collision boxes. Nothing of this runs inside the simulation's
steps, and a person standing still is posed once.
"""

import math
from dataclasses import dataclass

import numpy as np
from pydrake.common.value import AbstractValue
from pydrake.geometry import CollisionFilterDeclaration, FramePoseVector, GeometrySet
from pydrake.systems.framework import EventStatus, LeafSystem

from hrc_drake.evaluation.audited_body import AuditedBody
from hrc_drake.evaluation.realism import AuditState, Sample, audited
from hrc_drake.human.skeleton import SIDES
from hrc_drake.ports import message_value, value_or_none
from hrc_drake.scene_geometry import static_geometry
from hrc_drake.wiring import HUMAN_MODEL, REALISM_AUDIT
from hrc_drake.workpieces.geometry import Solid, moved
from hrc_drake.workpieces.messages import BOTH_HANDS, LEFT_HAND, PERSON_HOLDERS, RIGHT_HAND

HOLDING_HANDS = {LEFT_HAND: ("left",), RIGHT_HAND: ("right",), BOTH_HANDS: SIDES}


@dataclass(frozen=True, eq=False)
class PersonPose:
    """The person at a sampled instant."""

    pose_time: float
    """When the person took the pose (their last update)."""
    pelvis: tuple[float, float]
    walking: bool
    hands: dict[str, tuple[float, ...]]
    """Each hand's grasp point (x, y, z, then its orientation) by side."""
    positions: np.ndarray
    """The person's plant's joint positions, which the world scene poses the person from."""


@dataclass(frozen=True, eq=False)
class Recorded:
    """One sampled instant of the person and the objects, linked to the one before: the
    record grows by one value per sample and is never copied (immutable, so Drake's state
    copies share it)."""

    earlier: "Recorded | None"
    time: float
    objects: tuple
    """The objects' statuses (hrc_drake.workpieces.messages.ObjectStatus)."""
    person: PersonPose | None
    """None in a cell without a person."""

    def __deepcopy__(self, memo):
        return self

    def since(self, start: "Recorded | None") -> list["Recorded"]:
        """The samples after `start` (one of this record's, or None: all), oldest first."""
        samples, node = [], self
        while node is not start:
            samples.append(node)
            node = node.earlier
        return samples[::-1]

    def holds(self, sample: "Recorded") -> bool:
        """Whether `sample` is this record's last or an earlier one."""
        node = self
        while node is not None and node is not sample:
            node = node.earlier
        return node is not None


class RealismAudit(LeafSystem):
    """Records the person and the objects at the audit's rate (see the module docstring)."""

    def __init__(self, scene: "AuditScene", period: float, stride_time: float | None):
        super().__init__()
        self.period = period
        self.scene = scene
        self._stride_time = stride_time
        self._blank = AuditState(person=scene.body is not None)
        self._last_audit: tuple[Recorded | None, AuditState] = (None, self._blank)
        if scene.body is not None:
            self._human = self.DeclareAbstractInputPort("human_status", message_value())
            self._positions = self.DeclareVectorInputPort(
                "human_positions", scene.body.num_positions
            )
        self._objects = self.DeclareAbstractInputPort("workpieces_status", message_value())
        self._record = self.DeclareAbstractState(message_value())
        self.DeclarePeriodicUnrestrictedUpdateEvent(period, 0.0, self._sample)
        self.DeclareAbstractOutputPort(
            "realism",
            lambda: AbstractValue.Make(AuditState()),
            self._calc_realism,
            prerequisites_of_calc={self.abstract_state_ticket(self._record)},
        )

    def _sample(self, context, state) -> EventStatus:
        objects = value_or_none(self._objects, context)
        person = self._person(context) if self.scene.body is not None else None
        if self._nothing_yet(person, objects):
            return EventStatus.DidNothing()
        record = Recorded(
            earlier=self._recorded(context),
            time=context.get_time(),
            objects=objects.objects if objects is not None else (),
            person=person,
        )
        state.get_mutable_abstract_state(self._record).set_value(record)
        return EventStatus.Succeeded()

    def _nothing_yet(self, person: PersonPose | None, objects) -> bool:
        """Before the person's first pose (in a cell with one) or the objects' first status
        (in a cell without)."""
        if self.scene.body is not None:
            return person is None
        return objects is None

    def _person(self, context) -> PersonPose | None:
        """The person's pose (None before their first: nothing to record yet)."""
        status = value_or_none(self._human, context)
        if status is None or not status.left_hand:
            return None
        return PersonPose(
            pose_time=status.time,
            pelvis=tuple(status.base_pose[:2]),
            walking=status.state == "MOVEMENT",
            hands={"left": status.left_hand, "right": status.right_hand},
            positions=self._positions.Eval(context).copy(),
        )

    def _recorded(self, context) -> "Recorded | None":
        """The record so far (None before the first sample: the state starts as the message
        model's placeholder, as `AbstractValue.Make(None)` does not construct in newer Drake)."""
        value = context.get_abstract_state(self._record).get_value()
        return value if isinstance(value, Recorded) else None

    def _calc_realism(self, context, output) -> None:
        """The audit of the record: the last audit read carried on over the samples since,
        when this record goes on from it (a run read as it goes is audited once)."""
        record = self._recorded(context)
        last, audit = self._last_audit
        if record is None or last is None or not record.holds(last):
            last, audit = None, self._blank
        for recorded in record.since(last) if record is not None else ():
            audit = audited(audit, self.scene.sample(recorded), self._stride_time)
        self._last_audit = (record, audit)
        output.set_value(audit)


class AuditScene:
    """The world scene's geometry in a context of the audit's own, posed as at a recorded
    sample: the cell's static geometry as it stands, the person (`body`, None without one)
    from their joint positions, the objects from their statuses."""

    def __init__(self, scene_graph, mirror, body: AuditedBody | None, workpieces, solids):
        inspector = scene_graph.model_inspector()
        self._scene_graph = scene_graph
        self._inspector = inspector
        self._mirror = mirror
        self.body = body
        self._workpieces = workpieces
        self._scene = None
        self._static = static_geometry(mirror, inspector)
        self._solids = dict(solids)
        self._object_radii = {name: _bounding_radius(solid) for name, solid in self._solids.items()}
        self._last = (None, None, None)
        """(joint positions, objects, what the scene showed) of the last sample posed."""
        self._objects_posed = None

    def sample(self, recorded: Recorded) -> Sample:
        """What the audit sees of the recorded instant (without a person, only what the
        robot holds in the cell or another object)."""
        person = recorded.person
        static_depths, object_depths, sole_points = (
            self._seen(recorded) if person is not None else ((), (), {})
        )
        held = [o for o in recorded.objects if o.holder in PERSON_HOLDERS]
        return Sample(
            time=recorded.time,
            static_depths=static_depths,
            object_depths=object_depths,
            carried_depths=self._carried_depths(recorded),
            hand_gaps=tuple(gap for o in held for gap in self._hand_gaps(o, recorded)),
            tilts=tuple((_tilt(o.pose), f"{o.type} {o.id}") for o in held),
            sole_points=sole_points,
            pelvis=(person.pose_time, *person.pelvis) if person is not None else None,
            walking=person is not None and person.walking,
        )

    def _seen(self, recorded: Recorded) -> tuple:
        """Penetrations and sole points: the last sample's while the person's joints and the
        objects stay as they were (the objects' statuses are the same tuple while no object
        moves)."""
        positions, objects, seen = self._last
        current = recorded.person.positions
        if objects is not recorded.objects or not np.array_equal(positions, current):
            bodies = self._posed_person(current)
            free = [o for o in recorded.objects if o.holder not in PERSON_HOLDERS]
            seen = (
                self._static_depths(),
                self._object_depths(bodies, recorded, free),
                self.body.sole_points(bodies),
            )
            self._last = (current, recorded.objects, seen)
        return seen

    def _posed_person(self, positions: np.ndarray) -> np.ndarray:
        """Poses the person in the scene; returns their bodies' world poses (n × 3 × 4)."""
        geometry, bodies = self.body.posed(positions)
        self._fix_poses(self._scene_context(), self.body.source_id, geometry)
        return bodies

    def _query(self, objects=None):
        """The scene's query object (with `objects`, a sample's objects placed first)."""
        scene = self._scene_context()
        if objects is not None and objects is not self._objects_posed:
            self._fix_poses(scene, self._workpieces.source_id, self._object_poses(objects))
            self._objects_posed = objects
        return self._scene_graph.get_query_output_port().Eval(scene)

    def _object_poses(self, objects) -> FramePoseVector:
        """Every slot where the Workpieces put it: the objects' poses, the others parked."""
        poses = FramePoseVector()
        for frame, parked in self._workpieces.parked_poses():
            poses.set_value(frame, parked)
        for o in objects:
            if o.geometry_id is not None:
                poses.set_value(self._inspector.GetFrameId(o.geometry_id), o.pose)
        return poses

    def _scene_context(self):
        """The scene's context, made at its first use with the cell posed (the mirror's
        default pose: the static geometry does not move) and the objects parked."""
        if self._scene is not None:
            return self._scene
        scene = self._scene_graph.CreateDefaultContext()
        mirror = self._mirror.CreateDefaultContext()
        poses = self._mirror.get_geometry_pose_output_port().Eval(mirror)
        self._fix_poses(scene, self._mirror.get_source_id(), poses)
        if self._workpieces is not None:
            self._fix_poses(scene, self._workpieces.source_id, self._object_poses(()))
            static = GeometrySet(list(self._static))
            self._scene_graph.collision_filter_manager(scene).Apply(
                CollisionFilterDeclaration().AllowBetween(self._workpieces.geometry_set(), static)
            )
        self._scene = scene
        return scene

    def _fix_poses(self, scene_context, source, poses: FramePoseVector) -> None:
        self._scene_graph.get_source_pose_port(source).FixValue(scene_context, poses)

    def _static_depths(self) -> tuple:
        """The person's regions in the cell's static geometry (objects are filtered out of
        these contact queries, so where they are does not matter here)."""
        regions = self.body.regions
        depths = []
        for pair in self._query().ComputePointPairPenetration():
            for own, other in ((pair.id_A, pair.id_B), (pair.id_B, pair.id_A)):
                if own in regions and other in self._static:
                    depths.append((pair.depth, f"{regions[own]} in {self._static[other]}"))
        return tuple(depths)

    def _object_depths(self, bodies: np.ndarray, recorded: Recorded, objects) -> tuple:
        """Exact distances only for the pairs whose bounding shapes overlap."""
        near = [o for o in objects if o.geometry_id is not None]
        if not near:
            return ()
        body = self.body
        ends = body.segment_ends(bodies)
        centers = np.array([o.pose.translation() for o in near])
        reach = body.radii[:, None] + np.array([self._object_radii[o.type] for o in near])
        close = _point_segment_distances(centers, ends[:, 0], ends[:, 1]) <= reach
        if not close.any():
            return ()
        query = self._query(recorded.objects)
        depths = []
        for i, k in zip(*np.nonzero(close), strict=True):
            obj, geometry = near[k], body.geometries[i]
            distance = query.ComputeSignedDistancePairClosestPoints(
                geometry, obj.geometry_id
            ).distance
            if distance < 0:
                depths.append((-distance, f"{body.regions[geometry]} in {obj.type} {obj.id}"))
        return tuple(depths)

    def _carried_depths(self, recorded: Recorded) -> tuple:
        """How deep each object the person or the robot holds (a part the robot put 3 cm into
        a table was missed, a user's cell) goes into the cell's static geometry (broad phase)
        and into the others the person does not hold (pair queries where bounding spheres meet)."""
        held = [o for o in recorded.objects if o.holder]
        names = {o.geometry_id: f"{o.type} {o.id}" for o in held if o.geometry_id is not None}
        if not names:
            return ()
        query = self._query(recorded.objects)
        depths = [
            (pair.depth, f"{names[own]} in {self._static[other]}")
            for pair in query.ComputePointPairPenetration()
            for own, other in ((pair.id_A, pair.id_B), (pair.id_B, pair.id_A))
            if own in names and other in self._static
        ]
        free = [o for o in recorded.objects if o.holder not in PERSON_HOLDERS and o.geometry_id]
        pairs = ((h, f) for h in held if h.geometry_id in names for f in free if f.id != h.id)
        for obj, other in pairs:
            ids = (obj.geometry_id, other.geometry_id)
            reach = self._object_radii[obj.type] + self._object_radii[other.type]
            if np.linalg.norm(obj.pose.translation() - other.pose.translation()) <= reach:
                pair = query.ComputeSignedDistancePairClosestPoints(*ids)
                if pair.distance < 0:
                    what = f"{names[obj.geometry_id]} in {other.type} {other.id}"
                    depths.append((-pair.distance, what))
        return tuple(depths)

    def _hand_gaps(self, obj, recorded: Recorded) -> list:
        """Each holding hand's distance to the object's surface, both at the time of the
        person's pose (the object's pose moved back to it along its velocity)."""
        solid = self._solids[obj.type]
        person = recorded.person
        X_OW = moved(obj.pose, obj.velocity, person.pose_time - recorded.time).inverse()
        hands = person.hands
        return [
            (
                abs(solid.signed_distance_to(X_OW @ np.array(hands[side][:3]))),
                f"{obj.type} {obj.id}",
            )
            for side in HOLDING_HANDS[obj.holder]
        ]


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


def add_realism_audit(
    builder, scene_graph, mirror, human, human_plant, workpieces, solids, period
) -> RealismAudit:
    """Adds the audit named `realism_audit`, recording the person (`human` and their
    `human_plant`, None without one) and the workpieces (when there are any), and auditing
    them in the world scene's geometry."""
    body, stride_time = None, None
    if human is not None:
        instance = human_plant.GetModelInstanceByName(HUMAN_MODEL)
        body = AuditedBody(human_plant, scene_graph.model_inspector(), instance)
        stride_time = human.stride_time
    scene = AuditScene(scene_graph, mirror, body, workpieces, solids)
    audit = builder.AddNamedSystem(REALISM_AUDIT, RealismAudit(scene, period, stride_time))
    if human is not None:
        for port in ("human_status", "human_positions"):
            builder.Connect(human.GetOutputPort(port), audit.GetInputPort(port))
    if workpieces is not None:
        builder.Connect(
            workpieces.GetOutputPort("workpieces_status"), audit.GetInputPort("workpieces_status")
        )
    return audit
