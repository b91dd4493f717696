"""What the person's update costs in a scenario's short run, and what the arms' check costs
with and without the feet placed.

The run is simulated once, the HumanActor's updates timed by this process's CPU time; at
every change of activity the arms' check of the new activity (`clearance.arm_correction`,
the largest single cost of an update that takes a command) is worked out twice in turn:
from the arms' poses, as the person does (the feet left unplaced: they move no arm), and
from the full poses (feet placed, as before). The two must give the same correction, bit
for bit; their CPU times are compared in the same process.

With `--against REV`, every update's pose is then worked out again from the state it left
(posing: `pose_at`, the plant's positions and the reported frames), in turn with the code
of git revision REV (POSING_CODE: legs, stepping, walking, the actor) and the current code,
best of `--repeats` (this process's CPU time): printed are the µs per update, over all
updates and over those that walk (the legs place the feet), their ratio and the largest
difference between the poses.

    .venv/bin/python benchmarks/human_update.py [--duration 30] [--against REV [--repeats 5]]
        [coexistence collaboration ...]
"""

import sys
import time
from pathlib import Path
from types import FunctionType, ModuleType

import numpy as np
from pydrake.systems.analysis import Simulator

from hrc_drake.builder import build_diagram
from hrc_drake.human.activity import Activity
from hrc_drake.human.protocol import pose_at
from hrc_drake.human.walking import WalkSegment
from hrc_drake.scenario import load_scenario
from hrc_drake.systems.human_actor import HumanActor

sys.path.insert(0, str(Path(__file__).resolve().parent))
from realism_cost import SHORT_RUNS, short_runs_parser  # noqa: E402
from revision import module_at  # noqa: E402


class Clocks:
    """CPU seconds of the person's updates and of the arms' checks both ways, while in use."""

    def __init__(self):
        self.update = 0.0
        self.arms = 0.0
        self.full = 0.0
        self.checks = 0
        self.differing = 0
        self.updates = []
        """(actor, state it left, t) of every update."""
        self._originals = (HumanActor._update, Activity._arms_clear, Activity._blended_pose)

    def __enter__(self):
        update, arms_clear, blended = self._originals

        def timed_update(actor, context, state):
            start = time.process_time()
            update(actor, context, state)
            self.update += time.process_time() - start
            left = state.get_mutable_abstract_state(actor._actor).get_value()
            self.updates.append((actor, left, context.get_time()))

        def both_ways(activity, performer, t):
            start = time.process_time()
            correction = arms_clear(activity, performer, t)
            self.arms += time.process_time() - start
            Activity._blended_pose = lambda a, p, u, arms_only=False: blended(a, p, u)
            start = time.process_time()
            full = arms_clear(activity, performer, t)
            self.full += time.process_time() - start
            Activity._blended_pose = blended
            self.checks += 1
            self.differing += not _same(correction, full)
            return correction

        HumanActor._update, Activity._arms_clear = timed_update, both_ways
        return self

    def __exit__(self, *exc):
        HumanActor._update, Activity._arms_clear, Activity._blended_pose = self._originals


def _same(a, b) -> bool:
    """Whether two activities' corrections (head, then arms) are the same, key for key."""
    return len(a) == len(b) and all(
        x.times == y.times
        and all(np.array_equal(u, v) for u, v in zip(x.offsets, y.offsets, strict=True))
        for x, y in zip(a, b, strict=True)
    )


def _ratio(numerator: float, denominator: float) -> str:
    return f"ratio {numerator / denominator:.2f}" if denominator > 0 else "no ratio"


POSING_CODE = {
    "hrc_drake.human.legs": "hrc_drake/human/legs.py",
    "hrc_drake.human.stepping": "hrc_drake/human/stepping.py",
    "hrc_drake.human.walking": "hrc_drake/human/walking.py",
    "hrc_drake.systems.human_actor": "systems/human_actor.py",
}
"""The modules whose code `--against` takes from the older revision (by git path)."""
POSING_CLASSES = (WalkSegment, HumanActor)
"""Classes whose methods the older code replaces in turn (the run's states hold them)."""


