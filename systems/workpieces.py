"""Workpieces: kinematic objects that behavior trees spawn, robot and person carry and hand
over, conveyors transport, and every other system can track through the `workpieces_status` port.

The objects are a SceneGraph source of their own (proximity + illustration geometry), not
bodies of the dynamic plant, so they must be collision-filtered against everything else
that has proximity geometry (the discrete plant throws on contact pairs it does not own);
`add_workpieces` does that and the wiring. The physics is deliberately light (see
`hrc_drake.workpieces.update`): carried objects follow their holder's grasp frame, released
ones fall and rest on the highest support below them, belts move what rests on them.

Geometry cannot be added once a Context exists, so capacity is fixed: every object type
reserves `capacity` slots, each a SceneGraph frame with that type's geometry, registered at
construction. A slot without a live object is parked far below the floor, 10 m from the
next, and is not reported.
"""

import operator

import numpy as np
from pydrake.common.value import AbstractValue
from pydrake.geometry import (
    FramePoseVector,
    GeometryFrame,
    GeometryInstance,
    GeometrySet,
    MakePhongIllustrationProperties,
    ProximityProperties,
    SceneGraph,
)
from pydrake.math import RigidTransform
from pydrake.multibody.plant import MultibodyPlant
from pydrake.multibody.tree import Frame
from pydrake.systems.framework import Context, DiagramBuilder, EventStatus, LeafSystem

from hrc_drake.areas import Area
from hrc_drake.ports import message_value, value_or_none
from hrc_drake.scene_geometry import filter_against, other_proximity_geometry
from hrc_drake.systems.adapters import add_tool_pose
from hrc_drake.wiring import WORKPIECES, WORKPIECES_SYSTEM, command_input, issuers_of
from hrc_drake.workpieces.config import WorkpiecesConfig
from hrc_drake.workpieces.messages import HandPoses
from hrc_drake.workpieces.surfaces import Surface, cell_surfaces, named_surfaces
from hrc_drake.workpieces.update import initial_world, next_world, still
from hrc_drake.workpieces.world import (
    StatusOfWorld,
    Workcell,
    World,
    holder_frames,
    person_frames,
    since,
)

PARKING_DEPTH = -1000.0
PARKING_SPACING = 10.0


def parked_pose(slot: int) -> RigidTransform:
    """Where an unused slot waits: far below the floor and far from the other slots."""
    return RigidTransform([PARKING_SPACING * slot, 0.0, PARKING_DEPTH])


