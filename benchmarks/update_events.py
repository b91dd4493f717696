"""What Drake charges a Python system per event, apart from the work the event does.

Systems with nothing to do (each returns DidNothing) are given one periodic event (100 Hz)
of each kind: an unrestricted update, a discrete update or a publish, and 0, 1 or 4 abstract
states holding a Python object. Before every unrestricted update Drake copies the system's
whole state into the update's buffer, and a Python object held in an AbstractValue is copied
by `copy.deepcopy`: the count of `__deepcopy__` calls per event says how many, the time
per event what they and the call into Python cost (this process's CPU time, the cost of one
system set against six).

    .venv/bin/python benchmarks/update_events.py [--duration 100]
"""

import argparse
import time

import numpy as np
from pydrake.common.value import AbstractValue
from pydrake.systems.analysis import Simulator
from pydrake.systems.framework import DiagramBuilder, EventStatus, LeafSystem

PERIOD = 0.01
MANY = 6


class Held:
    """An immutable value, as the project's states are: its copies are itself."""

    copies = 0

    def __deepcopy__(self, memo):
        Held.copies += 1
        return self


class Idle(LeafSystem):
    """One periodic event of `kind` that does nothing, beside `held` abstract states."""

    def __init__(self, kind: str, held: int):
        super().__init__()
        for _ in range(held):
            self.DeclareAbstractState(AbstractValue.Make(Held()))
        self.DeclareDiscreteState(np.zeros(3))
        if kind == "unrestricted":
            self.DeclarePeriodicUnrestrictedUpdateEvent(PERIOD, 0.0, self._nothing)
        elif kind == "discrete":
            self.DeclarePeriodicDiscreteUpdateEvent(PERIOD, 0.0, self._nothing)
        else:
            self.DeclarePeriodicPublishEvent(PERIOD, 0.0, self._nothing)

    def _nothing(self, *context_and_state) -> EventStatus:
        return EventStatus.DidNothing()


def cost(kind: str, held: int, systems: int, duration: float) -> tuple[float, int]:
    """CPU seconds of the simulation and the deep copies made in it."""
    builder = DiagramBuilder()
    for _ in range(systems):
        builder.AddSystem(Idle(kind, held))
    simulator = Simulator(builder.Build())
    simulator.Initialize()
    Held.copies = 0
    start = time.process_time()
    simulator.AdvanceTo(duration)
    return time.process_time() - start, Held.copies


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--duration", type=float, default=100.0)
    args = parser.parse_args()
    events = args.duration / PERIOD
    print(f"{'event':>12} {'abstract states':>15} {'us/event':>9} {'deep copies/event':>18}")
    for kind in ("unrestricted", "discrete", "publish"):
        for held in (0, 1, 4):
            one, _ = cost(kind, held, 1, args.duration)
            many, copies = cost(kind, held, MANY, args.duration)
            each = (many - one) / (MANY - 1) / events * 1e6
            print(f"{kind:>12} {held:>15} {each:9.1f} {copies / MANY / events:18.2f}")


if __name__ == "__main__":
    main()
