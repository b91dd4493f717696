"""How closely the simulated robot follows RobotMotion's desired motion, per scenario.

At every simulator step (the plant's, and every event between) the tool centre point of the
plant's arm is compared with that of RobotMotion's exact desired motion (`MotionState.motion_at`,
the path evaluated at the path parameter, not what the controller was fed): the largest and
the root-mean-square distance over the run, and the same for the joints. Run it on two
versions of the code to compare their tracking: the issue's bound is 1 mm between them.

    .venv/bin/python benchmarks/tracking.py [--duration 30] [scenario ...]
"""

import argparse

import numpy as np
from pydrake.systems.analysis import Simulator
from pydrake.systems.framework import EventStatus

from hrc_drake.builder import build_diagram
from hrc_drake.scenario import load_scenario

SCENARIOS = ("coexistence", "cooperation", "collaboration")


def tracking_errors(name: str, duration: float) -> dict[str, float]:
    """Largest and RMS TCP distance (mm) and largest joint error (mrad) over the run."""
    parts = []
    diagram = build_diagram(load_scenario(name), attach=lambda _, station: parts.append(station))
    station = parts[0]
    motion, plant = station.robot_motion, station.plant
    model = motion.planner.model
    n = len(station.plant.GetPositionNames(station.arm))
    simulator = Simulator(diagram)
    tcp, joints = [], []

    def monitor(context):
        state = motion.GetMyContextFromRoot(context).get_abstract_state(0).get_value()
        desired = state.motion_at(context.get_time())[:n]
        actual = plant.GetPositions(plant.GetMyContextFromRoot(context), station.arm)
        error = model.tool_pose(actual).translation() - model.tool_pose(desired).translation()
        tcp.append(np.linalg.norm(error))
        joints.append(np.abs(actual - desired).max())
        return EventStatus.Succeeded()

    simulator.set_monitor(monitor)
    simulator.AdvanceTo(duration)
    tcp = np.array(tcp)
    return {
        "tcp_max_mm": 1e3 * tcp.max(),
        "tcp_rms_mm": 1e3 * np.sqrt(np.mean(tcp**2)),
        "joint_max_mrad": 1e3 * max(joints),
    }


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("scenarios", nargs="*", default=SCENARIOS)
    parser.add_argument("--duration", type=float, default=30.0)
    args = parser.parse_args()
    print(f"{'scenario':14s} {'TCP max mm':>11s} {'TCP rms mm':>11s} {'joint max mrad':>15s}")
    for name in args.scenarios:
        e = tracking_errors(name, args.duration)
        print(
            f"{name:14s} {e['tcp_max_mm']:11.3f} {e['tcp_rms_mm']:11.3f} "
            f"{e['joint_max_mrad']:15.3f}"
        )


if __name__ == "__main__":
    main()
