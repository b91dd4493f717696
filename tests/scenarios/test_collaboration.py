"""Scenario 3, collaboration: robot and person unload a pallet together.

The run is judged by what happened in the world: where every box went and who moved it (the
objects status), the calls and the help that answered them (the task events), the called
flag, and the safety totals. The expectations come from the seed's pallet layout (the box
attributes at the start), never from recorded numbers.
"""

from dataclasses import dataclass
from pathlib import Path

import pytest
from pydrake.systems.analysis import Simulator

from hrc_drake.areas import Area
from hrc_drake.builder import build_diagram
from hrc_drake.evaluation.realism import realism_metrics
from hrc_drake.messages import TaskEvent
from hrc_drake.safety.messages import SafetyTotals
from hrc_drake.scenario import load_scenario
from hrc_drake.workpieces.messages import PERSON_HOLDERS, ObjectStatus, WorkpiecesStatus
from tests.scenarios.realism_checks import (
    assert_holds_what_it_carries,
    assert_keeps_out_of_things,
    assert_walks_like_a_person,
    assert_within_the_audit_limits,
)

SCENARIO = Path(__file__).resolve().parents[2] / "scenarios" / "collaboration.yaml"
CONVEYOR = "outfeed"
HELP_FOR_CALL = {"carry": "box_by_person", "handover": "handover", "regrip": "regrip"}
"""The person's event that answers each reason of the robot's call."""
BOX_DONE = {"box_unloaded": "robot", "box_by_person": "human", "handover": "human"}
"""Events that finish a box (it left the pallet for the belt), and who emits them."""
SHORT_SEED = 15
"""Its first box is porous, its second fragile, and its third box's grip fails: a short run
shows a carry, a hand-over and a straightening."""
SHORT_DURATION = 80.0
"""Long enough for the retry after the straightening: the robot resumes once the person has
stepped back out of its protective separation distance."""


@dataclass
class Outcome:
    """What one simulated run left behind."""

    boxes: dict[int, ObjectStatus]
    """Every box at the start (with its drawn attributes), by id."""
    final: WorkpiecesStatus
    events: list[TaskEvent]
    """Both trees' task events in time order."""
    safety: SafetyTotals
    called: bool
    pallet: Area
    realism: dict
    """The run's realism audit (report.json's `realism`)."""

    def named(self, *names: str) -> list[TaskEvent]:
        return [e for e in self.events if e.name in names]

    def boxes_off_the_pallet(self) -> set[int]:
        """Boxes that are gone (removed at the belt's end) or lie free off the pallet."""
        gone = set(self.boxes) - {o.id for o in self.final.objects}
        moved = {
            o.id
            for o in self.final.objects
            if o.holder is None and not self.pallet.contains(o.pose.translation()[:2])
        }
        return gone | moved

    def boxes_in_hands(self) -> set[int]:
        """Boxes the person is carrying at the end (finished or not, depending on the event)."""
        return {o.id for o in self.final.objects if o.holder in PERSON_HOLDERS}

    def pallet_cleared(self) -> bool:
        return not any(
            self.pallet.contains(o.pose.translation()[:2]) or o.holder is not None
            for o in self.final.objects
        )


def simulate(seed: int, duration: float) -> Outcome:
    scenario = load_scenario(SCENARIO, [("seed", seed)])
    diagram = build_diagram(scenario)
    simulator = Simulator(diagram)
    context = simulator.get_context()
    start = diagram.GetOutputPort("workpieces_status").Eval(context)
    simulator.AdvanceTo(duration)
    events = [
        event
        for agent in ("robot", "human")
        for event in diagram.GetOutputPort(f"{agent}_task_events").Eval(context)
    ]
    return Outcome(
        boxes={o.id: o for o in start.objects},
        final=diagram.GetOutputPort("workpieces_status").Eval(context),
        events=sorted(events, key=lambda e: e.time),
        safety=diagram.GetOutputPort("safety_status").Eval(context).totals,
        called=diagram.GetOutputPort("human_status").Eval(context).called,
        pallet=scenario.area("pallet"),
        realism=realism_metrics(diagram.GetOutputPort("realism").Eval(context)),
    )


def needs_person(box: ObjectStatus) -> bool:
    return bool(box.attributes["heavy"] or box.attributes["porous"])


def is_fragile(box: ObjectStatus) -> bool:
    return bool(box.attributes["fragile"]) and not needs_person(box)


def assert_every_box_off_the_pallet_went_to_the_belt_once(outcome: Outcome) -> None:
    """Each box that left the pallet was finished by exactly one party, the right one for
    its attributes, and went onto the belt (or off its end)."""
    done = outcome.named(*BOX_DONE)
    finished = [int(e.value) for e in done]
    assert sorted(finished) == sorted(set(finished)), "a box was finished twice"
    off = outcome.boxes_off_the_pallet()
    assert off <= set(finished) <= off | outcome.boxes_in_hands()
    for event in done:
        box = outcome.boxes[int(event.value)]
        assert event.agent == BOX_DONE[event.name]
        expected = "box_by_person" if needs_person(box) else None
        expected = expected or ("handover" if is_fragile(box) else "box_unloaded")
        assert event.name == expected, f"box {box.id} {box.attributes}: {event.name}"
    for obj in outcome.final.objects:
        if obj.id in off:
            assert obj.support == CONVEYOR, f"box {obj.id} lies on {obj.support}"


