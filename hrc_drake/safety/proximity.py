"""Distances and approach speeds between the person and the robot, from SceneGraph.

`ProximityMeter.measure` fetches the world poses of the watched frames, bounds every
(body region, robot part) pair with the capsule broad phase, and asks the QueryObject for
exact signed distances (pair queries ignore collision filters) only where a pair can be the
closest or touching. Speeds come from the frame poses of the previous measurement.
"""

from dataclasses import dataclass

import numpy as np

from hrc_drake.safety.geometry import Part, bounding_segment, segment_distances


@dataclass(frozen=True)
class PairReading:
    """One (body region, robot part) pair: signed distance and approach speeds (m/s).

    `robot_approach` is the speed of the robot's witness point towards the person,
    `human_approach` that of the person's witness point towards the robot.
    """

    region: str
    part: str
    distance: float
    robot_approach: float
    human_approach: float

    @property
    def relative_speed(self) -> float:
        return self.robot_approach + self.human_approach


@dataclass(frozen=True)
class Reading:
    """One measurement; `poses` (frames × 3 × 4) feed the next one's speeds."""

    closest: PairReading | None
    contacts: tuple[PairReading, ...]
    robot_speed: float
    human_speed: float
    person_xy: tuple[float, float]
    poses: np.ndarray

    def __deepcopy__(self, memo):
        return self  # immutable: Drake's state copies may share it


class ProximityMeter:
    """Measures person–robot proximity for fixed sets of human and robot geometries."""

    def __init__(self, inspector, human: list[Part], robot: list[Part]):
        self.human, self.robot = human, robot
        parts = human + robot
        self.frames = list(dict.fromkeys(inspector.GetFrameId(p.geometry) for p in parts))
        frame_index = {frame: i for i, frame in enumerate(self.frames)}
        self.part_frame = np.array([frame_index[inspector.GetFrameId(p.geometry)] for p in parts])
        self.X_FG = [inspector.GetPoseInFrame(p.geometry) for p in parts]
        ends = [
            self._segment_in_frame(inspector, p, X) for p, X in zip(parts, self.X_FG, strict=True)
        ]
        self.p0_F = np.array([e[0] for e in ends])
        self.p1_F = np.array([e[1] for e in ends])
        self.radius = np.array([e[2] for e in ends])
        self.n_human = len(human)
        self.human_frames = np.unique(self.part_frame[: self.n_human])

    def measure(self, query_object, previous: np.ndarray | None, dt: float, active) -> Reading:
        """`active` (bool per robot part) switches carried objects in and out."""
        poses = np.array([query_object.GetPoseInWorld(f).GetAsMatrix34() for f in self.frames])
        if previous is None or dt <= 0:
            previous, dt = poses, 0.0
        active = np.asarray(active, dtype=bool)
        p0, p1 = self._world(poses, self.p0_F), self._world(poses, self.p1_F)
        h, r = slice(0, self.n_human), slice(self.n_human, None)
        bound = segment_distances(p0[h], p1[h], p0[r], p1[r])
        bound -= self.radius[h, None] + self.radius[None, r]
        bound[:, ~active] = np.inf
        pairs = self._exact_pairs(query_object, bound)
        readings = [self._pair_reading(pair, poses, previous, dt) for pair in pairs]
        centre = poses[self.human_frames, :, 3].mean(axis=0)
        return Reading(
            closest=min(readings, key=lambda x: x.distance, default=None),
            contacts=tuple(x for x in readings if x.distance <= 0.0),
            robot_speed=self._robot_speed(poses, previous, dt, active),
            human_speed=_speed(centre, previous[self.human_frames, :, 3].mean(axis=0), dt),
            person_xy=(float(centre[0]), float(centre[1])),
            poses=poses,
        )

    def _robot_speed(self, poses, previous, dt, active) -> float:
        """Fastest end of any active robot part's bounding segment (tool tip included)."""
        robot = np.flatnonzero(active) + self.n_human
        ends = [self.p0_F[robot], self.p1_F[robot]]
        now = np.concatenate([self._world(poses, e, robot) for e in ends])
        before = np.concatenate([self._world(previous, e, robot) for e in ends])
        if dt <= 0.0:
            return 0.0
        return float(np.linalg.norm(now - before, axis=1).max(initial=0.0)) / dt

    def _exact_pairs(self, query_object, bound: np.ndarray) -> list:
        """Exact signed distances of the pairs that can be the closest or in contact."""
        best = np.inf
        pairs = []
        for flat in np.argsort(bound, axis=None):
            lower = bound.flat[flat]
            if lower == np.inf or (lower >= best and (best > 0.0 or lower > 0.0)):
                break
            i, j = np.unravel_index(flat, bound.shape)
            pair = query_object.ComputeSignedDistancePairClosestPoints(
                self.human[i].geometry, self.robot[j].geometry
            )
            pairs.append((i, j, pair))
            best = min(best, pair.distance)
        return [p for p in pairs if p[2].distance <= max(best, 0.0)]

    def _pair_reading(self, pair, poses, previous, dt) -> PairReading:
        i, j, result = pair
        k_h, k_r = i, self.n_human + j
        v_h = self._point_velocity(k_h, result.p_ACa, poses, previous, dt)
        v_r = self._point_velocity(k_r, result.p_BCb, poses, previous, dt)
        towards_human = result.nhat_BA_W
        return PairReading(
            region=self.human[i].name,
            part=self.robot[j].name,
            distance=float(result.distance),
            robot_approach=float(v_r @ towards_human),
            human_approach=float(-v_h @ towards_human),
        )

    def _point_velocity(self, part: int, p_G, poses, previous, dt) -> np.ndarray:
        if dt <= 0.0:
            return np.zeros(3)
        p_F = self.X_FG[part] @ p_G
        frame = self.part_frame[part]
        now = poses[frame, :, :3] @ p_F + poses[frame, :, 3]
        before = previous[frame, :, :3] @ p_F + previous[frame, :, 3]
        return (now - before) / dt

    def _world(self, poses: np.ndarray, points_F: np.ndarray, parts=None) -> np.ndarray:
        """Points given per part in its frame, in world (for all parts or the listed ones)."""
        X = poses[self.part_frame if parts is None else self.part_frame[parts]]
        return np.einsum("nij,nj->ni", X[:, :, :3], points_F) + X[:, :, 3]

    @staticmethod
    def _segment_in_frame(inspector, part: Part, X_FG):
        p0, p1, radius = bounding_segment(inspector.GetShape(part.geometry))
        return X_FG @ p0, X_FG @ p1, radius


def _speed(now: np.ndarray, before: np.ndarray, dt: float) -> float:
    return float(np.linalg.norm(now - before)) / dt if dt > 0.0 else 0.0
