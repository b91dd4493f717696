"""A cell of the bundled furniture and a person walking in it, measured in the world.

The person's walks are planned as the actor plans them (plan_movement on a Performer with
the cell's navigation map) and posed at the person's update rate; each pose is put into a
Drake SceneGraph holding the furniture models and the person's collision geometry, and the
deepest penetration of a body segment into the furniture is read from SceneGraph (the
realism audit's measure), independently of the navigation map's polygons.
"""

from dataclasses import dataclass
from math import atan2, cos, radians, sin

import numpy as np
from pydrake.geometry import Box, ProximityProperties
from pydrake.math import RigidTransform, RollPitchYaw
from pydrake.multibody.plant import AddMultibodyPlantSceneGraph
from pydrake.multibody.tree import SpatialInertia
from pydrake.systems.framework import DiagramBuilder

from hrc_drake.human.anthropometry import DEFAULT_HEIGHT, DEFAULT_MASS
from hrc_drake.human.body import human_body, parse_human
from hrc_drake.human.clip import load_clips
from hrc_drake.human.grasp import carry_arms, held_corners
from hrc_drake.human.messages import Hold, MoveCommand
from hrc_drake.human.navigation import NavigationMap, cell_obstacles
from hrc_drake.human.performer import Performer
from hrc_drake.human.planning import plan_movement
from hrc_drake.station import model_parser

RATE = 30.0
"""Poses per second: half the person's update rate (a penetration builds up over a tenth of
a second or more; posing every one of them would double the tests' time)."""


@dataclass(frozen=True)
class Furniture:
    name: str
    model: str
    """A model of models/cell (without .sdf)."""
    x: float
    y: float
    yaw_deg: float = 0.0
    z: float = 0.0
    """Height of the model's origin (a bin standing on a table)."""


@dataclass(frozen=True)
class Penetration:
    depth: float
    where: str
    time: float


