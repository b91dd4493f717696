"""What each Python system costs a plant step when it does nothing, with the plant's output
ports sampled and live (`MultibodyPlantConfig.use_sampled_output_ports`).

A plant that samples its outputs steps as an unrestricted update, and after every
unrestricted update Drake's simulator asks each system for its witness functions: a call
into Python for every Python LeafSystem, at every plant step, however idle the system is.
With live output ports the plant steps as a discrete update and the question is not asked.
The arm and the scenario's cell under the inverse-dynamics controller, with N idle Python
systems beside them (no ports, no events), simulated in turns in this process (CPU time);
prints the cost per plant step and what each Python system adds to it.

    .venv/bin/python benchmarks/python_systems.py [--duration 6] [--systems 0 10 30] [scenario]
"""

import argparse
import sys
import time
from pathlib import Path

from pydrake.systems.analysis import Simulator
from pydrake.systems.framework import DiagramBuilder, LeafSystem

from hrc_drake.scenario import load_scenario, overridden

sys.path.insert(0, str(Path(__file__).resolve().parent))
from base_scenario import bare_diagram  # noqa: E402

SLICE = 0.5
"""Simulated seconds each simulator advances in its turn."""


class Idle(LeafSystem):
    """A Python system with nothing to do."""


def simulator(scenario, idle: int) -> Simulator:
    builder = DiagramBuilder()
    builder.AddSystem(bare_diagram(scenario, cell=True))
    for _ in range(idle):
        builder.AddSystem(Idle())
    simulator = Simulator(builder.Build())
    simulator.Initialize()
    return simulator


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--duration", type=float, default=6.0)
    parser.add_argument("--systems", type=int, nargs="+", default=[0, 10, 30])
    parser.add_argument("scenario", nargs="?", default="coexistence")
    args = parser.parse_args()
    base = load_scenario(args.scenario)
    cases = {
        (sampled, idle): simulator(
            overridden(base, [("plant.use_sampled_output_ports", sampled)]), idle
        )
        for sampled in (True, False)
        for idle in args.systems
    }
    spent = dict.fromkeys(cases, 0.0)
    t = 0.0
    while t < args.duration:
        t = min(args.duration, t + SLICE)
        for case, sim in cases.items():
            start = time.process_time()
            sim.AdvanceTo(t)
            spent[case] += time.process_time() - start
    steps = args.duration / base.plant.time_step
    fewest = min(args.systems)
    print(f"{'output ports':>12} {'Python systems':>15} {'us/step':>8} {'us/step/system':>15}")
    for (sampled, idle), seconds in spent.items():
        per_step = seconds / steps * 1e6
        alone = spent[(sampled, fewest)] / steps * 1e6
        each = (per_step - alone) / (idle - fewest) if idle != fewest else float("nan")
        mode = "sampled" if sampled else "live"
        print(f"{mode:>12} {idle:>15} {per_step:>8.1f} {each:>15.2f}")


if __name__ == "__main__":
    main()