def code_of_revision(revision: str) -> dict[str, ModuleType]:
    """POSING_CODE as it is at git `revision`, each a module of its own, using one
    another's older names where they import them from each other."""
    modules = {
        name: module_at(revision, path, f"{name}@{revision}") for name, path in POSING_CODE.items()
    }
    for module in modules.values():
        for key, value in list(vars(module).items()):
            older = modules.get(getattr(value, "__module__", ""))
            if older is not None and hasattr(older, key):
                setattr(module, key, getattr(older, key))
    return modules


def methods_of(modules: dict[str, ModuleType] | None) -> dict:
    """Per class of POSING_CLASSES, its methods: of its older version in `modules`, or
    the current ones (None)."""
    methods = {}
    for cls in POSING_CLASSES:
        source = cls if modules is None else getattr(modules[cls.__module__], cls.__name__)
        methods[cls] = {k: v for k, v in vars(source).items() if isinstance(v, FunctionType)}
    return methods


def posing(updates: list[tuple], with_legs, methods: dict) -> tuple[float, float, np.ndarray]:
    """CPU seconds of posing every update again (all, and those that walk), `with_legs`
    placing the feet and `methods` (methods_of) in place, and the poses."""
    actor, _, _ = updates[0]
    performer = actor._performer
    performer.__dict__["legs"] = with_legs  # the cached_property's slot
    for cls, functions in methods.items():
        for name, function in functions.items():
            setattr(cls, name, function)
    poses, walking = [], 0.0
    start = time.process_time()
    for _, state, t in updates:
        begun = time.process_time()
        q = pose_at(performer, state, t)
        actor._frames(performer.body.plant_positions(q))
        if isinstance(state.activity._segment_at(t), WalkSegment):
            walking += time.process_time() - begun
        poses.append(q)
    return time.process_time() - start, walking, np.array(poses)


def compare_posing(updates: list[tuple], revision: str, repeats: int) -> str:
    """Posing the run's updates with the code of `revision` and the current code, in turn."""
    performer = updates[0][0]._performer
    older = code_of_revision(revision)
    ways = {
        "old": (older["hrc_drake.human.legs"].Legs(performer.body), methods_of(older)),
        "new": (performer.legs, methods_of(None)),
    }
    best = {way: (np.inf, np.inf) for way in ways}
    poses = {}
    for _ in range(repeats):
        for way, code in ways.items():
            total, walking, poses[way] = posing(updates, *code)
            best[way] = tuple(map(min, best[way], (total, walking)))
    posing(updates[:1], *ways["new"])  # the current code back in place
    walks = sum(isinstance(s.activity._segment_at(t), WalkSegment) for _, s, t in updates)
    per = {way: (1e6 * a / len(updates), 1e6 * b / max(walks, 1)) for way, (a, b) in best.items()}
    return (
        f"  posing {len(updates)} updates ({walks} walking), code of {revision} vs now: "
        f"{per['old'][0]:.0f} -> {per['new'][0]:.0f} us per update "
        f"({_ratio(per['old'][0], per['new'][0])}), walking {per['old'][1]:.0f} -> "
        f"{per['new'][1]:.0f} us ({_ratio(per['old'][1], per['new'][1])}); poses differ by "
        f"at most {np.max(np.abs(poses['old'] - poses['new'])):.1e}"
    )


def main() -> None:
    parser = short_runs_parser(__doc__)
    parser.add_argument("--against", help="git revision whose legs to compare posing with")
    parser.add_argument("--repeats", type=int, default=5)
    args = parser.parse_args()
    for name in args.scenarios:
        with Clocks() as clocks:
            simulator = Simulator(build_diagram(load_scenario(name, [("seed", SHORT_RUNS[name])])))
            simulator.Initialize()
            start = time.process_time()
            simulator.AdvanceTo(args.duration)
            total = time.process_time() - start - clocks.full  # the run as the person runs it
        print(
            f"{name} seed {SHORT_RUNS[name]}, {args.duration:.0f} s: the person's updates "
            f"{clocks.update - clocks.full:.2f} s of {total:.2f} s CPU "
            f"({(clocks.update - clocks.full) / total:.1%}); arms' checks at "
            f"{clocks.checks} changes of activity: {clocks.arms:.2f} s from the arms' poses, "
            f"{clocks.full:.2f} s from the full poses ({_ratio(clocks.arms, clocks.full)}), "
            f"{clocks.differing} corrections differing"
        )
        if args.against:
            print(compare_posing(clocks.updates, args.against, args.repeats))


if __name__ == "__main__":
    main()
