"""Cost of the SafetyMonitor: real-time factor of a dynamic cell with and without it.

The cell: the iisy on the dynamic plant under its inverse-dynamics controller, swinging A1
along a desired-state trajectory, and the person of the approach test walking up to 0.75 m
from its base (close, no contact), waiting, and leaving. The monitor measures at its
default 100 Hz. Both variants run in this process, alternating, best of the repeats.

    .venv/bin/python benchmarks/safety_cost.py [--duration 10] [--repeats 3]
"""

import argparse
import math
import sys
import time
from pathlib import Path

import numpy as np
from pydrake.geometry import CollisionFilterDeclaration, GeometrySet
from pydrake.multibody.plant import AddMultibodyPlant, MultibodyPlantConfig
from pydrake.systems.analysis import Simulator
from pydrake.systems.controllers import InverseDynamicsController
from pydrake.systems.framework import DiagramBuilder
from pydrake.systems.primitives import TrajectorySource
from pydrake.trajectories import PiecewisePolynomial

from hrc_drake.human.body import parse_human
from hrc_drake.iisy import VARIANTS
from hrc_drake.safety.config import SafetyConfig
from hrc_drake.scenario import load_scenario
from hrc_drake.station_models import add_robot, make_control_plant, model_parser
from hrc_drake.systems.safety_monitor import add_safety_monitor

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests" / "safety"))
from approach_cell import kinematic, walk  # noqa: E402  (the approach test's cell)

SWING = math.radians(60)
SWING_PERIOD = 5.0


def swing(q_home: np.ndarray, duration: float) -> PiecewisePolynomial:
    """Desired state (q, v) swinging A1 sinusoidally about home."""
    times = np.arange(0.0, duration + 0.05, 0.05)
    omega = 2 * math.pi / SWING_PERIOD
    columns = []
    for t in times:
        q, v = q_home.copy(), np.zeros_like(q_home)
        q[0] += SWING * math.sin(omega * t)
        v[0] = SWING * omega * math.cos(omega * t)
        columns.append(np.concatenate([q, v]))
    return PiecewisePolynomial.CubicShapePreserving(times, np.array(columns).T)


def cell(with_monitor: bool, duration: float):
    scenario = load_scenario("base")
    variant = VARIANTS[scenario.robot.variant]
    builder = DiagramBuilder()
    plant, scene_graph = AddMultibodyPlant(
        MultibodyPlantConfig(time_step=scenario.time_step, discrete_contact_approximation="sap"),
        builder,
    )
    arm = add_robot(plant, model_parser(plant), scenario.robot)
    plant.Finalize()
    q0 = scenario.configuration("home")
    plant.SetDefaultPositions(arm, q0)
    controller = builder.AddSystem(
        InverseDynamicsController(
            make_control_plant(scenario), variant.kp, variant.ki, variant.kd, False
        )
    )
    desired = builder.AddSystem(TrajectorySource(swing(q0, duration)))
    builder.Connect(plant.get_state_output_port(arm), controller.get_input_port_estimated_state())
    builder.Connect(desired.get_output_port(), controller.get_input_port_desired_state())
    builder.Connect(controller.get_output_port_control(), plant.get_actuation_input_port(arm))
    human_plant, human, human_pose = kinematic(
        builder, scene_graph, lambda p: parse_human(p, 1.75, 75.0)
    )
    _keep_person_out_of_contact(scene_graph, human_plant)
    person = builder.AddSystem(TrajectorySource(walk(0.75, 3.0, 6.0, math.radians(55))))
    builder.Connect(person.get_output_port(), human_pose.get_input_port())
    if with_monitor:
        config = SafetyConfig(ssm=False)
        add_safety_monitor(builder, scene_graph, plant, human_plant, human, config, variant.name)
    return builder.Build()


def _keep_person_out_of_contact(scene_graph, human_plant) -> None:
    """The dynamic plant must not see the kinematic person's geometry in contact."""
    inspector = scene_graph.model_inspector()
    person = GeometrySet(
        [g for g in inspector.GetAllGeometryIds() if inspector.GetName(g).startswith("human::")]
    )
    everything = GeometrySet(inspector.GetAllGeometryIds())
    scene_graph.collision_filter_manager().Apply(
        CollisionFilterDeclaration().ExcludeBetween(person, everything)
    )


def wall_time(with_monitor: bool, duration: float) -> float:
    simulator = Simulator(cell(with_monitor, duration))
    simulator.Initialize()
    start = time.perf_counter()
    simulator.AdvanceTo(duration)
    return time.perf_counter() - start


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--duration", type=float, default=10.0)
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args()
    best = {False: math.inf, True: math.inf}
    for _ in range(args.repeats):
        for with_monitor in best:
            best[with_monitor] = min(best[with_monitor], wall_time(with_monitor, args.duration))
    for with_monitor, wall in best.items():
        name = "with monitor" if with_monitor else "without monitor"
        print(f"{name:16s} real-time factor {args.duration / wall:6.2f}  ({wall:.2f} s wall)")
    print(f"monitor overhead: {100 * (best[True] / best[False] - 1):.1f} % of wall time")


if __name__ == "__main__":
    main()
