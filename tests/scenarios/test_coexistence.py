"""Scenario 1, coexistence: the robot produces parts while the person does their own work.

The run is judged by what happened in the world, sampled every 0.1 s: where the parts are
(the objects status), the robot's speed override against where the person stands (the
robot and person statuses), the task events of both trees, and the safety totals.
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
from hrc_drake.workpieces.messages import PERSON_HOLDERS, ROBOT_HOLDER, ObjectStatus
from tests.scenarios.realism_checks import (
    assert_holds_what_it_carries,
    assert_keeps_out_of_things,
    assert_walks_like_a_person,
    assert_within_the_audit_limits,
)

SCENARIO = Path(__file__).resolve().parents[2] / "scenarios" / "coexistence.yaml"
SAMPLE_PERIOD = 0.1
SETTLED_SAMPLES = 3
"""Samples (0.3 s) the person stays on one side of the zone border before the robot's
speed must match it: the tree ticks every 50 ms and the robot takes a command at its next
update."""
ACTIVITIES = ("work_at_bench", "fetch_material", "inspect_output", "add_part", "stroll")
"""The person's activities; each starts with an event of its name."""
SHORT_SEED = 2
"""Its person fetches material, then adds a part to the robot's input tray (inside the cell
zone) while the robot finishes its first two parts: the short run shows all it checks."""


@dataclass(frozen=True)
class Sample:
    time: float
    person_xy: tuple[float, float]
    speed_fraction: float
    objects: tuple[ObjectStatus, ...]


@dataclass
class Outcome:
    """What one simulated run left behind."""

    duration: float
    slow_speed: float
    areas: dict[str, Area]
    samples: list[Sample]
    events: list[TaskEvent]
    """Both trees' task events in time order."""
    safety: SafetyTotals
    realism: dict
    """The run's realism audit (report.json's `realism`)."""

    def named(self, *names: str) -> list[TaskEvent]:
        return [e for e in self.events if e.name in names]

    def sample_after(self, time: float) -> Sample:
        return next(s for s in self.samples if s.time > time)

    def lies_in(self, obj: ObjectStatus, area: str) -> bool:
        return obj.holder is None and self.areas[area].contains(obj.pose.translation()[:2])


def simulate(seed: int, duration: float) -> Outcome:
    """Runs the scenario and samples the statuses."""
    scenario = load_scenario(SCENARIO, [("seed", seed)])
    diagram = build_diagram(scenario)
    simulator = Simulator(diagram)
    context = simulator.get_context()

    def status(name: str):
        return diagram.GetOutputPort(name).Eval(context)

    samples = []
    for k in range(1, round(duration / SAMPLE_PERIOD) + 1):
        simulator.AdvanceTo(k * SAMPLE_PERIOD)
        samples.append(
            Sample(
                time=context.get_time(),
                person_xy=tuple(status("human_status").base_pose[:2]),
                speed_fraction=status("robot_status").speed_fraction,
                objects=status("workpieces_status").objects,
            )
        )
    events = [e for agent in ("robot", "human") for e in status(f"{agent}_task_events")]
    return Outcome(
        duration=duration,
        slow_speed=float(scenario.parameters["slow_speed"]),
        areas={name: scenario.area(name) for name in scenario.areas},
        samples=samples,
        events=sorted(events, key=lambda e: e.time),
        safety=status("safety_status").totals,
        realism=realism_metrics(status("realism")),
    )


def assert_parts_keep_coming(outcome: Outcome, at_least: int, longest_gap: float) -> None:
    """Enough parts, and no long pause: from the start to the first part, between parts,
    and from the last part to the end of the run."""
    times = [0.0, *(e.time for e in outcome.named("part_finished")), outcome.duration]
    assert len(times) - 2 >= at_least, f"{len(times) - 2} parts finished"
    gaps = [later - earlier for earlier, later in zip(times, times[1:], strict=False)]
    assert max(gaps) <= longest_gap, f"a pause of {max(gaps):.1f} s between parts"


def assert_finished_parts_reach_the_output_tray(outcome: Outcome) -> None:
    """Each part_finished names a finished part lying in the output tray right after."""
    for event in outcome.named("part_finished"):
        objects = {o.id: o for o in outcome.sample_after(event.time).objects}
        part = objects[int(event.value)]
        assert part.type == "finished_part"
        assert outcome.lies_in(part, "output_tray"), f"part {part.id} at {part.pose}"


