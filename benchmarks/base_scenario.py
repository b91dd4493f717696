"""Cost of the scenario machinery: the base scenario against a bare plant + controller.

Both simulate the same arm holding its home pose for the same time, in this process,
alternating repetitions so machine noise hits both alike. Prints the real-time factor of
each, the cost per plant step, and the ratio (base / bare; 1.0 = no overhead).

    .venv/bin/python benchmarks/base_scenario.py [--duration 10] [--repeats 3]
"""

import argparse
import statistics
import time

import numpy as np
from pydrake.multibody.parsing import Parser
from pydrake.multibody.plant import AddMultibodyPlant
from pydrake.systems.analysis import Simulator
from pydrake.systems.framework import DiagramBuilder
from pydrake.systems.primitives import ConstantVectorSource

from hrc_drake.paths import add_model_package
from hrc_drake.runner import run
from hrc_drake.scenario import load_scenario
from hrc_drake.station import add_robot, add_station_models, model_parser
from hrc_drake.systems.robot_controller import add_robot_controller


def bare_diagram(scenario, desired=None, cell: bool = False):
    """The arm with its tool, an inverse-dynamics controller and a desired-state source (by
    default a constant set point at the initial configuration): no cell (unless `cell`: the
    scenario's static cell in the plant, as the station's dynamic plant has it), no person,
    no trees, no monitor, no visualizer, no loggers, no runner."""
    q0 = scenario.station.initial_positions
    if desired is None:
        desired = ConstantVectorSource(np.concatenate([q0, 0 * q0]))
    builder = DiagramBuilder()
    plant, _ = AddMultibodyPlant(
        scenario.plant,
        builder,
    )
    if cell:
        arm, _ = add_station_models(plant, model_parser(plant), scenario.station)
    else:
        parser = Parser(plant)
        add_model_package(parser.package_map())
        arm = add_robot(plant, parser, scenario.station)
    plant.Finalize()
    plant.SetDefaultPositions(arm, q0)
    controller = add_robot_controller(
        builder, scenario.station, plant, arm, reference_acceleration=False
    )
    hold = builder.AddSystem(desired)
    builder.Connect(hold.get_output_port(), controller.GetInputPort("desired_state"))
    return builder.Build()


def time_bare(scenario, duration: float, desired=None) -> float:
    simulator = Simulator(bare_diagram(scenario, desired))
    start = time.perf_counter()
    simulator.AdvanceTo(duration)
    return time.perf_counter() - start


def time_base(scenario, duration: float) -> float:
    return run(scenario, duration=duration).wall_time


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--duration", type=float, default=10.0)
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args()
    scenario = load_scenario("base")
    steps = args.duration / scenario.plant.time_step
    bare, base = [], []
    for _ in range(args.repeats):
        bare.append(time_bare(scenario, args.duration))
        base.append(time_base(scenario, args.duration))
    for name, times in (("bare plant + controller", bare), ("base scenario", base)):
        wall = statistics.median(times)
        print(
            f"{name:24s} real-time factor {args.duration / wall:6.2f}   "
            f"{1e6 * wall / steps:7.1f} µs per plant step"
        )
    print(f"ratio base / bare: {statistics.median(base) / statistics.median(bare):.3f}")


if __name__ == "__main__":
    main()
