"""What the dynamic plant's geometry costs: the bare robot replaying a scenario's desired
motion with and without the cell and contact geometry, in the same process.

For each scenario (as in `benchmarks/scenarios.py`: the desired state of a full run
replayed on the plant and its inverse-dynamics controller), these plants advance in turns,
timed by this process's CPU time, each printed against `bare` (the benchmarks' baseline:
the arm and tool with their collision geometry in a SceneGraph):

- `cell`: with the scenario's static cell, as the station's dynamic plant had it before
  it dropped its geometry (every pair of robot and cell a contact candidate);
- `cell, filtered`: the same with every pair filtered out (CollisionFilterDeclaration):
  no pair is checked, but SceneGraph still poses the robot's geometry at every step;
- `station`: the station's dynamic plant now (`station.make_dynamic_plant`: the arm and
  tool, no cell, no SceneGraph).

    .venv/bin/python benchmarks/plant_contact.py [--duration 20] [scenario ...]
"""

import argparse
import sys
import time
from pathlib import Path

from pydrake.geometry import CollisionFilterDeclaration, GeometrySet
from pydrake.multibody.plant import AddMultibodyPlant
from pydrake.systems.analysis import Simulator
from pydrake.systems.framework import DiagramBuilder
from pydrake.systems.primitives import TrajectorySource

from hrc_drake.scenario import load_scenario
from hrc_drake.station import add_station_models, make_dynamic_plant, model_parser
from hrc_drake.systems.robot_controller import add_robot_controller

sys.path.insert(0, str(Path(__file__).resolve().parent))
from base_scenario import bare_diagram  # noqa: E402

from scenarios import SCENARIOS, desired_motion, timed_in_turns  # noqa: E402


def cell_plant(builder, scenario, filtered: bool):
    """The arm, tool and cell with their geometry; with `filtered`, no pair checked."""
    plant, scene_graph = AddMultibodyPlant(scenario.plant, builder)
    arm, _ = add_station_models(plant, model_parser(plant), scenario.station)
    plant.Finalize()
    plant.SetDefaultPositions(arm, scenario.station.initial_positions)
    if filtered:
        everything = GeometrySet(scene_graph.model_inspector().GetAllGeometryIds())
        scene_graph.collision_filter_manager().Apply(
            CollisionFilterDeclaration().ExcludeWithin(everything)
        )
    return plant, arm


def station_plant(builder, scenario):
    plant, arm = make_dynamic_plant(scenario.station, scenario.plant)
    builder.AddSystem(plant)
    return plant, arm


def replay(scenario, desired, add_plant) -> Simulator:
    """`desired` replayed on the plant `add_plant(builder, scenario)` adds, under the
    station's controller."""
    builder = DiagramBuilder()
    plant, arm = add_plant(builder, scenario)
    controller = add_robot_controller(
        builder, scenario.station, plant, arm, reference_acceleration=False
    )
    source = builder.AddSystem(TrajectorySource(desired))
    builder.Connect(source.get_output_port(), controller.GetInputPort("desired_state"))
    simulator = Simulator(builder.Build())
    simulator.Initialize()
    return simulator


PLANTS = {
    "cell": lambda builder, scenario: cell_plant(builder, scenario, False),
    "cell, filtered": lambda builder, scenario: cell_plant(builder, scenario, True),
    "station": station_plant,
}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("scenarios", nargs="*", default=SCENARIOS)
    parser.add_argument("--duration", type=float, default=20.0)
    args = parser.parse_args()
    print(f"{'scenario':14s} " + " ".join(f"{name + ' / bare':>22s}" for name in PLANTS))
    for name in args.scenarios:
        scenario = load_scenario(name)
        desired = desired_motion(scenario, args.duration)
        bare = Simulator(bare_diagram(scenario, TrajectorySource(desired)))
        bare.Initialize()
        others = [replay(scenario, desired, add_plant) for add_plant in PLANTS.values()]
        times = timed_in_turns([bare, *others], args.duration, time.process_time)
        print(f"{name:14s} " + " ".join(f"{t / times[0]:22.3f}" for t in times[1:]))


if __name__ == "__main__":
    main()
