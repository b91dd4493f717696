"""Distances and approach speeds between the person and the robot, from SceneGraph.

`ProximityMeter.measure` fetches the world poses of the watched frames, bounds every
(body region, robot part) pair with the capsule broad phase, and asks the QueryObject for
exact signed distances (pair queries ignore collision filters) only where a pair can be the
closest or touching. Speeds come from the frame poses of the previous measurement (the
person's from their previous pose sample: HumanActor holds a pose between its updates, so
differencing at the monitor's rate would read 0 or too fast); the capsule gaps are reused,
less how far the parts moved, until a part moved `REFRESH_DISTANCE`. All of it lives in the
reading's `memory`, which the monitor keeps as vector state.

The person has two speeds here. `walking_speed` is the pelvis's along the floor. A pair's
`human_approach` is that of the person's witness point towards the robot, moving with its
body region's own frame: the closest region's approach never differences points of two
regions, so when another region becomes the closest the speed is that region's own.

Only the active parts are measured: the person, the arm and tool, and the object the robot
holds, not every workpiece it might hold. Frames of inactive parts are NaN in the memory; a
part that becomes active has no previous pose, so it counts as resting for that update.
"""

import dataclasses
import itertools
import math
from dataclasses import dataclass, field

import numpy as np

from hrc_drake.safety import kernels
from hrc_drake.safety.geometry import Part, bounding_segment

PELVIS = "pelvis"
"""The body region whose motion along the floor is the person's walking."""

BOUND_SLACK = 1e-6
"""m taken off every capsule bound, so that rounding (in the bound or in Drake's distance)
cannot skip a pair that is closer than the best one found by a hair."""

PIN_COS = 0.5
"""cos 60°: an obstacle within this angle of the direction the robot pushes a body region
holds the region against the robot (a clamping, quasi-static contact)."""

REFRESH_DISTANCE = 0.04
"""m any part may move before the capsule gaps are computed afresh. Until then the gaps of
the reference less both parts' displacements since bound the distances (a capsule moves no
farther than its segment's ends). At 0.02 m a third of the coexistence's readings computed
fresh gaps; at 0.04 m the exact queries stay as many (benchmarks/proximity_cost.py), farther
moves loosen the bounds into more of them than the fresh gaps cost."""


@dataclass(frozen=True, eq=False)
class PairReading:
    """One (body region, robot part) pair: signed distance and directed speeds (m/s).

    `robot_approach` is the speed of the robot's witness point towards the person,
    `human_approach` that of the person's witness point towards the robot; `normal` points
    from the robot part towards the person (world), `human_point` is the person's witness
    point (world), whichever order SceneGraph reports the pair in.
    """

    region: str
    part: str
    distance: float
    robot_approach: float
    human_approach: float
    human_part: int = -1
    """index into the meter's `human`"""
    robot_part: int = -1
    """index into the meter's `robot`"""
    normal: np.ndarray = field(default_factory=lambda: np.zeros(3))
    human_point: np.ndarray = field(default_factory=lambda: np.zeros(3))
    pinned: bool = False
    """a contact whose body region cannot recoil (see `ProximityMeter.pinned`)"""

    @property
    def relative_speed(self) -> float:
        return self.robot_approach + self.human_approach


@dataclass(frozen=True)
class Reading:
    """One measurement; `memory` (a vector) feeds the next one's speeds and bounds."""

    closest: PairReading | None
    contacts: tuple[PairReading, ...]
    robot_speed: float
    walking_speed: float
    """the person's pelvis along the floor (m/s), between their pose samples"""
    person_xy: tuple[float, float]
    """where the person's pelvis is on the floor"""
    memory: np.ndarray
    robot: tuple[np.ndarray, np.ndarray, np.ndarray] = ()
    """the watched robot parts' bounding capsules: starts and spans (parts × 3, world) and
    radii"""


@dataclass(frozen=True, eq=False)
class ActiveParts:
    """The robot parts a reading watches, and what follows from them: made once per set by
    `ProximityMeter.active`, not at every reading."""

    robot: np.ndarray
    """Indices into the meter's `robot`."""
    rows: np.ndarray
    """Their part numbers (after the person's parts)."""
    parts: np.ndarray
    """All watched part numbers: the person's, then `rows`."""
    frames: np.ndarray
    """The frames whose poses the reading looks up."""
    robot_frames: np.ndarray
    """Those of them that are the robot's (the person's are looked up only when they moved)."""
    frame_ids: list
    """The SceneGraph ids of `frames`, and of `robot_frames`."""
    robot_frame_ids: list
    part_frames: np.ndarray
    """The frame of each of `parts`, and their bounding segments' ends in it (`ends_F`)."""
    ends_F: np.ndarray
    radii: np.ndarray
    """Sums of the radii (human × `robot`): the capsule gaps less these bound the distances."""
    geometries: list
    """The SceneGraph ids of `rows`."""


