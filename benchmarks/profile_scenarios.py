"""Where a scenario's time goes: each part's share of a profiled run, as a sweep runs it.

Each scenario runs once under cProfile (`hrc_drake.runner.run` without a run directory, as
a sweep runs it: no replay recorder; the simulation only, not building nor reporting).
Every function's own time is charged to the system whose callback it ran for: a function
of a `systems/` file (the runner's state-change sampler among them: "loggers") is that
system's; any other (library code, numpy, Drake's Python bindings, C++ called from Python
such as a QueryObject lookup) is shared among its callers' systems in proportion to the
time they spent in it. What the simulator spends in C++ outside any Python callback (the
plant, the controller, SceneGraph, the C++ loggers, event dispatch) is "Drake (C++)".
Profiling inflates Python's share (every Python call is timed); the shares rank the parts,
`benchmarks/scenarios.py` measures the cost.

    .venv/bin/python benchmarks/profile_scenarios.py [--duration 20] [--top 0] [scenario ...]
"""

import argparse
import cProfile
import pstats
from collections import defaultdict
from pathlib import Path

from hrc_drake import runner
from hrc_drake.scenario import load_scenario

SCENARIOS = ("coexistence", "cooperation", "collaboration")
DRAKE = "Drake (C++)"
PARTS = {
    "robot_motion.py": "RobotMotion",
    "robot_controller.py": "RobotController",
    "safety_monitor.py": "SafetyMonitor",
    "workpieces.py": "Workpieces",
    "human_actor.py": "HumanActor",
    "behavior_tree.py": "trees",
    "realism_audit.py": "realism audit",
    "state_changes.py": "loggers",
}
SYSTEMS = Path(__file__).resolve().parent.parent / "systems"


ADVANCE = (runner.__file__, runner._advance.__code__.co_firstlineno, runner._advance.__name__)
"""The runner's loop around Simulator.AdvanceTo: the profiled simulation's root."""


def is_simulation(function) -> bool:
    """Drake's Simulator.AdvanceTo, or the runner's loop that calls it: cProfile names a C++
    method by its binding where it sees the call (Python 3.11), and charges its time to the
    caller where it does not (3.12 with newer Drake)."""
    return function == ADVANCE or (function[0] == "~" and function[2].endswith(".AdvanceTo>"))


def own_part(function) -> str | None:
    """The part a function belongs to by its file, None when it serves whoever calls it."""
    filename, _, name = function
    path = Path(filename)
    if is_simulation(function):
        return DRAKE
    if path.parent == SYSTEMS:
        return PARTS.get(path.name, path.stem)
    return None


def shares(stats: pstats.Stats) -> tuple[dict[str, float], dict[str, dict]]:
    """Seconds per part, and per part the functions whose own time is charged to it."""
    table = stats.stats
    memo: dict = {}

    def parts_of(function, seen=frozenset()) -> dict[str, float]:
        """Fractions of `function`'s time per part (its callers' parts, by time); empty
        when every caller is already on the walk (recursion: the walk's other callers
        carry it)."""
        if function in memo:
            return memo[function]
        part = own_part(function)
        if part is not None:
            return {part: 1.0}
        callers = table[function][4] if function in table else {}
        found = [
            (weight, parts_of(caller, seen | {function}))
            for caller, (_, _, _, weight) in callers.items()
            if caller not in seen
        ]
        found = [(weight, parts) for weight, parts in found if parts and weight > 0.0]
        total = sum(weight for weight, _ in found)
        result = defaultdict(float)
        for weight, parts in found:
            for name, fraction in parts.items():
                result[name] += fraction * weight / total
        if not seen:
            memo[function] = dict(result) or {"other": 1.0}
        return dict(result) if seen else memo[function]

    seconds: dict[str, float] = defaultdict(float)
    functions: dict[str, dict] = defaultdict(lambda: defaultdict(float))
    for function, (_, _, own, _, callers) in table.items():
        if own_part(function) is not None:
            charged = {own_part(function): own}
        else:
            charged = defaultdict(float)
            for caller, (_, _, tt, _) in callers.items():
                for name, fraction in parts_of(caller).items():
                    charged[name] += tt * fraction
        for name, t in charged.items():
            seconds[name] += t
            functions[name][pstats.func_std_string(function)] += t
    return dict(seconds), functions


def load_kernels(name: str) -> None:
    """Runs `name` briefly, unprofiled: numba loads (or compiles) the safety monitor's
    kernels at their first call, a one-off a sweep worker pays once; profiled, numba's
    recursive call graph would also make the shares' walk take hours."""
    runner.run(load_scenario(name), duration=0.05)


def profile(name: str, duration: float) -> pstats.Stats:
    """Profiles the simulation only (not building the diagram nor the report)."""
    profiler = cProfile.Profile()
    advance = runner._advance

    def profiled_advance(*args):
        profiler.runcall(advance, *args)

    runner._advance = profiled_advance
    try:
        runner.run(load_scenario(name), duration=duration)
    finally:
        runner._advance = advance
    return pstats.Stats(profiler)


def simulation_seconds(stats: pstats.Stats) -> float:
    """The whole simulation: the runner's loop, all it called included."""
    return stats.stats[ADVANCE][3]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("scenarios", nargs="*", default=SCENARIOS)
    parser.add_argument("--duration", type=float, default=20.0)
    parser.add_argument("--top", type=int, default=0, help="functions shown per part")
    args = parser.parse_args()
    load_kernels(args.scenarios[0])
    for name in args.scenarios:
        stats = profile(name, args.duration)
        seconds, functions = shares(stats)
        total = simulation_seconds(stats)
        print(f"\n{name} ({args.duration:g} s simulated, {total:.1f} s profiled in AdvanceTo)")
        for part, t in sorted(seconds.items(), key=lambda item: -item[1]):
            if t < 0.001 * total:
                continue
            print(f"  {part:16s} {100 * t / total:5.1f} %  {t:7.2f} s")
            ranked = sorted(functions[part].items(), key=lambda item: -item[1])
            for function, own in ranked[: args.top]:
                print(f"      {own:7.2f} s  {function}")


if __name__ == "__main__":
    main()
