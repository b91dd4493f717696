"""Robot motion: planning time per MoveTo, and the simulation's speed while executing.

Planning: median and 95th percentile wall time of `MotionPlanner.plan` for MoveTo over
random reachable targets (tool poses of random collision-free configurations with the tool
facing down), planned from home in the scenario's cell.

Execution: real-time factor of the robot station (plant, cell, inverse-dynamics controller,
RobotMotion) while it executes MoveTo commands back to back, against the foundation's
hold-position baseline (the same plant and controller with a constant set point), and the
station with RobotMotion holding still; all in this process, alternating repetitions.

    .venv/bin/python benchmarks/robot_motion.py [--scenario base] [--targets 50]
"""

import argparse
import statistics
import sys
import time
from pathlib import Path

import numpy as np
from pydrake.systems.analysis import Simulator

from hrc_drake.messages import FINISHED
from hrc_drake.motion.errors import PlanningFailed
from hrc_drake.motion.messages import MoveTo
from hrc_drake.motion.options import MotionOptions
from hrc_drake.motion.planner import MotionPlanner
from hrc_drake.scenario import load_scenario
from hrc_drake.seeding import stream
from hrc_drake.wiring import ROBOT_MOTION

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "motion")]
from base_scenario import bare_diagram  # noqa: E402
from motion_helpers import build_station  # noqa: E402

TOOL_FACING_DOWN = -0.5
"""Largest z component of the tool axis for a random target (tool tilted < 60° from down)."""


def random_targets(planner: MotionPlanner, count: int, seed: int = 1) -> list:
    """Tool poses of random collision-free configurations with the tool facing down."""
    rng = np.random.default_rng(seed)
    model = planner.model
    targets = []
    while len(targets) < count:
        q = rng.uniform(model.lower, model.upper)
        pose = model.tool_pose(q)
        if pose.rotation().col(2)[2] < TOOL_FACING_DOWN and model.collision_free(q):
            targets.append(pose)
    return targets


def planning_times(planner: MotionPlanner, targets: list, q_start) -> tuple[list, int]:
    times, failures = [], 0
    for seq, pose in enumerate(targets):
        start = time.perf_counter()
        try:
            planner.plan(MoveTo(seq, pose), q_start)
        except PlanningFailed:
            failures += 1
        times.append(time.perf_counter() - start)
    return times, failures


def time_hold_baseline(scenario, duration: float) -> float:
    simulator = Simulator(bare_diagram(scenario))
    start = time.perf_counter()
    simulator.AdvanceTo(duration)
    return time.perf_counter() - start


def time_station(scenario, duration: float, targets: list) -> tuple[float, int]:
    """Wall time of `duration` simulated seconds; MoveTo commands back to back if `targets`."""
    station = build_station(scenario)
    done, seq = 0, 0
    start = time.perf_counter()
    while station.context.get_time() < duration:
        if targets and (seq == 0 or station.status().results.outcome_of(seq) in FINISHED):
            done += seq > 0
            seq += 1
            station.command(MoveTo(seq, targets[seq % len(targets)]))
        station.simulator.AdvanceTo(min(duration, station.context.get_time() + 0.05))
    return time.perf_counter() - start, done


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scenario", default="base")
    parser.add_argument("--targets", type=int, default=50)
    parser.add_argument("--duration", type=float, default=10.0)
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args()
    scenario = load_scenario(args.scenario)
    planner = MotionPlanner(scenario.station, MotionOptions(), stream(scenario.seed, ROBOT_MOTION))
    home = scenario.station.initial_positions
    targets = random_targets(planner, args.targets)
    times, failures = planning_times(planner, targets, home)
    ms = 1e3 * np.array(times)
    print(
        f"MoveTo planning over {len(targets)} random reachable targets ({scenario.robot.variant}): "
        f"median {np.median(ms):.0f} ms, 95th percentile {np.percentile(ms, 95):.0f} ms, "
        f"max {ms.max():.0f} ms, {failures} failed"
    )
    walls = {
        "hold baseline (constant set point)": [],
        "RobotMotion holding": [],
        "RobotMotion executing": [],
    }
    moves = 0
    for _ in range(args.repeats):
        walls["hold baseline (constant set point)"].append(
            time_hold_baseline(scenario, args.duration)
        )
        walls["RobotMotion holding"].append(time_station(scenario, args.duration, [])[0])
        wall, moves = time_station(scenario, args.duration, targets)
        walls["RobotMotion executing"].append(wall)
    for name, wall in walls.items():
        print(f"{name:36s} real-time factor {args.duration / statistics.median(wall):6.2f}")
    print(f"({moves} moves finished in {args.duration:.0f} simulated seconds while executing)")


if __name__ == "__main__":
    main()
