"""The realism audit is worked out from the run's record when it is read: read part-way
through a run and again at its end, it is the audit of the whole run, the same as read only
at the end (the samples already audited are carried on, never counted twice)."""

from pydrake.systems.analysis import Simulator

from hrc_drake.builder import build_diagram
from hrc_drake.scenario import load_scenario
from hrc_drake.systems.realism_audit import Recorded

HALF = 3.0
"""s: coexistence's person is walking to the bench by then (strides, foot contacts)."""


def _simulator() -> Simulator:
    simulator = Simulator(build_diagram(load_scenario("coexistence", [("seed", 0)])))
    simulator.Initialize()
    return simulator


def _realism(simulator: Simulator):
    return simulator.get_system().GetOutputPort("realism").Eval(simulator.get_context())


def test_an_audit_read_as_the_run_goes_is_the_audit_read_at_its_end():
    read_twice, read_once = _simulator(), _simulator()
    read_twice.AdvanceTo(HALF)
    halfway = _realism(read_twice)
    read_twice.AdvanceTo(2 * HALF)
    read_once.AdvanceTo(2 * HALF)
    assert _realism(read_twice) == _realism(read_once)
    assert _realism(read_once) != halfway
    assert _realism(read_once).stride_speeds  # the person walked: strides were audited


def _record(times) -> Recorded | None:
    record = None
    for t in times:
        record = Recorded(record, t, (), None)
    return record


def test_a_record_lists_the_samples_after_one_of_its_own_oldest_first():
    record = _record([0.1, 0.2, 0.3, 0.4])
    earlier = record.earlier.earlier
    assert [r.time for r in record.since(earlier)] == [0.3, 0.4]
    assert [r.time for r in record.since(None)] == [0.1, 0.2, 0.3, 0.4]
    assert record.since(record) == []
    assert record.holds(earlier) and record.holds(record)
    assert not record.holds(_record([0.1]))
