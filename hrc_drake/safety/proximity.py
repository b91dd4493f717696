"""Distances and approach speeds between the person and the robot, from SceneGraph.

`ProximityMeter.measure` fetches the world poses of the watched frames, bounds every
(body region, robot part) pair with the capsule broad phase, and asks the QueryObject for
exact signed distances (pair queries ignore collision filters) only where a pair can be the
closest or touching. Speeds come from the frame poses of the previous measurement; the
capsule gaps are reused, less how far the parts moved, until a part moved `REFRESH_DISTANCE`.
Both live in the reading's `memory`, which the monitor keeps as vector state.
"""

import math
from dataclasses import dataclass

import numpy as np

from hrc_drake.safety.geometry import Part, bounding_segment, segment_distances

BOUND_SLACK = 1e-6
"""m taken off every capsule bound, so that rounding (in the bound or in Drake's distance)
cannot skip a pair that is closer than the best one found by a hair."""

REFRESH_DISTANCE = 0.02
"""m any part may move before the capsule gaps are computed afresh. Until then the gaps of
the reference less both parts' displacements since bound the distances (a capsule moves no
farther than its segment's ends); farther moves loosen them into more exact queries than
the fresh gaps cost."""


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
    """One measurement; `memory` (a vector) feeds the next one's speeds and bounds."""

    closest: PairReading | None
    contacts: tuple[PairReading, ...]
    robot_speed: float
    human_speed: float
    person_xy: tuple[float, float]
    memory: np.ndarray


