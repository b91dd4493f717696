"""A plant step calls no Python: Drake asks every system for its witness functions after
each unrestricted update, a call into Python for each Python system, so the plant must step
as a discrete update (its output ports live, not sampled: hrc_drake.scenario.schema), and a
Python system is asked only at the times its own systems update (benchmarks/python_systems.py
measures what each call costs)."""

from pydrake.systems.analysis import Simulator
from pydrake.systems.framework import LeafSystem

from hrc_drake.builder import build_diagram
from hrc_drake.scenario import load_scenario, overridden

DURATION = 0.2


class WitnessProbe(LeafSystem):
    """A Python system that counts how often the simulator asks it for witness functions."""

    def __init__(self):
        super().__init__()
        self.asked = 0

    def DoGetWitnessFunctions(self, context):
        self.asked += 1
        return []


def test_python_systems_are_not_called_at_every_plant_step():
    scenario = overridden(load_scenario("coexistence"), [("duration", DURATION)])
    probe = WitnessProbe()
    diagram = build_diagram(scenario, attach=lambda builder, _: builder.AddSystem(probe))
    Simulator(diagram).AdvanceTo(DURATION)
    plant_steps = DURATION / scenario.plant.time_step
    update_times = DURATION / scenario.robot.motion.period + DURATION * 60  # 100 Hz and 60 Hz
    assert probe.asked <= update_times + 1 < plant_steps
