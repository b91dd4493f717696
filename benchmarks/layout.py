"""Cost of the layout view's reach map against asking the planner at every point: one
height of a scenario mapped by ReachMapper (the planner's inverse kinematics along one line
from the base, turned about the base axis, collision checks per cell) against the planner's
own reach check (hrc_drake.motion.reach, as validate asks it) at a sample of the same
cells (its yes or no, without the words), per cell and scaled to the map's cells and
orientations. CPU time, this process.
Also prints how often the map and the planner agree on the sampled cells.

    .venv/bin/python benchmarks/layout.py [--scenario collaboration] [--samples 40]
"""

import argparse
import time

import numpy as np
from pydrake.math import RigidTransform

from hrc_drake.layout.cell import reach_heights, robot_targets
from hrc_drake.layout.reach_map import DIRECTIONS, ReachMapper
from hrc_drake.motion.planner import MotionPlanner
from hrc_drake.nodes.robot import TOOL_DOWN
from hrc_drake.scenario import load_scenario
from hrc_drake.seeding import stream
from hrc_drake.wiring import ROBOT_MOTION


def reaches(planner: MotionPlanner, pose: RigidTransform, linear: bool) -> bool:
    """The planner's yes or no, as validate's reach check asks it (its random starts)."""
    rng = np.random.default_rng(planner.seed)
    q_start = planner.station.initial_positions
    attempts = planner.options.ik_attempts
    return planner.ik.reaches(pose, q_start, True, rng, attempts, clearance=not linear)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scenario", default="collaboration")
    parser.add_argument("--samples", type=int, default=40)
    args = parser.parse_args()
    scenario = load_scenario(args.scenario)
    planner = MotionPlanner(
        scenario.station, scenario.robot.motion, stream(scenario.seed, ROBOT_MOTION)
    )
    mapper = ReachMapper(planner)
    height, linear = reach_heights(robot_targets(scenario))[0]
    start = time.process_time()
    reach = mapper.reach_map(height, linear)
    mapped = time.process_time() - start
    rng = np.random.default_rng(0)
    cells = [
        (int(rng.integers(reach.azimuths.size)), int(rng.integers(reach.radii.size)))
        for _ in range(args.samples)
    ]
    agree = 0
    start = time.process_time()
    for a, k in cells:
        azimuth, radius = reach.azimuths[a], reach.radii[k]
        xy = np.array(reach.centre) + radius * np.array([np.cos(azimuth), np.sin(azimuth)])
        pose = RigidTransform(TOOL_DOWN, [*xy, height])
        agree += reaches(planner, pose, linear) == (reach.share[a, k] > 0)
    asked = (time.process_time() - start) / len(cells)
    every_cell = asked * reach.share.size * DIRECTIONS
    print(f"{args.scenario}, tool down at z = {height:.3f} m, {reach.share.size} cells:")
    print(f"  reach map                 {mapped:8.2f} s CPU")
    print(f"  planner per cell          {asked:8.3f} s CPU (mean of {len(cells)})")
    print(f"  planner, every cell x {DIRECTIONS}   {every_cell:8.1f} s CPU (scaled)")
    print(f"  ratio                     {every_cell / mapped:8.1f}")
    print(f"  map and planner agree     {agree} of {len(cells)} cells")


if __name__ == "__main__":
    main()
