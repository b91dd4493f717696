"""What one proximity measurement costs: the meter of a git revision against the working
tree's, on the same updates of one run, in one process.

A scenario runs once with the working tree's monitor. At every measurement the world scene is
posed first (one pose lookup, timed on its own: both meters share that cost), then each meter
measures the same QueryObject, in alternating order, each with its own memory from its own
last reading (this process's CPU time, garbage collection off while timed; `--repeats` above
1 takes the best of as many calls, which are then warm in the caches as a run's are not).
Every reading of the two must agree bit for bit (closest pair, distances, approach speeds,
contacts, robot and walking speeds); the run stops at the first that does not. Prints the
CPU per measurement of each and their ratio.

    .venv/bin/python benchmarks/proximity_cost.py [--old REV] [--duration 20] [scenario ...]
"""

import argparse
import gc
import subprocess
import sys
import time
import types
from pathlib import Path

import numpy as np

from hrc_drake import runner
from hrc_drake.safety import proximity
from hrc_drake.scenario import load_scenario

ROOT = Path(__file__).resolve().parents[1]
BEFORE = "25e9476"
"""main before the meter's #28 changes."""
SEEDS = {"coexistence": 0, "cooperation": 0, "collaboration": 15}


def module_at(revision: str, path: str, name: str, replacing: dict | None = None):
    """The module `path` as it was at `revision`; `replacing` stands in for the modules it
    imports while it is loaded (name: module)."""
    source = subprocess.run(
        ["git", "show", f"{revision}:{path}"], cwd=ROOT, capture_output=True, text=True, check=True
    ).stdout
    module = types.ModuleType(name)
    saved = {key: sys.modules.get(key) for key in replacing or {}}
    sys.modules.update(replacing or {})
    try:
        exec(compile(source, f"{revision}:{path}", "exec"), module.__dict__)
    finally:
        sys.modules.update(saved)
    return module


def old_meter_class(revision: str):
    geometry = module_at(revision, "hrc_drake/safety/geometry.py", "old_geometry")
    old = module_at(
        revision,
        "hrc_drake/safety/proximity.py",
        "old_proximity",
        {"hrc_drake.safety.geometry": geometry},
    )
    return old.ProximityMeter


def best_of(repeats: int, measure, *args) -> tuple[float, object]:
    """The least CPU seconds of `repeats` calls, and the reading."""
    best = float("inf")
    for _ in range(repeats):
        gc.disable()
        start = time.process_time()
        reading = measure(*args)
        best = min(best, time.process_time() - start)
        gc.enable()
    return best, reading


def pair_values(pair) -> tuple:
    if pair is None:
        return ()
    return (
        pair.region,
        pair.part,
        pair.distance,
        pair.robot_approach,
        pair.human_approach,
        pair.pinned,
        *pair.normal,
        *pair.human_point,
    )


def reading_values(reading) -> tuple:
    return (
        pair_values(reading.closest),
        tuple(pair_values(c) for c in reading.contacts),
        reading.robot_speed,
        reading.walking_speed,
        reading.person_xy,
        *(np.asarray(a).tobytes() for a in reading.robot),
    )


class Compared:
    """Wraps the working tree's `ProximityMeter.measure`: times it and the old meter's on
    the same arguments."""

    def __init__(self, old_class, repeats: int):
        self.old_class, self.repeats = old_class, repeats
        self.seconds = {"scene": 0.0, "old": 0.0, "new": 0.0}
        self.calls = 0
        self._old = {}  # new meter: (old meter, its memory, its active sets)

    def measure(self, new_measure):
        def compared(meter, query, memory, now, active, person_time=None):
            old, old_memory, actives = self._old_of(meter)
            start = time.process_time()
            query.GetPoseInWorld(meter.frames[0])  # the world scene posed, for both
            self.seconds["scene"] += time.process_time() - start
            old_active = actives.setdefault(tuple(active.robot), old.active(active.robot))
            runs = {
                "new": (new_measure, meter, query, memory, now, active, person_time),
                "old": (old.measure, query, old_memory, now, old_active, person_time),
            }
            order = ("new", "old") if self.calls % 2 else ("old", "new")
            readings = {}
            for key in order:
                seconds, readings[key] = best_of(self.repeats, *runs[key])
                self.seconds[key] += seconds
            if reading_values(readings["new"]) != reading_values(readings["old"]):
                raise SystemExit(f"the meters read differently at t = {now}")
            self._old[id(meter)] = (old, readings["old"].memory, actives)
            self.calls += 1
            return readings["new"]

        return compared

    def made(self, new_init):
        """Wraps `ProximityMeter.__init__`: an old meter made alike beside each new one."""

        def init(meter, *args, **kwargs):
            new_init(meter, *args, **kwargs)
            self._old[id(meter)] = (self.old_class(*args, **kwargs), None, {})

        return init

    def _old_of(self, meter):
        return self._old[id(meter)]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("scenarios", nargs="*", default=tuple(SEEDS))
    parser.add_argument("--old", default=BEFORE, help="git revision of the old meter")
    parser.add_argument("--duration", type=float, default=20.0)
    parser.add_argument("--repeats", type=int, default=1)
    args = parser.parse_args()
    old_class = old_meter_class(args.old)
    meter = proximity.ProximityMeter
    new_init, new_measure = meter.__init__, meter.measure
    for name in args.scenarios:
        compared = Compared(old_class, args.repeats)
        meter.__init__, meter.measure = compared.made(new_init), compared.measure(new_measure)
        try:
            scenario = load_scenario(name, [("seed", SEEDS.get(name, 0))])
            runner.run(scenario, duration=args.duration)
        finally:
            meter.__init__, meter.measure = new_init, new_measure
        per = {key: 1e6 * s / compared.calls for key, s in compared.seconds.items()}
        print(
            f"{name:14s} {compared.calls:5d} measurements, same readings; us each: "
            f"scene posed {per['scene']:6.1f}, old meter {per['old']:6.1f}, "
            f"new {per['new']:6.1f}: {per['old'] / per['new']:4.2f}x",
            flush=True,
        )


if __name__ == "__main__":
    main()