def assert_parts_stay_in_the_process(outcome: Outcome) -> None:
    """At every sample each part is in a tray, in the fixture or in someone's hands, and
    no raw part ever lies in the output tray."""
    places = {"raw_part": ("input_tray", "fixture_area"), "finished_part": ("fixture_area",)}
    places["finished_part"] += ("output_tray",)
    for sample in outcome.samples:
        for obj in sample.objects:
            if obj.type not in places or obj.holder in (ROBOT_HOLDER, *PERSON_HOLDERS):
                continue
            if obj.type == "raw_part" and outcome.lies_in(obj, "bench_top"):
                continue  # the person's own stock
            assert any(outcome.lies_in(obj, area) for area in places[obj.type]), (
                f"{obj.type} {obj.id} at {obj.pose.translation()} at {sample.time:.1f} s"
            )


def assert_slower_while_person_in_cell(outcome: Outcome) -> None:
    """Once the person has been inside the cell zone (outside it) for SETTLED_SAMPLES, the
    robot runs at the slow (full) speed; the person was inside for a while."""
    zone = outcome.areas["cell_zone"]
    inside = [zone.contains(s.person_xy) for s in outcome.samples]
    settled_inside = 0
    for k in range(SETTLED_SAMPLES, len(outcome.samples)):
        recent = inside[k - SETTLED_SAMPLES : k + 1]
        fraction = outcome.samples[k].speed_fraction
        if all(recent):
            settled_inside += 1
            assert fraction == pytest.approx(outcome.slow_speed), outcome.samples[k]
        elif not any(recent):
            assert fraction == 1.0, outcome.samples[k]
    assert settled_inside * SAMPLE_PERIOD >= 5.0, "the person hardly entered the cell"


def assert_safe(outcome: Outcome) -> None:
    assert outcome.safety.violations == 0
    assert outcome.safety.contacts == 0


def assert_consistent(outcome: Outcome) -> None:
    assert_finished_parts_reach_the_output_tray(outcome)
    assert_parts_stay_in_the_process(outcome)
    assert_slower_while_person_in_cell(outcome)
    assert_safe(outcome)
    assert not outcome.named("cycle_failed")


@pytest.fixture(scope="module")
def short_run() -> Outcome:
    return simulate(SHORT_SEED, duration=45.0)


def test_short_run_parts_keep_coming_while_the_person_works_in_the_cell(short_run):
    assert_parts_keep_coming(short_run, at_least=2, longest_gap=30.0)
    assert_finished_parts_reach_the_output_tray(short_run)
    assert_parts_stay_in_the_process(short_run)


def test_short_run_robot_is_slower_while_the_person_is_in_the_cell(short_run):
    assert short_run.named("add_part"), "the short seed's choices changed"
    assert_slower_while_person_in_cell(short_run)


def test_short_run_person_adds_a_part_the_robot_then_takes(short_run):
    """A part the person put into the input tray lies there, and the robot picks it up."""
    added = short_run.named("part_added")
    assert added, "the person added no part"
    for event in added:
        objects = {o.id: o for o in short_run.sample_after(event.time).objects}
        assert short_run.lies_in(objects[int(event.value)], "input_tray")
    first = int(added[0].value)
    assert any(
        o.id == first and o.holder == ROBOT_HOLDER
        for sample in short_run.samples
        if sample.time > added[0].time
        for o in sample.objects
    ), "the robot never took the part the person added"


def test_short_run_person_holds_what_they_carry(short_run):
    assert_holds_what_it_carries(short_run.realism)


def test_short_run_person_walks_without_sliding(short_run):
    assert_walks_like_a_person(short_run.realism)


def test_short_run_person_keeps_out_of_the_cell_and_the_objects(short_run):
    assert_keeps_out_of_things(short_run.realism)


def test_short_run_is_safe(short_run):
    assert_safe(short_run)
    assert not short_run.named("cycle_failed")


LONGEST_GAP = 50.0
"""s between finished parts at most. A person who adds a part and then inspects the output
keeps the robot slowed down for about 40 s (seed 4: 99.6-139.8 s, a 45.0 s gap); the
robot does not pause for anything else."""


@pytest.mark.long
@pytest.mark.parametrize("seed", range(10))
def test_production_and_the_persons_work_coexist(seed):
    outcome = simulate(seed, duration=load_scenario(SCENARIO).duration)
    assert_parts_keep_coming(outcome, at_least=5, longest_gap=LONGEST_GAP)
    assert_consistent(outcome)
    assert len({e.name for e in outcome.named(*ACTIVITIES)}) >= 4
    assert_within_the_audit_limits(outcome.realism)
