"""What the SafetyMonitor's measurements cost: the monitor of a git revision against the
working tree's, on the same run, in one process.

Each scenario is built twice, once with the revision's monitor (its `systems/safety_monitor.py`,
`hrc_drake/safety/proximity.py` and `geometry.py`) and once with the working tree's, and
the two simulations advance in turns of `--turn` simulated seconds. Timed by this
process's CPU time: every monitor update, with all it makes Drake compute (posing a scene,
the pose sources' kinematics, the objects' poses, the judge), and each simulation as a
whole. The two monitors' `safety_signals` must agree at every update (a logger at the
monitor's period) bit for bit, or within `--tolerance` (compiled kernels may round the last
bit of a float otherwise), or the benchmark stops. Prints, per scenario, the CPU per
measuring update of each monitor and the ratio, the whole simulation's, and the largest
difference of the signals.

    .venv/bin/python benchmarks/safety_measure.py [--old REV] [--duration 20]
        [--tolerance 1e-12] [scenario ...]
"""

import argparse
import math
import sys
import time
from collections import defaultdict
from pathlib import Path

import numpy as np
from pydrake.systems.analysis import Simulator
from pydrake.systems.framework import EventStatus
from pydrake.systems.primitives import LogVectorOutput

from hrc_drake import builder as station_builder
from hrc_drake.builder import build_diagram
from hrc_drake.scenario import load_scenario
from hrc_drake.systems import safety_monitor

sys.path.insert(0, str(Path(__file__).resolve().parent))
from revision import module_at  # noqa: E402

BEFORE = "25e9476"
"""main before the monitor's #28 changes of session 14."""
SEEDS = {"coexistence": 0, "cooperation": 0, "collaboration": 15}


def monitor_at(revision: str):
    """systems/safety_monitor.py at `revision`, with that revision's meter."""
    geometry = module_at(revision, "hrc_drake/safety/geometry.py", "old_geometry")
    replacing = {"hrc_drake.safety.geometry": geometry}
    proximity = module_at(revision, "hrc_drake/safety/proximity.py", "old_proximity", replacing)
    replacing["hrc_drake.safety.proximity"] = proximity
    return module_at(revision, "systems/safety_monitor.py", "old_safety_monitor", replacing)


class Timed:
    """Times the `_update` of each monitor class given, inclusive, and counts those that
    measured (did not return DidNothing); the first measuring update apart (`first`): it
    pays what a process pays once, such as loading (or compiling) numba's kernels."""

    def __init__(self, classes: dict):
        self.seconds, self.measured = defaultdict(float), defaultdict(int)
        self.first = {}
        self._originals = {key: cls._update for key, cls in classes.items()}
        self._classes = classes

    def __enter__(self):
        for key, cls in self._classes.items():
            cls._update = self._timed(key, self._originals[key])
        return self

    def __exit__(self, *exc):
        for key, cls in self._classes.items():
            cls._update = self._originals[key]

    def _timed(self, key: str, update):
        def timed(monitor, context, state):
            start = time.process_time()
            status = update(monitor, context, state)
            seconds = time.process_time() - start
            if status.severity() == EventStatus.Severity.kDidNothing:
                self.seconds[key] += seconds
            elif key not in self.first:
                self.first[key] = seconds
            else:
                self.seconds[key] += seconds
                self.measured[key] += 1
            return status

        return timed


def built(name: str, add_monitor):
    """The scenario's diagram with `add_monitor` as its `add_safety_monitor`, and a logger of
    the monitor's signals."""
    scenario = load_scenario(name, [("seed", SEEDS.get(name, 0))])
    logs = {}

    def attach(builder, station):
        port = station.safety.GetOutputPort("safety_signals")
        logs["signals"] = LogVectorOutput(port, builder, scenario.safety.period)

    kept = station_builder.add_safety_monitor
    station_builder.add_safety_monitor = add_monitor
    try:
        diagram = build_diagram(scenario, attach=attach)
    finally:
        station_builder.add_safety_monitor = kept
    simulator = Simulator(diagram)
    simulator.Initialize()
    return simulator, logs["signals"]


def largest_difference(old: np.ndarray, new: np.ndarray) -> tuple[float, int]:
    """The largest absolute difference of two logs (signals × updates) and its signal;
    NaN where only one of them is NaN."""
    difference = np.abs(old - new)
    difference[np.isnan(old) & np.isnan(new)] = 0.0
    difference[np.isnan(old) != np.isnan(new)] = np.nan
    if np.isnan(difference).any():
        return math.nan, int(np.nonzero(np.isnan(difference))[0][0])
    signal = int(np.unravel_index(np.argmax(difference), difference.shape)[0])
    return float(difference.max()), signal


def compare(name: str, old, duration: float, turn: float, tolerance: float) -> None:
    total = defaultdict(float)
    classes = {"old": old.SafetyMonitor, "new": safety_monitor.SafetyMonitor}
    with Timed(classes) as timed:  # before the monitors declare their updates
        runs = {
            "old": built(name, old.add_safety_monitor),
            "new": built(name, safety_monitor.add_safety_monitor),
        }
        now = 0.0
        while now < duration - 1e-9:
            now = min(now + turn, duration)
            for key, (simulator, _) in runs.items():
                start = time.process_time()
                simulator.AdvanceTo(now)
                total[key] += time.process_time() - start
    signals = {
        key: logger.FindLog(simulator.get_context()).data()
        for key, (simulator, logger) in runs.items()
    }
    difference, signal = largest_difference(signals["old"], signals["new"])
    if not difference <= tolerance:
        raise SystemExit(f"{name}: the monitors' signal {signal} differs by {difference}")
    per = {key: 1e6 * timed.seconds[key] / timed.measured[key] for key in runs}
    print(
        f"{name:14s} {timed.measured['new']:5d} measurements, signals differ by at most "
        f"{difference:.1e} (signal {signal}). Per measuring "
        f"update: old {per['old']:6.1f} us, new {per['new']:6.1f} us "
        f"({per['old'] / per['new']:4.2f}x); the first: old {1e3 * timed.first['old']:5.1f} ms, "
        f"new {1e3 * timed.first['new']:5.1f} ms; whole run: old {total['old']:5.2f} s, "
        f"new {total['new']:5.2f} s CPU ({total['old'] / total['new']:4.2f}x)",
        flush=True,
    )


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("scenarios", nargs="*", default=tuple(SEEDS))
    parser.add_argument("--old", default=BEFORE, help="git revision of the old monitor")
    parser.add_argument("--duration", type=float, default=20.0)
    parser.add_argument("--turn", type=float, default=0.5, help="simulated seconds per turn")
    parser.add_argument(
        "--tolerance", type=float, default=1e-12, help="of the signals (m, m/s; 0: bit for bit)"
    )
    args = parser.parse_args()
    old = monitor_at(args.old)
    for name in args.scenarios:
        compare(name, old, args.duration, args.turn, args.tolerance)


if __name__ == "__main__":
    main()