class Workpieces(LeafSystem):
    """Moving objects of a scenario.

    Inputs: `<issuer>_command` for each issuer (the issuer's latest command or None),
    `tool_pose` (RigidTransform of the robot's `tcp` in the world) and `human_hands`
    (HandPoses); an unconnected holder input means that holder does not exist.
    Outputs: `geometry_pose` (FramePoseVector for SceneGraph) and `workpieces_status`
    (WorkpiecesStatus), both from state only, extrapolated from the last update to the
    context's time. State: one immutable World, updated every `config.period` while
    anything moves, is held or is commanded (`hrc_drake.workpieces.update.still`).
    """

    def __init__(
        self,
        config: WorkpiecesConfig,
        scene_graph: SceneGraph,
        seed: np.random.SeedSequence,
        issuers: tuple[str, ...] = issuers_of(WORKPIECES),
        surfaces: list[Surface] = (),
        areas: dict[str, Area] | None = None,
        name: str = WORKPIECES_SYSTEM,
    ):
        super().__init__()
        all_surfaces = [*surfaces, *named_surfaces(config.surfaces)]
        self.cell = Workcell(config, all_surfaces, seed, issuers, areas)
        self.source_id = scene_graph.RegisterSource(name)
        self.frame_ids = self._register_slots(scene_graph, config)
        inspector = scene_graph.model_inspector()
        self.geometry_ids = [inspector.GetGeometries(f)[0] for f in self.frame_ids]
        self._parked = [parked_pose(slot) for slot in range(len(self.frame_ids))]
        self._poses = FramePoseVector()
        for frame_id, X_WS in zip(self.frame_ids, self._parked, strict=True):
            self._poses.set_value(frame_id, X_WS)
        self._written = [None] * len(self.frame_ids)  # the piece each slot's pose is of
        self._person = (None, {})  # the hands input's last value and its grasp frames
        self._resting = (None, [])
        self._still_for = None  # the world and commands last found still
        initial = initial_world(self.cell)
        self._status_of = StatusOfWorld(self.cell, initial, self.geometry_ids)
        self._state = self.DeclareAbstractState(AbstractValue.Make(initial))
        self._commands = {
            issuer: self.DeclareAbstractInputPort(command_input(issuer), message_value())
            for issuer in self.cell.issuers
        }
        self._tool = self.DeclareAbstractInputPort(
            "tool_pose", AbstractValue.Make(RigidTransform())
        )
        neutral_hands = HandPoses(RigidTransform(), RigidTransform())
        self._hands = self.DeclareAbstractInputPort(
            "human_hands", AbstractValue.Make(neutral_hands)
        )
        from_state = {self.time_ticket(), self.abstract_state_ticket(self._state)}
        self.DeclareAbstractOutputPort(
            "geometry_pose",
            lambda: AbstractValue.Make(FramePoseVector()),
            self._calc_poses,
            prerequisites_of_calc=from_state,
        )
        self.DeclareAbstractOutputPort(
            "workpieces_status",
            lambda: AbstractValue.Make(self.cell.status(initial, 0.0)),
            self._calc_status,
            prerequisites_of_calc=from_state,
        )
        self.DeclarePeriodicUnrestrictedUpdateEvent(config.period, 0.0, self._update)

    def _register_slots(self, scene_graph: SceneGraph, config: WorkpiecesConfig) -> list:
        """One frame with its type's geometry per slot, in slot order."""
        frame_ids = []
        for kind in self.cell.kinds.values():
            color = config.types[kind.name].color
            for index in range(len(kind.slots)):
                name = f"{kind.name}_{index}"
                frame_id = scene_graph.RegisterFrame(self.source_id, GeometryFrame(name))
                instance = GeometryInstance(RigidTransform(), kind.solid.drake_shape(), name)
                instance.set_proximity_properties(ProximityProperties())
                instance.set_illustration_properties(MakePhongIllustrationProperties(color))
                scene_graph.RegisterGeometry(self.source_id, frame_id, instance)
                frame_ids.append(frame_id)
        return frame_ids

    def geometry_set(self) -> GeometrySet:
        """All the workpieces' geometry (for collision filters)."""
        return GeometrySet(self.geometry_ids)

    def parked_poses(self) -> list[tuple]:
        """(frame id, pose) of every slot while it has no live object."""
        return list(zip(self.frame_ids, self._parked, strict=True))

    def world(self, context: Context) -> World:
        return context.get_abstract_state(self._state).get_value()

    def _update(self, context: Context, state) -> EventStatus:
        """The next world, unless nothing moves, is held or is commanded (`still`): then
        the update did nothing, and Drake leaves the state as it is."""
        commands = {issuer: value_or_none(port, context) for issuer, port in self._commands.items()}
        world = self.world(context)
        if self._still(world, commands):
            return EventStatus.DidNothing()
        frames = holder_frames(value_or_none(self._tool, context), self._person_frames(context))
        world = next_world(self.cell, world, context.get_time(), commands, frames)
        state.get_mutable_abstract_state(self._state).set_value(world)
        return EventStatus.Succeeded()

    def _still(self, world: World, commands: dict) -> bool:
        """`still`, asked again only when the world or a command port's value is another
        object than at the last update found still (all immutable): most updates of a
        resting world find the same ones."""
        inputs = (world, *commands.values())
        if self._still_for is None or not all(map(operator.is_, inputs, self._still_for)):
            if not still(self.cell, world, commands):
                return False
            self._still_for = inputs
        return True

    def _person_frames(self, context: Context) -> dict:
        """`person_frames` of the hands input, made again only when its value is a new one:
        the person's pose changes at their own rate (60 Hz), below the objects' (100 Hz).
        The last value is kept, so a new one is never taken for it."""
        hands = value_or_none(self._hands, context)
        if hands is not self._person[0]:
            self._person = (hands, person_frames(hands))
        return self._person[1]

    def _resting_poses(self, world: World) -> tuple[FramePoseVector, list]:
        """Every slot's pose while `world` lasts, but for the moving pieces, and their drifts.
        Computed once per update, not once per plant step (a World is immutable, so its
        identity is the key), and only for slots whose piece changed: a resting piece stays
        the same object from update to update."""
        if self._resting[0] is not world:
            by_slot = {piece.slot: piece for piece in world.pieces.values()}
            moving = []
            for slot, frame_id in enumerate(self.frame_ids):
                piece = by_slot.get(slot)
                if piece is not None and piece.moving:
                    moving.append((frame_id, piece.drift))
                elif piece is not self._written[slot]:
                    self._poses.set_value(frame_id, self._slot_pose(slot, piece, world))
                self._written[slot] = piece
            self._resting = (world, moving)
        return self._poses, self._resting[1]

    def _slot_pose(self, slot: int, piece, world: World) -> RigidTransform:
        return self._parked[slot] if piece is None else self.cell.pose_at(piece, world, world.time)

    def _calc_poses(self, context: Context, output: AbstractValue) -> None:
        """Resting and parked slots as at the last update; moving pieces extrapolated to the
        context's time."""
        world = self.world(context)
        resting, moving = self._resting_poses(world)
        output.set_value(resting)
        poses = output.get_mutable_value()
        dt = since(world, context.get_time())
        for frame_id, drift in moving:
            poses.set_value(frame_id, drift.after(dt))

    def _calc_status(self, context: Context, output: AbstractValue) -> None:
        """The world at the context's time: an object at rest is made once, not at every
        evaluation or update (`StatusOfWorld`)."""
        world = self.world(context)
        if self._status_of.world is not world:
            self._status_of = StatusOfWorld(self.cell, world, self.geometry_ids, self._status_of)
        output.set_value(self._status_of.at(context.get_time()))


