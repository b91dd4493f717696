"""Cost of recording the replay, and its size: a scenario simulated without Meshcat against
the same run drawn in Meshcat and sampled by the ReplayRecorder, in this process, alternating
repetitions so machine noise hits both alike. Prints the CPU time of each and their ratio
(1.0 = recording is free), then the size of replay.html: in all, per simulated minute, and the
animation's share per simulated minute (the rest is Meshcat's viewer and the models).

    .venv/bin/python benchmarks/replay.py [--scenario collaboration] [--duration 30] [--repeats 2]
"""

import argparse
import statistics
import tempfile
import time
from pathlib import Path

from pydrake.geometry import Meshcat
from pydrake.systems.analysis import Simulator

from hrc_drake.builder import build_diagram
from hrc_drake.evaluation.recording import meshcat_path
from hrc_drake.evaluation.replay import animation_message, write_replay
from hrc_drake.scenario import load_scenario
from hrc_drake.wiring import HUMAN_MODEL, VISUAL_PREFIX


def simulate(scenario, duration: float, meshcat: Meshcat | None):
    """CPU seconds of the run, and the station's parts (its recorder holds the replay)."""
    parts = []
    diagram = build_diagram(scenario, meshcat, attach=lambda _, station: parts.append(station))
    start = time.process_time()
    Simulator(diagram).AdvanceTo(duration)
    return time.process_time() - start, parts[0]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scenario", default="collaboration")
    parser.add_argument("--duration", type=float, default=30.0)
    parser.add_argument("--repeats", type=int, default=2)
    args = parser.parse_args()
    scenario = load_scenario(args.scenario)
    plain, recorded = [], []
    for _ in range(args.repeats):
        plain.append(simulate(scenario, args.duration, None)[0])
        meshcat = Meshcat()
        seconds, station = simulate(scenario, args.duration, meshcat)
        recorded.append(seconds)
    print(f"{args.scenario}, {args.duration:g} s simulated, best of {args.repeats}:")
    print(f"  without Meshcat   {min(plain):7.2f} s CPU (median {statistics.median(plain):.2f})")
    print(
        f"  drawn + recorded  {min(recorded):7.2f} s CPU (median {statistics.median(recorded):.2f})"
    )
    print(f"  ratio             {min(recorded) / min(plain):7.3f}")
    recording = station.recorder.recording
    with tempfile.TemporaryDirectory() as folder:
        path = write_replay(
            Path(folder) / "replay.html",
            meshcat,
            recording,
            meshcat_path(VISUAL_PREFIX, HUMAN_MODEL),
        )
        megabytes = path.stat().st_size / 1e6
    animation = len(animation_message(recording)) * 4 / 3 / 1e6  # base64 in the page
    minutes = args.duration / 60
    print(f"  replay.html       {megabytes:7.2f} MB, {megabytes / minutes:.2f} MB per minute")
    print(f"  animation         {animation:7.2f} MB, {animation / minutes:.2f} MB per minute")


if __name__ == "__main__":
    main()
