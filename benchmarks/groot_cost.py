"""Cost of serving the trees to Groot2 with no client attached, in the same process.

Each scenario is simulated unpaced twice per repeat: plain, and with `serve_groot` serving
both trees. Variants alternate, best of the repeats; times are the process's CPU time (the
server threads included). On a shared machine that ratio moves by several percent from run
to run, so the served run also measures its own parts directly:

- the tick path: the time spent in the servers' observer and tick-boundary calls (status
  buffer updates, the snapshot handed over per tick), timed around each call;
- the server threads: their CPU time (polling the sockets, the heartbeat).

Both are printed as a share of the plain run. Target: under 2 % together.

    .venv/bin/python benchmarks/groot_cost.py [--duration 20] [--repeats 3] [scenario ...]
"""

import argparse
import time
from functools import wraps

from pydrake.systems.analysis import Simulator

from hrc_drake.builder import build_diagram
from hrc_drake.groot import serve_groot
from hrc_drake.scenario import load_scenario

PORT = 21667
TICK_PATH = ("on_transition", "before_tick", "after_tick")


def timed(method, spent: list[float]):
    @wraps(method)
    def call(*args):
        start = time.perf_counter()
        try:
            return method(*args)
        finally:
            spent[0] += time.perf_counter() - start

    return call


def thread_cpu(thread) -> float:
    return time.clock_gettime(time.pthread_getcpuclockid(thread.ident))


def simulate(scenario, duration: float, served: bool) -> tuple[float, float, float]:
    """CPU seconds of the run, seconds in the tick path, CPU seconds of the server threads
    (the diagram is built outside the timing)."""
    diagram = build_diagram(scenario)
    simulator = Simulator(diagram)
    servers = serve_groot(diagram, PORT).servers.values() if served else ()
    spent = [0.0]
    for server in servers:
        for name in TICK_PATH:
            setattr(server, name, timed(getattr(server, name), spent))
    start = time.process_time()
    simulator.AdvanceTo(duration)
    elapsed = time.process_time() - start
    threads = sum(thread_cpu(server._thread) for server in servers)  # noqa: SLF001
    for server in servers:
        server.close()
    return elapsed, spent[0], threads


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("scenarios", nargs="*", default=["coexistence", "collaboration"])
    parser.add_argument("--duration", type=float, default=20.0)
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args()
    for name in args.scenarios:
        scenario = load_scenario(name)
        plain, served = float("inf"), (float("inf"), 0.0, 0.0)
        for _ in range(args.repeats):
            plain = min(plain, simulate(scenario, args.duration, False)[0])
            served = min(served, simulate(scenario, args.duration, True))
        total, tick_path, threads = served
        print(
            f"{name:14s} {args.duration:g} s simulated: plain {plain:.2f} s CPU, served "
            f"{total:.2f} s CPU (ratio {total / plain:.3f}); tick path {tick_path * 1e3:.0f} ms "
            f"({100 * tick_path / plain:.2f} %), server threads {threads * 1e3:.0f} ms "
            f"({100 * threads / plain:.2f} %)"
        )


if __name__ == "__main__":
    main()
