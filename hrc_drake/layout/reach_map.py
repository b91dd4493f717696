"""Where the robot reaches with the tool down at one height, seen from above, and how much
room to turn the tool it has there: the planner's own inverse kinematics (as `validate`'s
reach check, hrc_drake.motion.reach), asked along one line from the base and turned about
the base axis instead of at every point of the floor.

The arm's first joint turns everything beyond it about the (vertical) base axis, and its
range (+-185 deg) covers the full circle: a tool pose the arm reaches at distance r and
height z is reached at every azimuth by the same joint positions with A1 turned. So the
inverse kinematics is solved once per distance along the base's x axis (each solution
seeding the next), then turned to every azimuth, where the planner's collision checker says
whether the arm and tool keep clear of the cell there. A layout then costs hundreds of
inverse-kinematics solves and a few thousand collision checks, not one solve per point and
orientation (benchmarks/layout.py measures both).

`share` says how much of the orientation range reaches: the tool straight down and tilted
by TILT towards the base, away from it and to either side (the arm's kinematics alone);
shown only where the tool straight down reaches and keeps clear of the cell.
"""

import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np
from pydrake.common import Parallelism
from pydrake.math import RigidTransform, RotationMatrix

from hrc_drake.motion.model import PlanningModel
from hrc_drake.motion.options import MotionOptions
from hrc_drake.motion.planner import MotionPlanner
from hrc_drake.station import StationSpec

TILT = math.radians(30.0)
"""How far the tilted tool directions lean from straight down."""
TILTS = ((1.0, 0.0), (-1.0, 0.0), (0.0, 1.0))
"""Tilt directions in the base's (radial, tangential) frame: away, towards the base, to the
side (the other side is its mirror image: the arm is symmetric about its own plane)."""
DIRECTIONS = 1 + len(TILTS) + 1
"""Straight down and four tilts (the mirrored side counted twice)."""
RADIAL_STEP = 0.025
"""m between the distances from the base axis that are solved."""
AZIMUTH_STEP = math.radians(3.0)
"""Between the directions round the base axis that are checked for collisions (5 cm apart
at 1 m)."""
OUTER_MARGIN = 0.25
"""m beyond the variant's nominal reach that is still searched (the tool's length)."""