class ProximityMeter:
    """Measures person–robot proximity for fixed sets of human and robot geometries.

    Parts are numbered human first, then robot; `measure` takes the active robot parts as
    indices into `robot`.
    """

    def __init__(self, inspector, human: list[Part], robot: list[Part]):
        self.human, self.robot = human, robot
        self.n_human = len(human)
        self.geometries = [p.geometry for p in human + robot]
        part_frames = [inspector.GetFrameId(g) for g in self.geometries]
        self.frames = list(dict.fromkeys(part_frames))
        self.part_frame = np.array([self.frames.index(f) for f in part_frames])
        self.X_FG = np.array([inspector.GetPoseInFrame(g).GetAsMatrix34() for g in self.geometries])
        segments = [bounding_segment(inspector.GetShape(g)) for g in self.geometries]
        self.ends_F = np.array(
            [
                _homogeneous_ends(X, p0, p1)
                for X, (p0, p1, _) in zip(self.X_FG, segments, strict=True)
            ]
        )
        radius = np.array([r for _, _, r in segments])
        self.radii = radius[: self.n_human, None] + radius[None, self.n_human :] + BOUND_SLACK
        human_frames = np.unique(self.part_frame[: self.n_human])
        self.centre_weights = np.zeros(len(self.frames))
        self.centre_weights[human_frames] = 1.0 / len(human_frames)
        poses_end = 12 * len(self.frames)
        ends_end = poses_end + 6 * len(self.geometries)
        self._memory_parts = slice(0, poses_end), slice(poses_end, ends_end), slice(ends_end, None)
        self.memory_size = ends_end + self.radii.size

    def measure(self, query_object, memory: np.ndarray | None, dt: float, robot) -> Reading:
        """`memory` is the last reading's (None at first); `robot` (indices into `robot`) are
        the active parts: carried objects come and go."""
        poses = np.array([query_object.GetPoseInWorld(f).GetAsMatrix34() for f in self.frames])
        previous, reference = self._recall(memory) if memory is not None else (poses, None)
        if dt <= 0:
            previous, dt = poses, 0.0
        robot_rows = self.n_human + robot
        ends = self._ends(poses)
        gaps, reference = self._gaps(ends, reference)
        bound = gaps[:, robot] - self.radii[:, robot]
        readings = [
            self._pair_reading(i, robot_rows[j], result, poses, previous, dt)
            for i, j, result in self._exact_pairs(query_object, bound, robot_rows)
        ]
        centre = self.centre_weights @ poses[:, :, 3]
        return Reading(
            closest=min(readings, key=lambda x: x.distance, default=None),
            contacts=tuple(x for x in readings if x.distance <= 0.0),
            robot_speed=self._robot_speed(ends, previous, dt, robot_rows),
            human_speed=_speed(centre, self.centre_weights @ previous[:, :, 3], dt),
            person_xy=(float(centre[0]), float(centre[1])),
            memory=np.concatenate([poses.ravel(), *(r.ravel() for r in reference)]),
        )

    def _recall(self, memory: np.ndarray):
        """The last poses and the gaps' reference (part ends, gaps) stored in `memory`."""
        poses, ends, gaps = (memory[part] for part in self._memory_parts)
        return poses.reshape(-1, 3, 4), (ends.reshape(-1, 3, 2), gaps.reshape(self.n_human, -1))

    def _ends(self, poses: np.ndarray) -> np.ndarray:
        """World end points (parts × 3 × 2) of all parts' bounding segments."""
        return poses[self.part_frame] @ self.ends_F

    def _gaps(self, ends: np.ndarray, reference) -> tuple:
        """Lower bounds (human × robot parts) of the distances between the bounding segments,
        and their reference (part ends, gaps): the last one while no part moved far."""
        if reference is not None:
            moved = ends - reference[0]
            moved = np.sqrt((moved * moved).sum(axis=1).max(axis=1))
            if moved.max() <= REFRESH_DISTANCE:
                h, r = moved[: self.n_human, None], moved[None, self.n_human :]
                return reference[1] - h - r, reference
        starts, directions = ends[:, :, 0], ends[:, :, 1] - ends[:, :, 0]
        h, r = slice(0, self.n_human), slice(self.n_human, None)
        gaps = segment_distances(starts[h], directions[h], starts[r], directions[r])
        return gaps, (ends, gaps)

    def _robot_speed(self, ends, previous, dt, robot_rows) -> float:
        """Fastest end of any active robot part's bounding segment (tool tip included)."""
        if dt <= 0.0:
            return 0.0
        moved = (ends - self._ends(previous))[robot_rows]
        return math.sqrt((moved * moved).sum(axis=1).max()) / dt

    def _exact_pairs(self, query_object, bound: np.ndarray, robot_rows: np.ndarray) -> list:
        """Exact signed distances of the pairs that can be the closest or in contact, as
        (human part, column of `bound`, result)."""
        flat = bound.ravel()
        best = math.inf
        pairs = []
        for k in np.argsort(flat):
            lower = flat[k]
            if lower >= best and (best > 0.0 or lower > 0.0):
                break
            i, j = divmod(int(k), bound.shape[1])
            result = query_object.ComputeSignedDistancePairClosestPoints(
                self.geometries[i], self.geometries[robot_rows[j]]
            )
            pairs.append((i, j, result))
            best = min(best, result.distance)
        return [p for p in pairs if p[2].distance <= max(best, 0.0)]

    def _pair_reading(self, i: int, k: int, result, poses, previous, dt) -> PairReading:
        """Reading of human part `i` and part `k` (a robot part)."""
        v_h, v_r = self._point_velocities([i, k], [result.p_ACa, result.p_BCb], poses, previous, dt)
        towards_human = result.nhat_BA_W
        return PairReading(
            region=self.human[i].name,
            part=self.robot[k - self.n_human].name,
            distance=float(result.distance),
            robot_approach=float(v_r @ towards_human),
            human_approach=float(-v_h @ towards_human),
        )

    def _point_velocities(self, parts: list, points_G: list, poses, previous, dt) -> np.ndarray:
        """World velocities (parts × 3) of points fixed in the parts' geometry frames."""
        if dt <= 0.0:
            return np.zeros((len(parts), 3))
        X_FG = self.X_FG[parts]
        p_F = X_FG[:, :, :3] @ np.array(points_G)[:, :, None] + X_FG[:, :, 3:]
        frames = self.part_frame[parts]
        moved = poses[frames] - previous[frames]
        return (moved[:, :, :3] @ p_F + moved[:, :, 3:])[:, :, 0] / dt


def _homogeneous_ends(X_FG: np.ndarray, p0_G: np.ndarray, p1_G: np.ndarray) -> np.ndarray:
    """A segment's ends in its frame F as the columns of a 4 × 2 matrix (X_WF @ ends)."""
    ends_F = X_FG[:, :3] @ np.column_stack([p0_G, p1_G]) + X_FG[:, 3:]
    return np.vstack([ends_F, np.ones(2)])


def _speed(now: np.ndarray, before: np.ndarray, dt: float) -> float:
    return math.dist(now, before) / dt if dt > 0.0 else 0.0