def add_workpieces(
    builder: DiagramBuilder,
    scene_graph: SceneGraph,
    plant: MultibodyPlant,
    config: WorkpiecesConfig,
    seed: np.random.SeedSequence,
    tool_frame: Frame | None = None,
    areas: dict[str, Area] | None = None,
    issuers: tuple[str, ...] = issuers_of(WORKPIECES),
) -> Workpieces:
    """Adds Workpieces beside a finalized plant: its support surfaces come from the plant's
    static geometry, its poses go to SceneGraph, it is collision-filtered against all the
    proximity geometry registered so far (add it after the plant and the person's geometry,
    or filter later geometry against `geometry_set()`), and, given the robot's `tcp` frame,
    its `tool_pose` input is fed from the body poses of that frame's plant."""
    surfaces = cell_surfaces(plant, scene_graph) if config.derive_surfaces else []
    workpieces = builder.AddNamedSystem(
        WORKPIECES_SYSTEM, Workpieces(config, scene_graph, seed, issuers, surfaces, areas)
    )
    builder.Connect(
        workpieces.GetOutputPort("geometry_pose"),
        scene_graph.get_source_pose_port(workpieces.source_id),
    )
    filter_against(
        scene_graph,
        workpieces.geometry_set(),
        other_proximity_geometry(scene_graph, workpieces.source_id),
    )
    if tool_frame is not None:  # its plant may be another than the cell's
        builder.Connect(add_tool_pose(builder, tool_frame), workpieces.GetInputPort("tool_pose"))
    return workpieces
