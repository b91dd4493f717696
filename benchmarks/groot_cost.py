"""Cost of serving the trees to Groot2 with no client attached, in the same process.

Each scenario is simulated unpaced twice per repeat: plain, and with `serve_groot` serving
both trees (the tick path updates the status buffer and hands over a snapshot per tick; the
server threads poll their sockets). Variants alternate, best of the repeats. Times are the
process's CPU time (the server threads included), so that other work on the machine does not
blur them.
Target: ratio (served / plain) below 1.02.

    .venv/bin/python benchmarks/groot_cost.py [--duration 20] [--repeats 3] [scenario ...]
"""

import argparse
import time

from pydrake.systems.analysis import Simulator

from hrc_drake.builder import build_diagram
from hrc_drake.groot import serve_groot
from hrc_drake.scenario import load_scenario

PORT = 21667


def simulate(scenario, duration: float, served: bool) -> float:
    """CPU seconds to simulate `duration` (the diagram is built outside the timing)."""
    diagram = build_diagram(scenario)
    simulator = Simulator(diagram)
    servers = serve_groot(diagram, PORT) if served else None
    start = time.process_time()
    simulator.AdvanceTo(duration)
    elapsed = time.process_time() - start
    if servers is not None:
        servers.close()
    return elapsed


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("scenarios", nargs="*", default=["coexistence", "collaboration"])
    parser.add_argument("--duration", type=float, default=20.0)
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args()
    for name in args.scenarios:
        scenario = load_scenario(name)
        best = {False: float("inf"), True: float("inf")}
        for _ in range(args.repeats):
            for served in (False, True):
                best[served] = min(best[served], simulate(scenario, args.duration, served))
        print(
            f"{name:14s} {args.duration:g} s simulated: plain {best[False]:.2f} s CPU, "
            f"served {best[True]:.2f} s CPU, ratio {best[True] / best[False]:.3f}"
        )


if __name__ == "__main__":
    main()
