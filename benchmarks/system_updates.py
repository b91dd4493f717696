"""How often each Python system of a scenario's run is called, and what each call costs.

A scenario runs once as a sweep runs it (`hrc_drake.runner.run`, no run directory); every
Python callback of the station's systems (periodic updates, publishes and the outputs that
Python computes) is timed by this process's CPU time, each without the timed callbacks it
calls in turn (an update's query evaluates the objects' poses: that time is the objects').
Prints, per callback: calls per simulated second, the share of them that did something (an
update that returns `DidNothing` changes no state), CPU per call, and its share of the
run's CPU time. What is left (`rest`) is Drake's C++ (the plant, the controller, SceneGraph,
event dispatch and the state copies of every unrestricted update: benchmarks/update_events.py)
and the Python callbacks not listed (the trees' outputs, small adapters).

    .venv/bin/python benchmarks/system_updates.py [--duration 30] [scenario ...]
"""

import argparse
import time
from collections import defaultdict

from pydrake.systems.framework import EventStatus

from hrc_drake import runner
from hrc_drake.scenario import load_scenario
from hrc_drake.systems.adapters import TcpPose
from hrc_drake.systems.behavior_tree import BehaviorTreeSystem
from hrc_drake.systems.human_actor import HumanActor
from hrc_drake.systems.realism_audit import RealismAudit
from hrc_drake.systems.robot_motion import RobotMotion
from hrc_drake.systems.safety_monitor import SafetyMonitor
from hrc_drake.systems.state_changes import StateChanges
from hrc_drake.systems.workpieces import Workpieces

SCENARIOS = ("coexistence", "cooperation", "collaboration")
CALLBACKS = (
    (HumanActor, "_update"),
    (SafetyMonitor, "_update"),
    (RobotMotion, "_update"),
    (RobotMotion, "_calc_path_rate"),
    (RobotMotion, "_calc_status"),
    (RobotMotion, "_calc_gripper_command"),
    (Workpieces, "_update"),
    (Workpieces, "_calc_poses"),
    (Workpieces, "_calc_status"),
    (BehaviorTreeSystem, "_tick"),
    (RealismAudit, "_sample"),
    (StateChanges, "_sample"),
    (TcpPose, "_calc"),
)


class Timed:
    """Replaces each callback (class, method name) by one that counts and times it, until
    the block ends."""

    def __init__(self, callbacks=CALLBACKS):
        self.calls = defaultdict(int)
        self.idle = defaultdict(int)
        self.seconds = defaultdict(float)
        self.idle_seconds = defaultdict(float)
        """CPU seconds of the calls that did nothing (part of `seconds`)."""
        self._nested = [0.0]
        """CPU seconds of the timed callbacks called inside the one running now."""
        self._originals = {(cls, name): getattr(cls, name) for cls, name in callbacks}

    def __enter__(self):
        for (cls, name), original in self._originals.items():
            setattr(cls, name, self._timed(f"{cls.__name__}.{name}", original))
        return self

    def __exit__(self, *exc):
        for (cls, name), original in self._originals.items():
            setattr(cls, name, original)

    def _timed(self, key: str, original):
        def timed(system, *args):
            self._nested.append(0.0)
            start = time.process_time()
            result = original(system, *args)
            spent = time.process_time() - start
            own = spent - self._nested.pop()
            self.seconds[key] += own
            self._nested[-1] += spent
            self.calls[key] += 1
            if (
                isinstance(result, EventStatus)
                and result.severity() == EventStatus.Severity.kDidNothing
            ):
                self.idle[key] += 1
                self.idle_seconds[key] += own
            return result

        return timed


def measured(name: str, duration: float, callbacks=CALLBACKS) -> tuple[Timed, float]:
    """The callbacks' counts and times over a run, and the simulation's CPU seconds."""
    advance = runner._advance
    total = [0.0]

    def timed_advance(*args):
        start = time.process_time()
        advance(*args)
        total[0] += time.process_time() - start

    runner._advance = timed_advance
    try:
        with Timed(callbacks) as timed:
            runner.run(load_scenario(name), duration=duration)
    finally:
        runner._advance = advance
    return timed, total[0]


def scenario_arguments(doc: str) -> argparse.Namespace:
    """The scenarios to run (all bundled ones by default) and the simulated seconds."""
    parser = argparse.ArgumentParser(description=doc.splitlines()[0])
    parser.add_argument("scenarios", nargs="*", default=SCENARIOS)
    parser.add_argument("--duration", type=float, default=30.0)
    return parser.parse_args()


def main() -> None:
    args = scenario_arguments(__doc__)
    for name in args.scenarios:
        timed, total = measured(name, args.duration)
        print(f"\n{name} ({args.duration:g} s simulated, {total:.2f} s CPU)")
        print(f"  {'callback':38s} {'calls/s':>8s} {'acting':>7s} {'us/call':>8s} {'share':>6s}")
        for key, seconds in sorted(timed.seconds.items(), key=lambda item: -item[1]):
            calls = timed.calls[key]
            acting = 1.0 - timed.idle[key] / calls
            print(
                f"  {key:38s} {calls / args.duration:8.1f} {100 * acting:6.0f}% "
                f"{1e6 * seconds / calls:8.0f} {100 * seconds / total:5.1f}%"
            )
        rest = total - sum(timed.seconds.values())
        print(f"  {'rest (Drake C++, dispatch)':65s} {100 * rest / total:5.1f}%")


if __name__ == "__main__":
    main()