@dataclass(frozen=True)
class ReachMap:
    """The reach at `height` round the base axis at `centre` (x, y): cells by azimuth
    (rows) and distance (columns), their centres `azimuths` (rad, world frame) and `radii`
    (m)."""

    height: float
    linear: bool
    """Reached as a linear move's end reaches it (touching nothing, no clearance kept)."""
    centre: tuple[float, float]
    radii: np.ndarray
    azimuths: np.ndarray
    share: np.ndarray
    """(azimuth, radius): the fraction of DIRECTIONS reached; 0 where straight down fails."""
    blocked: np.ndarray
    """(azimuth, radius): the arm reaches there but it or the tool would touch the cell."""

    def cell(self, x: float, y: float) -> tuple[int, int] | None:
        """The cell (azimuth, radius index) a floor point lies in (None: beyond the map)."""
        dx, dy = x - self.centre[0], y - self.centre[1]
        k = int(math.hypot(dx, dy) // RADIAL_STEP)
        if k >= self.radii.size:
            return None
        step = self.azimuths[1] - self.azimuths[0]
        a = int(round((math.atan2(dy, dx) - self.azimuths[0]) / step)) % self.azimuths.size
        return a, k

    def share_at(self, x: float, y: float) -> float:
        cell = self.cell(x, y)
        return float(self.share[cell]) if cell is not None else 0.0


def reach_maps(
    station: StationSpec,
    options: MotionOptions,
    seed: np.random.SeedSequence,
    heights: list[tuple[float, bool]],
) -> list[ReachMap]:
    """The reach maps at `heights` ((height, linear) each) of the planner that `station`,
    `options` and `seed` make. Kept per process: a layout's maps take one to three seconds
    of inverse kinematics and collision checks, and the same scenario and seed are laid out
    again by every run directory and `layout` of them."""
    key = repr(
        (
            station.variant,
            station.tool,
            station.cell,
            station.base_pose.GetAsMatrix34().tolist(),
            station.initial_positions.tolist(),
            options,
            seed.entropy,
            seed.spawn_key,
        )
    )
    missing = [height for height in heights if (key, height) not in _REACH_MAPS]
    if missing:
        mapper = ReachMapper(MotionPlanner(station, options, seed))
        for height, linear in missing:
            _REACH_MAPS[key, (height, linear)] = mapper.reach_map(height, linear)
    return [_REACH_MAPS[key, height] for height in heights]


_REACH_MAPS: dict[tuple[str, tuple[float, bool]], ReachMap] = {}


def base_centre(station: StationSpec) -> tuple[float, float]:
    """x, y (m) of the robot's base axis on the floor."""
    return tuple(float(v) for v in station.base_pose.translation()[:2])


class ReachMapper:
    """Reach maps of one station at any heights, from one planner's inverse kinematics."""

    def __init__(self, planner: MotionPlanner):
        self.planner = planner
        self.station = planner.station
        base = self.station.base_pose
        self.centre = base_centre(self.station)
        x_axis = base.rotation().col(0)
        self.heading = math.atan2(x_axis[1], x_axis[0])
        """Azimuth of the base's x axis, along which the distances are solved."""
        count = int(math.ceil((planner.model.variant.reach + OUTER_MARGIN) / RADIAL_STEP))
        self.radii = (np.arange(count) + 0.5) * RADIAL_STEP
        turns = int(round(2 * math.pi / AZIMUTH_STEP))
        self.turns = np.arange(turns) * (2 * math.pi / turns)
        """Azimuths relative to the base's x axis."""
        self.a1_sense = _a1_sense(planner.model, self.station.initial_positions)

    @cached_property
    def touching_model(self) -> PlanningModel:
        """The planner's model without its clearance: where a linear move may end."""
        return PlanningModel(self.station, 0.0)

    def reach_map(self, height: float, linear: bool = False) -> ReachMap:
        down = self.radial_solutions(height, (0.0, 0.0))
        reached = [i for i, q in enumerate(down) if q is not None]
        within = range(reached[0], reached[-1] + 1) if reached else range(0)
        tilted = [self.radial_solutions(height, tilt, within) for tilt in TILTS]
        reached_tilts = sum(np.array([q is not None for q in s], dtype=float) for s in tilted)
        reached_tilts += np.array([q is not None for q in tilted[-1]], dtype=float)  # mirror
        clear = self._clear_of_cell(down, linear)
        kinematic = np.array([q is not None for q in down])
        share = np.where(clear, (1.0 + reached_tilts[None, :]) / DIRECTIONS, 0.0)
        return ReachMap(
            height=height,
            linear=linear,
            centre=self.centre,
            radii=self.radii,
            azimuths=self.turns + self.heading,
            share=share,
            blocked=kinematic[None, :] & ~clear,
        )

    def radial_solutions(
        self, height: float, tilt: tuple[float, float], within: range | None = None
    ) -> list:
        """Joint positions that put the tool at each distance along the base's x axis at
        `height`, its axis leaning by TILT towards `tilt` (radial, tangential), or None
        where the planner's inverse kinematics finds none (the cell ignored): from a
        distance that is reached, outwards and inwards, each solution seeding the next.
        Only the distances `within` are wanted (all if None): the line is followed no
        further than they lie, and not at all when there are none."""
        within = range(self.radii.size) if within is None else within
        solutions: list = [None] * self.radii.size
        start = self._first_reached(height, tilt) if within else None
        if start is None:
            return solutions
        k, q = start
        solutions[k] = q
        for order in (range(k + 1, within.stop), range(k - 1, within.start - 1, -1)):
            previous = q
            for i in order:
                previous = self._kinematic(self._pose(i, height, tilt), previous)
                if previous is None:
                    break
                solutions[i] = previous
        return solutions

    def _first_reached(self, height: float, tilt) -> tuple[int, np.ndarray] | None:
        """A distance the tool reaches (mid-reach first, then from the axis outwards)."""
        middle = self.radii.size // 3
        q_start = self.station.initial_positions
        for i in [middle, *range(0, self.radii.size, 4)]:
            q = self._kinematic(self._pose(i, height, tilt), q_start)
            if q is not None:
                return i, q
        return None

    def _kinematic(self, pose: RigidTransform, q_seed: np.ndarray):
        """The planner's kinematic solution (its starts and budget), tried from `q_seed`
        first."""
        planner = self.planner
        rng = np.random.default_rng(planner.seed)
        return planner.ik.kinematic_solution(pose, q_seed, True, rng, planner.options.ik_attempts)

    def _pose(self, i: int, height: float, tilt) -> RigidTransform:
        """The tool at distance i on the base's x axis, its axis tilted towards `tilt`."""
        c, s = math.cos(self.heading), math.sin(self.heading)
        radial, tangential = np.array([c, s, 0.0]), np.array([-s, c, 0.0])
        lean = math.sin(TILT) * (tilt[0] * radial + tilt[1] * tangential)
        down = -math.cos(TILT) if any(tilt) else -1.0
        axis = lean + np.array([0.0, 0.0, down])
        position = np.array([*self.centre, height]) + self.radii[i] * radial
        return RigidTransform(RotationMatrix.MakeFromOneVector(axis, 2), position)

    def _clear_of_cell(self, down: list, linear: bool) -> np.ndarray:
        """(azimuth, radius): the tool-down solution turned there keeps the planner's
        clearance to the cell (for a linear move's end: touches nothing)."""
        model = self.touching_model if linear else self.planner.model
        reached = [i for i, q in enumerate(down) if q is not None]
        clear = np.zeros((self.turns.size, self.radii.size), dtype=bool)
        if not reached:
            return clear
        configurations = [
            turned(down[i], self.a1_sense * turn, model) for turn in self.turns for i in reached
        ]
        free = model.checker.CheckConfigsCollisionFree(configurations, Parallelism(1))
        clear[:, reached] = np.array(free, dtype=bool).reshape(self.turns.size, len(reached))
        return clear


def _a1_sense(model: PlanningModel, q: np.ndarray) -> float:
    """+1 when turning A1 positively turns the arm counter-clockwise seen from above (its
    axis along the base's z), else -1."""
    q = np.array(q, dtype=float)
    q[1:] = 0.0
    q[1] = -math.pi / 4  # the arm leaning out, off the axis
    before = model.tool_pose(q).translation()
    q[0] += 0.1
    after = model.tool_pose(q).translation()
    centre = model.plant.GetFrameByName("base_link").CalcPoseInWorld(model.plant_context)
    a, b = before[:2] - centre.translation()[:2], after[:2] - centre.translation()[:2]
    return 1.0 if a[0] * b[1] - a[1] * b[0] > 0 else -1.0


def turned(q: np.ndarray, angle: float, model: PlanningModel) -> np.ndarray:
    """`q` with A1 turned by `angle`, within its limits (its range covers the circle)."""
    q = np.array(q, dtype=float)
    for a1 in (q[0] + angle, q[0] + angle - 2 * math.pi, q[0] + angle + 2 * math.pi):
        if model.lower[0] <= a1 <= model.upper[0]:
            q[0] = a1
            return q
    q[0] = math.remainder(q[0] + angle, 2 * math.pi)
    return q
