"""StateChanges: when each actor's state changed over a run, for the timeline figure.

A periodic publish samples one attribute of each connected status (the robot's `mode`, the
person's `state`, a tree's `running_path`; as text unless asked to keep the value, e.g.
what the person's hands hold) and keeps, per actor, the (time, state) pairs at which it
changed. It has no outputs and changes nothing in the simulation.
"""

from pydrake.systems.framework import DiagramBuilder, LeafSystem, OutputPort

from hrc_drake.ports import message_value
from hrc_drake.wiring import STATE_CHANGES


class StateChanges(LeafSystem):
    """Samples status ports and keeps, per actor, the times its state changed. `fields`
    maps each actor (an input port of that name) to the status attribute that is its
    state."""

    def __init__(self, fields: dict[str, str], period: float, as_text: bool = True):
        super().__init__()
        self._as_text = as_text
        self._inputs = {
            actor: (self.DeclareAbstractInputPort(actor, message_value()), attribute)
            for actor, attribute in fields.items()
        }
        self._changes: dict[str, list[tuple[float, str]]] = {}
        self.DeclarePeriodicPublishEvent(period, 0.0, self._sample)

    def _sample(self, context) -> None:
        for actor, (port, attribute) in self._inputs.items():
            state = getattr(port.Eval(context), attribute)
            state = str(state) if self._as_text else state
            history = self._changes.setdefault(actor, [])
            if not history or history[-1][1] != state:
                history.append((context.get_time(), state))

    def changes(self) -> dict[str, list[tuple[float, str]]]:
        return self._changes


def add_state_changes(
    builder: DiagramBuilder,
    sources: dict[str, tuple[OutputPort, str]],
    period: float,
    name: str = STATE_CHANGES,
    as_text: bool = True,
) -> StateChanges:
    """Adds a sampler named `name`, every `period` s, connected to each actor's (status
    output, attribute) in `sources`."""
    fields = {actor: attribute for actor, (_, attribute) in sources.items()}
    sampler = builder.AddNamedSystem(name, StateChanges(fields, period, as_text))
    for actor, (port, _) in sources.items():
        builder.Connect(port, sampler.GetInputPort(actor))
    return sampler