class Cell:
    """The furniture welded to the floor and the person beside it in one scene, with the
    box the person holds (`held`: its size) when given."""

    def __init__(self, furniture: list[Furniture], held: tuple | None = None):
        builder = DiagramBuilder()
        self.plant, self.scene_graph = AddMultibodyPlantSceneGraph(builder, 0.0)
        parser = model_parser(self.plant)
        for item in furniture:
            url = f"package://hrc_drake_models/cell/{item.model}.sdf"
            (model,) = parser.AddModels(url=url)
            self.plant.RenameModelInstance(model, item.name)
            turned = RollPitchYaw(0, 0, radians(item.yaw_deg))
            pose = RigidTransform(turned, [item.x, item.y, item.z])
            body = self.plant.GetBodyByName("body", model)
            self.plant.WeldFrames(self.plant.world_frame(), body.body_frame(), pose)
        self.person = parse_human(self.plant, DEFAULT_HEIGHT, DEFAULT_MASS)
        self._held = None if held is None else self._held_box(held)
        self.plant.Finalize()
        self.diagram = builder.Build()
        self.context = self.diagram.CreateDefaultContext()
        self._plant_context = self.plant.GetMyContextFromRoot(self.context)
        inspector = self.scene_graph.model_inspector()
        self.navigation = NavigationMap(cell_obstacles(self.plant, inspector))
        self.performer = Performer(human_body(), load_clips(), self.navigation)
        self._names = {}
        for index in self.plant.GetBodyIndices(self.person):
            for geometry in self.plant.GetCollisionGeometriesForBody(self.plant.get_body(index)):
                self._names[geometry] = inspector.GetName(geometry).split("::")[-1]

    def _held_box(self, size):
        """A free body of the box's shape: its collision geometry's id."""
        inertia = SpatialInertia.SolidBoxWithMass(1.0, *size)
        box = self.plant.AddRigidBody("held", self.plant.AddModelInstance("held"), inertia)
        properties = ProximityProperties()
        return self.plant.RegisterCollisionGeometry(
            box, RigidTransform(), Box(*size), "held", properties
        )

    def carries(self, start: tuple[float, float, float], goal, hold: Hold) -> Penetration:
        """The deepest the box held as `hold` goes into the furniture (SceneGraph's
        penetration pairs, as the realism audit measures a carried object) while the person
        carries it from `start` (x, y, yaw in degrees) to the point `goal`."""
        pose = (start[0], start[1], radians(start[2]))
        command = MoveCommand(1, (*goal, 0.0), hold=hold)
        activity = plan_movement(self.performer, command, pose, 0.0)
        carry = carry_arms(self.performer.body, hold)
        worst = Penetration(0.0, "", 0.0)
        for t in np.arange(0.0, activity.end + 1 / RATE, 1 / RATE):
            corners = held_corners(self.performer.body, carry, activity.pose(self.performer, t))
            found = self._held_penetration(corners, t)
            worst = found if found.depth > worst.depth else worst
        return worst

    def _held_penetration(self, corners: np.ndarray, t: float) -> Penetration:
        """The held box with `corners` (8 x 3, as hrc_drake.human.grasp gives them) in the
        furniture."""
        along = corners[4] - corners[0]
        X_WB = RigidTransform(RollPitchYaw(0, 0, atan2(along[1], along[0])), corners.mean(axis=0))
        self.plant.SetFreeBodyPose(self._plant_context, self.plant.GetBodyByName("held"), X_WB)
        query = self.scene_graph.get_query_output_port().Eval(
            self.scene_graph.GetMyContextFromRoot(self.context)
        )
        worst = Penetration(0.0, "", t)
        for pair in query.ComputePointPairPenetration():
            ids = (pair.id_A, pair.id_B)
            if self._held not in ids or any(g in self._names for g in ids):
                continue
            other = pair.id_B if pair.id_A == self._held else pair.id_A
            if pair.depth > worst.depth:
                furniture = query.inspector().GetName(other).split("::")[0]
                worst = Penetration(pair.depth, f"held box in {furniture}", t)
        return worst

    def walks(self, start: tuple[float, float, float], *goals) -> Penetration:
        """The deepest penetration into the furniture while the person walks from `start`
        (x, y, yaw in degrees) to each goal (x, y, yaw in degrees) in turn."""
        pose = (start[0], start[1], radians(start[2]))
        worst, t0 = Penetration(0.0, "", 0.0), 0.0
        for seq, (x, y, yaw_deg) in enumerate(goals, 1):
            half = radians(yaw_deg) / 2
            command = MoveCommand(seq, (x, y, 0.0), (cos(half), 0.0, 0.0, sin(half)))
            activity = plan_movement(self.performer, command, pose, t0)
            for t in np.arange(t0, activity.end + 1 / RATE, 1 / RATE):
                found = self.penetration(activity.pose(self.performer, t), t)
                worst = found if found.depth > worst.depth else worst
            pose, t0 = activity.final_pose, activity.end
        return worst

    def penetration(self, q: np.ndarray, t: float = 0.0, segments=("",)) -> Penetration:
        """The deepest overlap of the person's collision geometry at the canonical pose q
        (its `segments`: those whose names start with one of them; all by default) with the
        furniture (SceneGraph's penetration pairs)."""
        body = self.performer.body
        self.plant.SetPositions(self._plant_context, self.person, body.plant_positions(q))
        query = self.scene_graph.get_query_output_port().Eval(
            self.scene_graph.GetMyContextFromRoot(self.context)
        )
        worst = Penetration(0.0, "", t)
        inspector = query.inspector()
        for pair in query.ComputePointPairPenetration():
            for own, other in ((pair.id_A, pair.id_B), (pair.id_B, pair.id_A)):
                if (
                    own in self._names
                    and other not in self._names
                    and self._names[own].startswith(segments)
                    and pair.depth > worst.depth
                ):
                    furniture = inspector.GetName(other).split("::")[0]
                    worst = Penetration(pair.depth, f"{self._names[own]} in {furniture}", t)
        return worst
