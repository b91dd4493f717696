"""Scenario 2, cooperation: the robot inspects and sorts parts, the person clears the rejects.

The run is judged by the world it leaves: where every spawned part is (the objects status,
sampled during the run, so parts that left on the outfeed belt are known too), the task
events of both trees, the reject zone's count over time, and the safety totals. What each
part should do follows from its drawn `defective` attribute, never from recorded numbers.
"""

from collections import Counter
from dataclasses import dataclass, field
from pathlib import Path

import pytest
from pydrake.systems.analysis import Simulator

from hrc_drake.bt.ports import value_to_text
from hrc_drake.builder import build_diagram
from hrc_drake.evaluation.realism import realism_metrics
from hrc_drake.messages import TaskEvent
from hrc_drake.safety.messages import SafetyTotals
from hrc_drake.scenario import Scenario, load_scenario
from hrc_drake.workpieces.messages import PERSON_HOLDERS, ROBOT_HOLDER, ObjectStatus
from tests.scenarios.realism_checks import (
    assert_holds_what_it_carries,
    assert_keeps_out_of_things,
    assert_walks_like_a_person,
    assert_within_the_audit_limits,
)

SCENARIO = Path(__file__).resolve().parents[2] / "scenarios" / "cooperation.yaml"
SAMPLE_PERIOD = 0.25
"""Seconds between looks at the objects status: a part needs longer to cross the belt."""
GONE = "gone"
PLACES_OF_GOOD = {"infeed", ROBOT_HOLDER, "outfeed", GONE}
PLACES_OF_DEFECTIVE = {"infeed", ROBOT_HOLDER, "reject_zone", "person", "scrap_bin"}
SHORT_SEED = 0
"""Its first three parts are defective and its fourth good: a short run fills the reject
zone, brings the person to clear it and sends a part out on the belt."""
SHORT_DURATION = 50.0
"""s: the good fourth part leaves at about 47 s (the robot slowed down while the person
clears the reject zone, 24-60 s)"""
BEHAVIOURS = {"part_rejected": 8, "part_scrapped": 8, "speed_reduced": 8, "reject_wait": 2}
"""Events and in how many of ten seeds (at least) a full-length run shows them."""


@dataclass
class Outcome:
    """What one simulated run left behind."""

    defective: dict[int, bool] = field(default_factory=dict)
    """Every part ever seen, by id: its drawn attribute."""
    place: dict[int, str] = field(default_factory=dict)
    """Where each part was at the last look (`gone` once it left the simulation)."""
    max_in_reject_zone: int = 0
    events: list[TaskEvent] = field(default_factory=list)
    safety: SafetyTotals | None = None
    realism: dict = field(default_factory=dict)
    """The run's realism audit (report.json's `realism`)."""

    def count(self, name: str) -> int:
        return sum(e.name == name for e in self.events)

    def parts(self, defective: bool, place: str) -> int:
        return sum(self.defective[i] == defective and p == place for i, p in self.place.items())


def place_of(obj: ObjectStatus, scenario: Scenario) -> str:
    """Where a part is, in the scenario's terms."""
    if obj.holder == ROBOT_HOLDER:
        return ROBOT_HOLDER
    if obj.holder in PERSON_HOLDERS:
        return "person"
    if obj.support in ("infeed", "outfeed"):
        return obj.support
    xy = obj.pose.translation()[:2]
    for area in ("reject_zone", "scrap_bin"):
        if obj.holder is None and scenario.area(area).contains(xy):
            return area
    return f"elsewhere ({obj.support})"


def in_reject_zone(objects, scenario: Scenario) -> int:
    """What the trees' CountObjects(reject_zone, type=part) sees: free parts lying there."""
    return sum(place_of(o, scenario) == "reject_zone" for o in objects)


def simulate(duration: float, seed: int) -> Outcome:
    scenario = load_scenario(SCENARIO, [("seed", seed)])
    diagram = build_diagram(scenario)
    simulator = Simulator(diagram)
    context = simulator.get_context()
    outcome = Outcome()
    t = 0.0
    while t < duration:
        t = min(duration, t + SAMPLE_PERIOD)
        simulator.AdvanceTo(t)
        look(outcome, diagram.GetOutputPort("workpieces_status").Eval(context).objects, scenario)
    outcome.events = sorted(
        (
            e
            for a in ("robot", "human")
            for e in diagram.GetOutputPort(f"{a}_task_events").Eval(context)
        ),
        key=lambda e: e.time,
    )
    outcome.safety = diagram.GetOutputPort("safety_status").Eval(context).totals
    outcome.realism = realism_metrics(diagram.GetOutputPort("realism").Eval(context))
    return outcome