class ProximityMeter:
    """Measures person–robot proximity for fixed sets of human and robot geometries.

    Parts are numbered human first, then robot; `measure` takes the active robot parts as
    an `ActiveParts` (`active(indices into robot)`).
    """

    def __init__(
        self, inspector, human: list[Part], robot: list[Part], fixed=(), clamping_gap=0.02
    ):
        self.human, self.robot = human, robot
        self.fixed = tuple(fixed)
        """Geometries that do not move (the cell): a body region against them is pinned."""
        self.clamping_gap = clamping_gap
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
        self.part_radii = radius
        self.radii = radius[: self.n_human, None] + radius[None, self.n_human :] + BOUND_SLACK
        self.human_frames = np.unique(self.part_frame[: self.n_human])
        self.pelvis_frame = self.part_frame[[part.name for part in human].index(PELVIS)]
        sizes = [2, 12 * len(self.frames), 12 * len(self.human_frames)]
        bounds = np.cumsum([0, *sizes, 6 * len(self.geometries), self.radii.size])
        self._memory_parts = [slice(a, b) for a, b in itertools.pairwise(bounds)]
        self.memory_size = int(bounds[-1])
        self._blank_memory = self._blank(self.memory_size, self._memory_parts[2])
        self._load_kernels()

    def _load_kernels(self) -> None:
        """Compiles the kernels for the types a measurement passes them (or loads them from
        numba's cache) while the diagram is built, with every part active and the frames at
        the origin: else the first measurement of the run waits for it (a watched run's
        first tick waited ~8 s on a fresh machine)."""
        active = self.active(np.arange(len(self.robot)))
        poses = np.tile(np.eye(4)[:3], (len(self.frames), 1, 1))
        rates, *_ = self._kinematics(poses, self._blank_memory, 0.0, 0.0, active)
        point = np.zeros(3)  # SceneGraph's witness points are read-only, the normal is not
        point.flags.writeable = False
        kernels.witness_motion(
            self.X_FG, self.part_frame, poses, rates, 0, self.n_human, point, point, np.ones(3)
        )

    @staticmethod
    def _blank(size: int, person_rates: slice) -> np.ndarray:
        """The memory before the first reading: no times, poses or gaps (NaN), so every
        rate is zero and every gap fresh; the person's rates 0 stand for the missing
        pose samples. Read-only, as the monitor's state is (one compiled kernel each)."""
        memory = np.full(size, np.nan)
        memory[person_rates] = 0.0
        memory.flags.writeable = False
        return memory

    def active(self, robot: np.ndarray) -> ActiveParts:
        """The parts to watch while the robot parts `robot` (indices into `robot`) are."""
        robot = np.asarray(robot)
        rows = self.n_human + robot
        parts = np.concatenate([np.arange(self.n_human), rows])
        frames = np.unique(self.part_frame[parts])
        robot_frames = np.setdiff1d(frames, self.human_frames)
        return ActiveParts(
            robot,
            rows,
            parts,
            frames,
            robot_frames,
            [self.frames[f] for f in frames],
            [self.frames[f] for f in robot_frames],
            self.part_frame[parts],
            self.ends_F[parts],
            self.radii[:, robot],
            [self.geometries[k] for k in rows],
        )

    def measure(
        self,
        query_object,
        memory: np.ndarray | None,
        time: float,
        active: ActiveParts,
        person_time: float | None = None,
    ) -> Reading:
        """`memory` is the last reading's (None at first); `active` the robot parts watched
        now: carried objects come and go. `person_time` is when the person's pose was
        sampled (None: continuously, at `time`)."""
        person_time = time if person_time is None else person_time
        memory = self._blank_memory if memory is None else memory
        poses = self._current_poses(query_object, memory, person_time, active)
        rates, ends, bound, memory, robot_speed = self._kinematics(
            poses, memory, time, person_time, active
        )
        readings = [
            self._pair_reading(i, active.rows[j], result, poses, rates)
            for i, j, result in self._exact_pairs(query_object, bound, active.geometries)
        ]
        contacts = tuple(
            dataclasses.replace(x, pinned=self.pinned(query_object, x, active))
            for x in readings
            if x.distance <= 0.0
        )
        pelvis, pelvis_rate = poses[self.pelvis_frame, :2, 3], rates[self.pelvis_frame, :2, 3]
        memory.flags.writeable = False  # as the monitor's state is (see `_blank`)
        robot = ends[self.n_human :]
        return Reading(
            closest=min(readings, key=lambda x: x.distance, default=None),
            contacts=contacts,
            robot_speed=robot_speed,
            walking_speed=math.hypot(*pelvis_rate.tolist()),
            person_xy=(float(pelvis[0]), float(pelvis[1])),
            memory=memory,
            robot=(robot[:, :, 0], robot[:, :, 1] - robot[:, :, 0], self.part_radii[active.rows]),
        )

    def _poses(self, frames: np.ndarray, ids: list, query_object) -> np.ndarray:
        """World poses (frames × 3 × 4) of `frames` (SceneGraph's `ids`); NaN for the others
        (SceneGraph's pose lookups are most of the meter's cost)."""
        poses = np.full((len(self.frames), 3, 4), np.nan)
        poses[frames] = [query_object.GetPoseInWorld(f).GetAsMatrix34() for f in ids]
        return poses

    def _current_poses(self, query_object, memory, person_time: float, active: ActiveParts):
        """`_poses` of the active frames; the person's are the last reading's while the
        person has no newer pose sample (HumanActor holds its pose between samples)."""
        if person_time != memory[1]:  # NaN before the first reading
            return self._poses(active.frames, active.frame_ids, query_object)
        poses = self._poses(active.robot_frames, active.robot_frame_ids, query_object)
        humans = self.human_frames
        poses[humans] = memory[self._memory_parts[1]].reshape(poses.shape)[humans]
        return poses

    def _kinematics(self, poses, memory, time: float, person_time: float, active) -> tuple:
        """`kernels.kinematics` of `poses` after the reading that left `memory`: rates,
        segment ends, pair bounds, the new memory and the robot's speed."""
        return kernels.kinematics(
            poses,
            *self._recalled(memory, poses.shape),
            time,
            person_time,
            active.robot_frames,
            self.human_frames,
            active.parts,
            active.part_frames,
            active.ends_F,
            active.robot,
            active.radii,
            REFRESH_DISTANCE,
        )

    def _recalled(self, memory: np.ndarray, poses_shape: tuple) -> tuple:
        """`memory`'s parts: times (of the reading and of the person's pose sample), the
        frames' poses, the person's frames' rates, all parts' segment ends and all gaps
        (NaN where not computed)."""
        times, poses, person_rates, ends, gaps = (memory[part] for part in self._memory_parts)
        return (
            times,
            poses.reshape(poses_shape),
            person_rates.reshape(-1, 3, 4),
            ends.reshape(-1, 3, 2),
            gaps.reshape(self.n_human, -1),
        )

    def _exact_pairs(self, query_object, bound: np.ndarray, robot_geometries: list) -> list:
        """Exact signed distances of the pairs that can be the closest or in contact, as
        (human part, column of `bound`, result)."""
        flat = bound.ravel()
        columns = bound.shape[1]
        best = math.inf
        pairs = []
        for k in np.argsort(flat).tolist():
            lower = float(flat[k])
            if lower >= best and (best > 0.0 or lower > 0.0):
                break
            i, j = divmod(k, columns)
            result = query_object.ComputeSignedDistancePairClosestPoints(
                self.geometries[i], robot_geometries[j]
            )
            pairs.append((i, j, result))
            best = min(best, result.distance)
        return [p for p in pairs if p[2].distance <= max(best, 0.0)]

    def _pair_reading(self, i: int, k: int, result, poses, rates) -> PairReading:
        """Reading of human part `i` and part `k` (a robot part). SceneGraph orders the pair
        its own way (`id_A`, `id_B`), so the person's side is looked up, never assumed."""
        human_is_a = result.id_A == self.geometries[i]
        p_H, p_R = (result.p_ACa, result.p_BCb) if human_is_a else (result.p_BCb, result.p_ACa)
        towards_human = (1.0 if human_is_a else -1.0) * result.nhat_BA_W  # one kernel type
        robot_approach, human_approach, p_WH = kernels.witness_motion(
            self.X_FG, self.part_frame, poses, rates, i, k, p_H, p_R, towards_human
        )
        return PairReading(
            region=self.human[i].name,
            part=self.robot[k - self.n_human].name,
            distance=float(result.distance),
            robot_approach=robot_approach,
            human_approach=human_approach,
            human_part=i,
            robot_part=k - self.n_human,
            normal=np.asarray(towards_human, dtype=float),
            human_point=p_WH,
        )

    def pinned(self, query_object, contact: PairReading, active: ActiveParts) -> bool:
        """Whether the touched body region has fixed cell geometry or another robot part
        within the clamping gap on its far side (within PIN_CONE of the direction the robot pushes):
        it cannot recoil, the contact is a clamping one."""
        human = self.geometries[contact.human_part]
        others = [self.geometries[self.n_human + j] for j in active.robot]
        others.remove(self.geometries[self.n_human + contact.robot_part])
        for obstacle in (*self.fixed, *others):
            result = query_object.ComputeSignedDistancePairClosestPoints(human, obstacle)
            if result.distance > self.clamping_gap:
                continue
            towards_human = result.nhat_BA_W if result.id_A == human else -result.nhat_BA_W
            if float(-towards_human @ contact.normal) >= PIN_COS:
                return True
        return False


def _homogeneous_ends(X_FG: np.ndarray, p0_G: np.ndarray, p1_G: np.ndarray) -> np.ndarray:
    """A segment's ends in its frame F as the columns of a 4 × 2 matrix (X_WF @ ends)."""
    ends_F = X_FG[:, :3] @ np.column_stack([p0_G, p1_G]) + X_FG[:, 3:]
    return np.vstack([ends_F, np.ones(2)])
