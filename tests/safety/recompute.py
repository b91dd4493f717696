"""An independent recomputation of the monitor's SSM verdict from the logged robot and person
trajectories, written plainly and on purpose sharing no code with the monitor: every pair of
robot and body geometry is measured (no broad phase), speeds are backward differences of
body-fixed points between updates, the robot's speed is that of the ends of its
geometries' core segments, and S_p follows docs/safety.md term by term with the stopping
data read straight from the YAML file.
"""

import math
from dataclasses import dataclass

import numpy as np
import yaml
from pydrake.geometry import Box, Capsule, Cylinder, SceneGraph, Sphere
from pydrake.multibody.plant import MultibodyPlant
from pydrake.systems.framework import DiagramBuilder

from hrc_drake.human.body import parse_human
from hrc_drake.paths import resource_dir
from hrc_drake.station import add_station_models, model_parser


@dataclass
class Recomputed:
    separation: np.ndarray
    region: list
    part: list
    protective: np.ndarray
    robot_speed: np.ndarray
    violation: np.ndarray
    human_approach: np.ndarray
    robot_approach: np.ndarray


class Scene:
    """The robot with its cell and the person, posed by hand in one SceneGraph."""

    def __init__(self, scenario):
        builder = DiagramBuilder()
        self.scene_graph = builder.AddSystem(SceneGraph())
        self.robot = MultibodyPlant(0.0)
        self.robot.RegisterAsSourceForSceneGraph(self.scene_graph)
        arm, instances = add_station_models(self.robot, model_parser(self.robot), scenario.station)
        self.robot.Finalize()
        self.human = MultibodyPlant(0.0)
        self.human.RegisterAsSourceForSceneGraph(self.scene_graph)
        parse_human(self.human, 1.75, 75.0)
        self.human.Finalize()
        self.robot_context = self.robot.CreateDefaultContext()
        self.human_context = self.human.CreateDefaultContext()
        self.inspector = self.scene_graph.model_inspector()
        self.robot_geometry = self._geometries(self.robot, instances)
        self.human_geometry = self._geometries(
            self.human, [self.human.GetModelInstanceByName("human")]
        )
        self.scene_graph_context = self.scene_graph.CreateDefaultContext()

    def _geometries(self, plant, instances):
        """(geometry, body, name) of every collision geometry of the instances."""
        return [
            (g, body, self.inspector.GetName(g))
            for instance in instances
            for index in plant.GetBodyIndices(instance)
            for body in [plant.get_body(index)]
            for g in plant.GetCollisionGeometriesForBody(body)
        ]

    def pose(self, robot_q, person_q):
        """The QueryObject of the scene at these positions, and the world pose of every robot
        and body geometry (from the plants' kinematics)."""
        self.robot.SetPositions(self.robot_context, robot_q)
        self.human.SetPositions(self.human_context, person_q)
        poses = {}
        for plant, context in ((self.robot, self.robot_context), (self.human, self.human_context)):
            self.scene_graph.get_source_pose_port(plant.get_source_id()).FixValue(
                self.scene_graph_context, plant.get_geometry_pose_output_port().Eval(context)
            )
        for plant, context, geometries in (
            (self.robot, self.robot_context, self.robot_geometry),
            (self.human, self.human_context, self.human_geometry),
        ):
            for g, body, _ in geometries:
                X_WB = plant.EvalBodyPoseInWorld(context, body)
                poses[g] = X_WB @ self.inspector.GetPoseInFrame(g)
        return self.scene_graph.get_query_output_port().Eval(self.scene_graph_context), poses

    def closest(self, query, poses):
        """The closest (robot, body) pair over all pairs: distance, both witness points in
        world coordinates, the unit normal from robot to person, the two geometries."""
        best = None
        for g_h, _, _ in self.human_geometry:
            for g_r, _, _ in self.robot_geometry:
                result = query.ComputeSignedDistancePairClosestPoints(g_h, g_r)
                if best is None or result.distance < best[0].distance:
                    best = (result, g_h, g_r)
        result, g_h, g_r = best
        if result.id_A == g_h:
            p_h, p_r, n = result.p_ACa, result.p_BCb, result.nhat_BA_W
        else:
            p_h, p_r, n = result.p_BCb, result.p_ACa, -result.nhat_BA_W
        return result.distance, poses[g_h] @ p_h, poses[g_r] @ p_r, n, g_h, g_r

    def ends(self, poses) -> np.ndarray:
        """World positions of the ends of every robot geometry's core segment: a capsule's
        or cylinder's axis, a box's longest middle line, a sphere's centre (the points
        whose fastest speed the monitor calls the robot's speed)."""
        points = []
        for g, _, _ in self.robot_geometry:
            half = _half_axis(self.inspector.GetShape(g))
            points += [poses[g] @ half, poses[g] @ -half]
        return np.array(points)