def look(outcome: Outcome, objects, scenario: Scenario) -> None:
    """Record where every part is now; parts no longer there are gone."""
    seen = {o.id for o in objects}
    for part_id in outcome.place.keys() - seen:
        if outcome.place[part_id] != GONE:
            assert outcome.place[part_id] == "outfeed", (
                f"part {part_id} vanished from the {outcome.place[part_id]}"
            )
            outcome.place[part_id] = GONE
    for obj in objects:
        outcome.defective[obj.id] = value_to_text(obj.attributes["defective"]) == "true"
        outcome.place[obj.id] = place_of(obj, scenario)
    outcome.max_in_reject_zone = max(outcome.max_in_reject_zone, in_reject_zone(objects, scenario))


def assert_sorted_correctly(outcome: Outcome) -> None:
    """Good parts only ever go out on the belt, defective ones only to the reject zone and
    the scrap bin; the events count the parts that got there (an event comes after the
    release, so the last part put down may still lack its event when the run ends)."""
    for part_id, place in outcome.place.items():
        allowed = PLACES_OF_DEFECTIVE if outcome.defective[part_id] else PLACES_OF_GOOD
        assert place in allowed, (
            f"part {part_id} (defective={outcome.defective[part_id]}) is {place}"
        )
    assert len(outcome.place) - outcome.count("part_arrived") in (0, 1)
    out = outcome.parts(False, "outfeed") + outcome.parts(False, GONE)
    scrapped = outcome.parts(True, "scrap_bin")
    rejected = outcome.parts(True, "reject_zone") + outcome.parts(True, "person") + scrapped
    for event, parts in (
        ("part_good", out),
        ("part_rejected", rejected),
        ("part_scrapped", scrapped),
    ):
        assert parts - outcome.count(event) in (0, 1), (
            f"{event}: {outcome.count(event)} for {parts}"
        )
    sorted_parts = outcome.count("part_good") + outcome.count("part_rejected")
    assert outcome.count("part_inspected") - sorted_parts in (0, 1)


def assert_safe(outcome: Outcome) -> None:
    assert outcome.max_in_reject_zone <= 3
    assert outcome.safety.violations == 0
    assert outcome.safety.contacts == 0


def test_short_run_sorts_parts_and_fills_the_reject_zone():
    outcome = simulate(SHORT_DURATION, seed=SHORT_SEED)
    assert_sorted_correctly(outcome)
    assert_safe(outcome)
    assert outcome.count("part_good") >= 1
    assert outcome.max_in_reject_zone == 3
    assert outcome.count("part_scrapped") >= 1
    assert outcome.count("speed_reduced") >= 1
    assert outcome.count("sort_failed") == 0
    assert_holds_what_it_carries(outcome.realism)
    assert_walks_like_a_person(outcome.realism)
    assert_keeps_out_of_things(outcome.realism)


@pytest.mark.long
def test_ten_seeds_sort_every_part_and_clear_the_reject_zone():
    """Every seed sorts correctly and safely and sends good parts out. Most seeds draw
    enough defective parts to fill the zone, bring the person and slow the robot down; a
    rejected part arriving while the zone is full or being cleared (the robot waits) is
    rarer, a few seeds in ten."""
    scenario = load_scenario(SCENARIO)
    shown = Counter()
    for seed in range(10):
        outcome = simulate(scenario.duration, seed=seed)
        assert_sorted_correctly(outcome)
        assert_safe(outcome)
        assert outcome.count("sort_failed") == 0
        assert outcome.count("part_good") >= 1
        assert_within_the_audit_limits(outcome.realism)
        shown.update(name for name in BEHAVIOURS if outcome.count(name) > 0)
    for name, seeds in BEHAVIOURS.items():
        assert shown[name] >= seeds, f"{name} shown by {shown[name]} seeds of 10"
