"""Cost of the simulated person: real-time factor of the base cell with and without it.

The cell is the base scenario's station (dynamic plant with iisy, tool and cell, SAP,
inverse-dynamics controller and RobotMotion holding home). The person variant adds the
scenario's `human:` section, walking back and forth between two points for the whole run
(turns included).
Both variants run in this process, alternating, best of the repeats. Times are the process's
CPU time, so that other work on the machine does not blur the comparison.

    .venv/bin/python benchmarks/human_cost.py [--duration 10] [--repeats 3]
"""

import argparse
import time

from pydrake.systems.analysis import Simulator
from pydrake.systems.framework import DiagramBuilder, LeafSystem

from hrc_drake.builder import build_diagram
from hrc_drake.human.messages import MoveCommand
from hrc_drake.ports import message_value
from hrc_drake.scenario import HumanConfig, load_scenario

LEGS = ((1.5, -2.0), (-1.5, -2.0))
"""The person walks between these two points (m), about 3 m in front of the robot."""


class Patrol(LeafSystem):
    """Sends the next walk each time the person reports the previous one finished."""

    def __init__(self):
        LeafSystem.__init__(self)
        self._status = self.DeclareAbstractInputPort("status", message_value())
        self.DeclareAbstractOutputPort("command", message_value, self._calc)

    def _calc(self, context, output):
        status = self._status.Eval(context)
        last = status.results.last if status is not None else None
        done = 0 if last is None else last.seq
        if last is not None and last.outcome == "running":
            done -= 1
        seq = done + 1
        x, y = LEGS[seq % 2]
        output.set_value(MoveCommand(seq, (x, y, 0.0)))


def cell(with_person: bool):
    """The base station through the scenario builder; with the person (and no safety
    monitor, so only the person's cost is measured) patrolling in front of the robot."""
    scenario = load_scenario("base")
    if with_person:
        scenario.human = HumanConfig(start=[*LEGS[0], 180.0])
        scenario.safety.enabled = False
    builder = DiagramBuilder()
    station = builder.AddSystem(build_diagram(scenario))
    if with_person:
        patrol = builder.AddSystem(Patrol())
        builder.Connect(station.GetOutputPort("human_status"), patrol.get_input_port())
        builder.Connect(
            patrol.get_output_port(), station.GetInputPort("human_actor.human_tree_command")
        )
    return builder.Build()


def real_time_factor(with_person: bool, duration: float) -> float:
    """Simulated seconds per second of CPU time."""
    simulator = Simulator(cell(with_person))
    simulator.Initialize()
    start = time.process_time()
    simulator.AdvanceTo(duration)
    return duration / (time.process_time() - start)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--duration", type=float, default=10.0)
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args()
    best = {False: 0.0, True: 0.0}
    for _ in range(args.repeats):
        for with_person in (False, True):
            best[with_person] = max(best[with_person], real_time_factor(with_person, args.duration))
    added = best[False] / best[True] - 1.0
    print(f"real-time factor without person: {best[False]:.2f}")
    print(f"real-time factor with person walking: {best[True]:.2f}")
    print(f"the person adds {100 * added:.1f} % to the run time (target < 10 %)")


if __name__ == "__main__":
    main()