def _half_axis(shape) -> np.ndarray:
    if isinstance(shape, Capsule | Cylinder):
        return np.array([0.0, 0.0, shape.length() / 2])
    if isinstance(shape, Sphere):
        return np.zeros(3)
    if isinstance(shape, Box):
        size = shape.size()
        longest = int(np.argmax(size))
        return np.eye(3)[longest] * size[longest] / 2
    raise ValueError(type(shape).__name__)


def worst_stopping_times(variant: str) -> tuple[list, list, float]:
    """From the YAML: the speed levels with 0 first, the worst stopping time at each (the
    first segment carried on to rest, never below 0) and κ."""
    path = resource_dir("models") / "iisy" / "stopping" / f"{variant}.yaml"
    stops = yaml.safe_load(path.read_text())["stops"]
    levels = sorted({s["speed"] for s in stops})
    worst = [max(s["time"] for s in stops if s["speed"] == level) for level in levels]
    slope = (worst[1] - worst[0]) / (levels[1] - levels[0])
    kappa = max(s["distance"] / (s["point_speed"] * s["time"]) for s in stops)
    return [0.0, *levels], [max(0.0, worst[0] - slope * levels[0]), *worst], kappa


def sensing_time(config) -> float:
    """How late the person is known: the slowest safety sensor's response time, or without
    sensors the monitor's own sensing time."""
    sensors = [*config.sensors.scanners.values(), *config.sensors.light_curtains.values()]
    return max((sensor.response_time for sensor in sensors), default=config.sensing_time)


def recompute(outcome, variant: str, command_latency: float = 0.01) -> Recomputed:
    """S_p = v_h (T_r + T_s) + v_r T_r + S_s + C + Z_d + Z_r at every logged update, v_h by
    ISO 13855 (the walk-in cell's rule), of the real body (with sensors too, whose response
    time T_r then holds); the directed speeds of both witness points too."""
    config = outcome.config
    scene = Scene(outcome.scenario)
    speeds, times, kappa = worst_stopping_times(variant)
    t_r = sensing_time(config) + config.period + command_latency
    margins = config.intrusion_distance + config.sensor_uncertainty + config.robot_uncertainty
    rates = outcome.signals_named("path_rate")
    result = Recomputed(*([] for _ in range(8)))
    previous = None
    for k, t in enumerate(outcome.times):
        query, poses = scene.pose(outcome.robot_q[:, k], outcome.person_q[:, k])
        distance, p_h, p_r, n, g_h, g_r = scene.closest(query, poses)
        ends = scene.ends(poses)
        v_r = v_h = robot_speed = 0.0
        if previous is not None:
            dt = t - outcome.times[k - 1]
            before, ends_before = previous
            # the same body-fixed points one update earlier
            p_r_before = before[g_r] @ (poses[g_r].inverse() @ p_r)
            p_h_before = before[g_h] @ (poses[g_h].inverse() @ p_h)
            v_r = max(0.0, float((p_r - p_r_before) @ n) / dt)
            v_h = max(0.0, float(-(p_h - p_h_before) @ n) / dt)
            robot_speed = float(np.linalg.norm(ends - ends_before, axis=1).max()) / dt
        previous = poses, ends
        t_s = 0.0 if rates[k] <= 0.0 else float(np.interp(rates[k], speeds, times))
        s_s = kappa * robot_speed * t_s

        robot_terms = v_r * t_r + s_s + margins
        near = config.v_h_near * (t_r + t_s) + robot_terms  # ISO 13855
        walking = config.v_h * (t_r + t_s) + robot_terms
        protective = near if near <= config.near_distance else max(walking, config.near_distance)
        result.separation.append(distance)
        result.region.append(scene.inspector.GetName(g_h).split("::")[-1].split("__")[0])
        result.part.append(scene.robot.GetBodyFromFrameId(scene.inspector.GetFrameId(g_r)).name())
        result.protective.append(protective)
        result.robot_speed.append(robot_speed)
        result.violation.append(robot_speed > config.moving_speed and distance < protective)
        result.human_approach.append(v_h)
        result.robot_approach.append(v_r)
    return Recomputed(
        np.array(result.separation),
        result.region,
        result.part,
        np.array(result.protective),
        np.array(result.robot_speed),
        np.array(result.violation),
        np.array(result.human_approach),
        np.array(result.robot_approach),
    )


def episodes(flags: np.ndarray, times: np.ndarray) -> list[tuple[float, float]]:
    """(first, last) time of every run of True."""
    runs, start = [], None
    for flag, t, before in zip(flags, times, [math.nan, *times[:-1]], strict=True):
        if flag and start is None:
            start = t
        if not flag and start is not None:
            runs.append((start, before))
            start = None
    if start is not None:
        runs.append((start, times[-1]))
    return runs