def assert_every_help_answered_a_call(outcome: Outcome) -> None:
    """Calls and help alternate: each call is answered by the help its reason asks for,
    before the next call; at most the last call is still being answered."""
    calls = outcome.named("call")
    helps = outcome.named(*HELP_FOR_CALL.values())
    assert len(calls) - len(helps) in (0, 1)
    for k, (call, help_) in enumerate(zip(calls, helps, strict=False)):
        assert call.agent == "robot" and help_.agent == "human"
        assert help_.name == HELP_FOR_CALL[call.value]
        assert call.time < help_.time
        if k + 1 < len(calls):
            assert help_.time < calls[k + 1].time
    assert_every_grip_failure_called_for_straightening(outcome)
    if not outcome.called:
        assert len(calls) == len(helps), "the call was reset before the person helped"


def assert_every_grip_failure_called_for_straightening(outcome: Outcome) -> None:
    """Failed grips and regrip calls alternate; the run may end between the last failure and
    its call."""
    failures = outcome.named("grip_failed")
    calls = [c for c in outcome.named("call") if c.value == "regrip"]
    assert len(failures) - len(calls) in (0, 1)
    for k, call in enumerate(calls):
        assert failures[k].time < call.time
        if k + 1 < len(failures):
            assert call.time < failures[k + 1].time


def assert_consistent(outcome: Outcome) -> None:
    """The world outcomes every run must show, finished or not, including safety: no SSM
    violation and no contact, hand-overs included."""
    assert_every_box_off_the_pallet_went_to_the_belt_once(outcome)
    assert_every_help_answered_a_call(outcome)
    assert (outcome.safety.violations, outcome.safety.contacts) == (0, 0)


def unloading_order(outcome: Outcome) -> list[ObjectStatus]:
    """The boxes in the order the trees take them: cartons (top layer) first, by id."""
    return sorted(outcome.boxes.values(), key=lambda b: (b.type != "carton", b.id))


@pytest.fixture(scope="module")
def short_run() -> Outcome:
    return simulate(SHORT_SEED, duration=SHORT_DURATION)


def test_short_run_person_carries_the_box_the_robot_must_not_handle(short_run):
    first, second = unloading_order(short_run)[:2]
    assert needs_person(first) and is_fragile(second), "the short seed's layout changed"
    assert short_run.named("call")[0].value == "carry"
    carried = short_run.named("box_by_person")
    assert [int(e.value) for e in carried] == [first.id]


def test_short_run_robot_hands_the_fragile_box_over(short_run):
    second = unloading_order(short_run)[1]
    assert [int(e.value) for e in short_run.named("handover")] == [second.id]
    handover_call = next(c for c in short_run.named("call") if c.value == "handover")
    assert handover_call.time < short_run.named("handover")[0].time


def test_short_run_person_straightens_the_box_whose_grip_failed_and_robot_retries(short_run):
    third = unloading_order(short_run)[2]
    assert not (needs_person(third) or is_fragile(third)), "the short seed's layout changed"
    failed = short_run.named("grip_failed")[0]
    regrip_call = next(c for c in short_run.named("call") if c.value == "regrip")
    straightened = short_run.named("regrip")[0]
    assert int(failed.value) == int(straightened.value) == third.id
    assert failed.time < regrip_call.time < straightened.time
    retry = next(e for e in short_run.events if e.agent == "robot" and e.time > straightened.time)
    assert (retry.name, int(retry.value)) in {("grip_failed", third.id), ("box_unloaded", third.id)}


def test_short_run_person_holds_what_they_carry(short_run):
    assert_holds_what_it_carries(short_run.realism)


def test_short_run_person_walks_without_sliding(short_run):
    assert_walks_like_a_person(short_run.realism)


def test_short_run_person_keeps_out_of_the_cell_and_the_objects(short_run):
    assert_keeps_out_of_things(short_run.realism)


def test_short_run_is_consistent_and_safe(short_run):
    assert_consistent(short_run)


@pytest.mark.long
@pytest.mark.parametrize("seed", range(10))
def test_pallet_is_cleared_together(seed):
    outcome = simulate(seed, duration=300.0)
    assert outcome.pallet_cleared()
    assert outcome.named("pallet_cleared")
    assert outcome.boxes_off_the_pallet() == set(outcome.boxes)
    assert_consistent(outcome)
    assert not outcome.called
    helped = {int(e.value) for e in outcome.named("box_by_person", "handover")}
    assert helped == {b.id for b in outcome.boxes.values() if needs_person(b) or is_fragile(b)}
    assert_within_the_audit_limits(outcome.realism)
