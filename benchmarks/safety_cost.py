"""Cost of the SafetyMonitor: real-time factor with and without it, in the same process.

1. The bundled scenarios (what users run): each scenario with the monitor measuring (SSM
   off, so the robot moves exactly as without it) against the same scenario with the
   monitor removed (`safety.enabled: false`). The robot's final state must agree, so both
   runs did the same work. The monitor's cost includes keeping the world scene (person,
   workpieces, robot mirror) posed at its rate: headless, nobody else asks for it.
2. The worst case: the bare arm on the dynamic plant under its controller, swinging A1 along
   a desired-state trajectory, with the person of the approach test walking up to 0.75 m
   from its base and away, and nothing else in Python but the monitor.

The monitor measures at its default 100 Hz. Variants alternate, best of the repeats. Times are
the process's CPU time, so that other work on the machine does not blur the comparison.

    .venv/bin/python benchmarks/safety_cost.py [--duration 30] [--repeats 2] [scenario ...]
"""

import argparse
import math
import sys
import time
from functools import partial
from pathlib import Path

import numpy as np
from pydrake.multibody.plant import AddMultibodyPlant
from pydrake.systems.analysis import Simulator
from pydrake.systems.framework import DiagramBuilder
from pydrake.systems.primitives import TrajectorySource
from pydrake.trajectories import PiecewisePolynomial

from hrc_drake.builder import build_diagram
from hrc_drake.human.body import parse_human
from hrc_drake.iisy import VARIANTS
from hrc_drake.safety.config import SafetyConfig
from hrc_drake.scenario import load_scenario
from hrc_drake.scenario.overrides import overridden
from hrc_drake.station import add_robot, model_parser
from hrc_drake.systems.robot_controller import add_robot_controller
from hrc_drake.systems.safety_monitor import add_safety_monitor

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests" / "safety"))
from approach_cell import (  # noqa: E402  (the approach test's cell)
    keep_person_out_of_contact,
    kinematic,
    walk,
)

SCENARIOS = ("coexistence", "cooperation", "collaboration")
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
        scenario.plant,
        builder,
    )
    arm = add_robot(plant, model_parser(plant), scenario.station)
    plant.Finalize()
    q0 = scenario.station.configuration("home")
    plant.SetDefaultPositions(arm, q0)
    controller = add_robot_controller(
        builder, scenario.station, plant, arm, reference_acceleration=False
    )
    desired = builder.AddSystem(TrajectorySource(swing(q0, duration)))
    builder.Connect(desired.get_output_port(), controller.GetInputPort("desired_state"))
    human_plant, human, human_pose = kinematic(
        builder, scene_graph, lambda p: parse_human(p, 1.75, 75.0)
    )
    keep_person_out_of_contact(scene_graph)
    person = builder.AddSystem(TrajectorySource(walk(0.75, 3.0, 6.0, math.radians(55))))
    builder.Connect(person.get_output_port(), human_pose.get_input_port())
    if with_monitor:
        config = SafetyConfig(ssm=False)
        add_safety_monitor(builder, scene_graph, plant, human_plant, human, config, variant.name)
    builder.ExportOutput(plant.get_state_output_port(arm), "robot_state")
    return builder.Build()


def scenario(name: str, with_monitor: bool):
    """The bundled scenario, its monitor measuring (SSM off) or removed."""
    overrides = [("safety.ssm", False), ("safety.enabled", with_monitor)]
    return build_diagram(overridden(load_scenario(name), overrides))


def simulated(diagram, duration: float) -> tuple[float, np.ndarray]:
    """CPU seconds to simulate `duration`, and the robot's final state."""
    simulator = Simulator(diagram)
    simulator.Initialize()
    start = time.process_time()
    simulator.AdvanceTo(duration)
    cpu = time.process_time() - start
    return cpu, diagram.GetOutputPort("robot_state").Eval(simulator.get_context())


def overhead(name: str, make_diagram, duration: float, repeats: int) -> None:
    """Best CPU time without and with the monitor, alternating; both runs must leave the
    robot in the same state (the same work was done)."""
    best, final = {False: math.inf, True: math.inf}, {}
    for _ in range(repeats):
        for with_monitor in best:
            cpu, final[with_monitor] = simulated(make_diagram(with_monitor), duration)
            best[with_monitor] = min(best[with_monitor], cpu)
    if not np.allclose(final[False], final[True], atol=1e-9):
        raise SystemExit(f"{name}: the robot moved differently with the monitor measuring")
    report(name, best, duration)


def report(name: str, best: dict, duration: float) -> None:
    print(
        f"{name:22s} RTF without {duration / best[False]:6.2f}  with {duration / best[True]:6.2f}"
        f"  monitor overhead {100 * (best[True] / best[False] - 1):5.1f} %",
        flush=True,
    )


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("scenarios", nargs="*", default=SCENARIOS)
    parser.add_argument("--duration", type=float, default=30.0)
    parser.add_argument("--repeats", type=int, default=2)
    args = parser.parse_args()
    for name in args.scenarios:
        overhead(name, partial(scenario, name), args.duration, args.repeats)
    cell_duration = min(args.duration, 10.0)
    overhead(
        "bare arm (worst case)", partial(cell, duration=cell_duration), cell_duration, args.repeats
    )


if __name__ == "__main__":
    main()
