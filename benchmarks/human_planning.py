"""What planning the person's commands costs, with the IK solves run to their caps (as
before they stopped once settled) and as the person runs them, in the same process.

Each scenario's short run is simulated once and every command the person takes recorded
with the state it met (the protocol is pure, so a command can be planned again from them).
Then all of them are planned again, in turn each way, best of the repeats (this process's
CPU time): with `body.SETTLED` at 0 (no solve stops before its tolerance or its cap) and at
its value. Printed: the CPU ratio, the solves' steps each way, and how far the planned
poses (sampled over each planned activity) differ between the two.

    .venv/bin/python benchmarks/human_planning.py [--duration 30] [--repeats 3] [scenario ...]
"""

import argparse
import time

import numpy as np
from pydrake.systems.analysis import Simulator

from hrc_drake.builder import build_diagram
from hrc_drake.human import body, protocol
from hrc_drake.scenario import load_scenario

SHORT_RUNS = {"coexistence": 1, "cooperation": 0, "collaboration": 15}
"""The seed of each scenario's run (those the realism audit's fixed runs use)."""
SAMPLES = 20
"""Poses compared over each planned activity (its first HORIZON seconds: idling never ends)."""
HORIZON = 30.0


def taken_commands(name: str, duration: float) -> list[tuple]:
    """(performer, state, command, t) of every command the person handles in the run."""
    handle, taken = protocol._handle, []

    def recording(performer, state, command, t):
        taken.append((performer, state, command, t))
        return handle(performer, state, command, t)

    protocol._handle = recording
    try:
        simulator = Simulator(build_diagram(load_scenario(name, [("seed", SHORT_RUNS[name])])))
        simulator.Initialize()
        simulator.AdvanceTo(duration)
    finally:
        protocol._handle = handle
    return taken


def planned(taken: list[tuple], settled: float):
    """CPU seconds and steps of planning all `taken` commands with `body.SETTLED` at
    `settled`, and the poses of what was planned."""
    errors, steps, kept = body.HumanBody._task_errors, [0], body.SETTLED

    def counted(self, q, tasks):
        steps[0] += 1
        return errors(self, q, tasks)

    body.HumanBody._task_errors, body.SETTLED = counted, settled
    try:
        start = time.process_time()
        states = [protocol._handle(*call) for call in taken]
        cpu = time.process_time() - start
    finally:
        body.HumanBody._task_errors, body.SETTLED = errors, kept
    return cpu, steps[0], _poses(taken, states)


def _poses(taken: list[tuple], states: list) -> np.ndarray:
    """Each planned activity's poses at SAMPLES times from the command to its end."""
    poses = []
    for (performer, _, _, t), state in zip(taken, states, strict=True):
        end = min(state.activity.end, t + HORIZON)
        poses.extend(protocol.pose_at(performer, state, u) for u in np.linspace(t, end, SAMPLES))
    return np.array(poses)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("scenarios", nargs="*", default=list(SHORT_RUNS))
    parser.add_argument("--duration", type=float, default=30.0)
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args()
    for name in args.scenarios:
        taken = taken_commands(name, args.duration)
        best, results = {0.0: np.inf, body.SETTLED: np.inf}, {}
        for _ in range(args.repeats):
            for settled in best:
                cpu, *results[settled] = planned(taken, settled)
                best[settled] = min(best[settled], cpu)
        (capped, capped_poses), (stopped, stopped_poses) = results[0.0], results[body.SETTLED]
        print(
            f"{name} seed {SHORT_RUNS[name]}, {args.duration:.0f} s, {len(taken)} commands: "
            f"planning {best[0.0]:.2f} s CPU to the caps, {best[body.SETTLED]:.2f} s settled "
            f"(ratio {best[0.0] / best[body.SETTLED]:.2f}); IK steps {capped} -> {stopped}; "
            f"planned poses differ by {np.abs(capped_poses - stopped_poses).max():.1e} at most"
        )


if __name__ == "__main__":
    main()
