"""Where RobotMotion's updates go: the parts of one update, and why updates act.

A scenario runs once as a sweep runs it (`benchmarks/system_updates.py`'s timing: this
process's CPU time, each part without the timed parts it calls). Prints, per part of
`RobotMotion._update`, its calls and its CPU per update (all updates, acting or not) and
its share of the updates' CPU; the workpieces' status, which the update reads, and
`Causes.cause`, this benchmark's own bookkeeping, are lines of their own. Then the acting
updates by cause, the first that holds of: a new command, a new safety scale (the
monitor's scale changes: each must take effect at once), the held object changed, a
steady segment ended (its horizon ran out), a steady horizon whose one quintic strays from
the desired motion (`faithful_segment`: one period instead), and the motion changing each
period (the path rate changing, planning, arriving, the gripper).

    .venv/bin/python benchmarks/robot_update.py [--duration 30] [scenario ...]
"""

from collections import Counter

from system_updates import measured, scenario_arguments

from hrc_drake.messages import newer_commands
from hrc_drake.motion.planner import MotionPlanner
from hrc_drake.motion.state_machine import MotionStateMachine
from hrc_drake.ports import value_or_none
from hrc_drake.systems.robot_motion import RobotMotion
from hrc_drake.systems.workpieces import Workpieces

PARTS = (
    (RobotMotion, "_update"),
    (RobotMotion, "_within_segment"),
    (RobotMotion, "_inputs"),
    (MotionStateMachine, "update"),
    (MotionStateMachine, "_measured"),
    (MotionStateMachine, "_workpieces_seen"),
    (MotionPlanner, "plan"),
    (MotionStateMachine, "_advanced"),
    (RobotMotion, "_segment_ahead"),
    (RobotMotion, "_samples_of"),
    (Workpieces, "_calc_status"),
)
OTHERS = ("Workpieces", "Causes")
"""Timed parts outside the update's own: what it reads, and this benchmark's bookkeeping."""


class Causes:
    """Counts why each acting update of RobotMotion acted, until the block ends."""

    def __init__(self):
        self.counts = Counter()
        self._update = RobotMotion._update

    def __enter__(self):
        causes, update = self, self._update

        def counted(system, context, new_state):
            cause = Causes.cause(system, context)
            result = update(system, context, new_state)
            if result.severity() != result.Severity.kDidNothing:
                causes.counts[cause] += 1
            return result

        RobotMotion._update = counted
        return self

    def __exit__(self, *exc):
        RobotMotion._update = self._update

    @staticmethod
    def cause(system: RobotMotion, context) -> str:
        state = system._state(context)
        segment = context.get_discrete_state(system._segment).get_value()
        end = context.get_discrete_state(system._segment_end).get_value()[0]
        horizon = system._machine.horizon(state)
        period = system._options.period
        workpieces = value_or_none(system._workpieces, context)
        if newer_commands(value_or_none(system._command, context), state.seen_seq):
            return "a new command"
        if system._safety_scale(context) != state.safety_scale:
            return "a new safety scale"
        if not system._machine.unchanged(state, None, state.safety_scale, workpieces):
            return "the held object changed"
        if horizon > period and end - segment[0] > period * 1.5:
            return "a steady segment ended"
        if horizon > period:
            return "a steady horizon, one quintic strays: one period"
        return "one period: " + Causes.short_horizon(state)

    @staticmethod
    def short_horizon(state) -> str:
        """Why the last update knew its motion one period ahead only."""
        if state.pending is not None:
            return "planning"
        if state.gripper_waiting:
            return "gripper waiting"
        progress = state.progress
        if state.stop_seq is not None:
            return "stopping" if not progress.at_rest else "stopped"
        if state.move_seq is None:
            return "stopped on a path"
        if state.arrived_since is not None or progress.finished(state.path.duration):
            return "arriving (settling)"
        if progress.rate_change > 0.0:
            return "rate ramping up"
        if progress.rate_change < 0.0:
            return "rate ramping down"
        if progress.rate != state.speed_fraction * state.safety_scale:
            return "rate off target, no change"
        return "path's end within the horizon"


def main() -> None:
    args = scenario_arguments(__doc__)
    for name in args.scenarios:
        with Causes() as causes:
            timed, _ = measured(name, args.duration, (*PARTS, (Causes, "cause")))
        updates = timed.calls["RobotMotion._update"]
        own = sum(s for key, s in timed.seconds.items() if not key.startswith(OTHERS))
        acting = sum(causes.counts.values()) / updates
        print(f"\n{name} ({updates} updates, {100 * acting:.0f}% acting)")
        print(f"  {'part':40s} {'calls':>6s} {'us/update':>10s} {'share':>6s}")
        for key, seconds in sorted(timed.seconds.items(), key=lambda item: -item[1]):
            share = "" if key.startswith(OTHERS) else f"{100 * seconds / own:5.1f}%"
            print(f"  {key:40s} {timed.calls[key]:6d} {1e6 * seconds / updates:10.0f} {share:>6s}")
        print("  acting updates by cause:")
        for cause, count in causes.counts.most_common():
            print(f"    {cause:55s} {count:6d} {100 * count / updates:5.1f}%")


if __name__ == "__main__":
    main()
