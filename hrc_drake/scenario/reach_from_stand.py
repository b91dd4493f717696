"""Where the person's hand goes against where the tree has them stand: a place or reach
target farther from the last walk's end (or the person's start) than a hand reaches
without walking fails the node at run time ("out of reach without walking"), so validate
says it first. So does a pick of an object that a NextObject finds in an area, for the
objects that lie there at the start (a pallet's far row: "hand stays 0.27 m from the
target", every time the person tried), or that its port names by number, where it lies
at the start (a sheet on a shelf's board: "the right arm would go 2.4 cm into"), and a
place after a pick of what a NextObject finds, for an object of the type it finds (a tote
put into a shelf's compartment from too close: "the head would go 3.4 cm into 'shelf'").

Where the person stands is the last walk, and what a pick takes what the last node that
wrote its `object_id` entry found or made (or where a put-down since left it), among the
earlier children of the Sequences above the node. A choice (Fallback, WeightedRandom,
Switch) before the node may have run any one of its children to success, and a node inside
one runs after its own branch, never a sibling's: each way (`ways_before`; a Switch on
the type of what a NextObject found only to its case, `switch_ways`) is followed,
each object it leaves (a NextObject's area, a SpawnObject's pose, a put-down's target)
judged on its own, its line naming where it comes from; the walks the ways end with are
judged together, as a walk's several targets are (which walk goes with which object is
often a condition of the tree). A Fallback's tries before the one that succeeded failed:
one that starts by looking for an object is judged as the run meets it, its NextObject
finding none (what ran before that in it has run, what it looked for is gone); where a try
fails otherwise, and the way's own branch has no walk or writer, nothing is said; nor after
a Parallel, a loop or a skippable walk (`RUN_ONCE` decorators are passed through), nor past
MAX_WAYS ways.
"""

from collections.abc import Callable, Iterator
from functools import partial

import numpy as np

from hrc_drake.bt import TreeNode
from hrc_drake.human.clip_files import clip_catalog
from hrc_drake.human.targeting import MAX_HORIZONTAL_REACH, TARGETED
from hrc_drake.known_values import Known
from hrc_drake.nodes.targeted import ActorPick, ActorPlace, ActorReach
from hrc_drake.scenario.located import Finding, Locator
from hrc_drake.scenario.switch_ways import ways_to
from hrc_drake.scenario.tree_ways import (
    UNKNOWN,
    Way,
    all_before,
    finder_of,
    held_at,
    parents_of,
    walk_before,
)

Resolve = Callable[[Known], np.ndarray | None]
"""A known pose value to its point in the world (None: not resolvable)."""
Taken = Callable[[TreeNode, Way], list[tuple[str, np.ndarray, Callable]]]
"""The objects a pick node may take the way the tree went, as far as known before the run:
a label, the centre,
and what keeps the person from taking it from a place to stand (the walk's known target,
None: the person's start): why the hands cannot get there, or ""."""
Placing = Callable[[TreeNode, np.ndarray, list, list, Way], Callable | None]
"""For the last pick before a place node, the place's target point, where the person may
stand at the pick (as `_stand_points`; [] when not known), every pick known to have run
before the place (what they took is gone) and the way the tree went: what keeps the person
from putting it down there (as `Taken`'s), or None when what the hands hold is unknown."""


def clip_step_back(clips: dict) -> float:
    """How far (m) a targeted clip moves the person's base before its hands arrive (the
    run measures the reach from there)."""
    steps = [0.0]
    for name, event in TARGETED.items():
        clip = clips[name]
        x, y = (clip.joint_names.index(axis) for axis in ("base_x", "base_y"))
        moved = clip.sample(clip.events[event]) - clip.sample(0.0)
        steps.append(float(np.hypot(moved[x], moved[y])))
    return max(steps)


def reach_findings(
    at: Locator,
    nodes: list[TreeNode],
    known: dict[tuple[int, str], list[Known]],
    resolve: Resolve,
    start: np.ndarray,
    clips: dict | None = None,
    taken: Taken | None = None,
    placing: Placing | None = None,
) -> Iterator[Finding]:
    """A Finding at each ActorPlace/ActorReach whose known target, and each ActorPick whose
    `taken` object, is farther from every place the person can stand there than a hand
    reaches, or that the hands cannot get to from all of them, each way the tree may go
    to the node (`known`: the known values by (id(node), port); `start`: the person's start
    on the floor), located by `at` (a parameter's at its line)."""
    limit = MAX_HORIZONTAL_REACH + clip_step_back(clips or clip_catalog())
    parents = parents_of(nodes)
    for node in nodes:
        if isinstance(node, ActorPick) and taken is not None:
            port = "object_id"
            targets = _each_way(node, parents, known, partial(taken, node))
        elif isinstance(node, ActorPlace | ActorReach):
            port = "target"
            targets = [(value, resolve(value), None) for value in known.get((id(node), port), ())]
            if isinstance(node, ActorPlace) and placing is not None:
                stands_at = partial(_stands_before, parents, known, resolve, start)
                placings = partial(_placings, node, parents, targets, placing, stands_at)
                targets = _each_way(node, parents, known, placings)
        else:
            continue
        stands = _stands_before(parents, known, resolve, start, node)
        if stands:
            yield from _judged(at, node, port, targets, stands, limit)


def _judged(at: Locator, node, port: str, targets, stands, limit: float) -> Iterator[Finding]:
    """The Findings of `reach_findings` at `node`, whose `targets` (with what keeps the
    person from each, and a note of where its object comes from) are done from wherever of
    `stands` the person stands."""
    for what, target, hindrance, *note in targets:
        if target is None:
            continue
        distance = min(float(np.hypot(*(target[:2] - s[:2]))) for s, _, _ in stands)
        if distance > limit:
            yield at.read(node, port, what, _too_far(what, target, distance, stands, limit), target)
        elif hindrance is not None:
            problems = [(hindrance(value), said) for _, said, value in stands]
            if all(problem for problem, _ in problems):
                problem, said = problems[0]
                done = "taken" if isinstance(node, ActorPick) else "put down"
                message = (
                    f"{what} at {point_text(target)}, {done} where the person stands "
                    f"({said}){''.join(note)}: {problem}"
                )
                yield at.read(node, port, what, message, target)


def _each_way(node, parents, known, targets: Callable[[Way], list]) -> list:
    """The `targets` of `node` each way the tree may go to it (`ways_to`), each once."""
    found: dict[tuple, tuple] = {}
    for way in ways_to(node, parents, known):
        for what, point, *rest in targets(way):
            key = (str(what), None if point is None else tuple(point), *rest[1:])
            found.setdefault(key, (what, point, *rest))
    return list(found.values())


def _chosen_object(place, parents, way: Way) -> str:
    """What the hands hold at `place` when a choice of the tree found or made it (its
    finder is known only the `way` the tree went), else ""."""
    pick = held_at(place, parents, way)
    finder = finder_of(pick, parents, way) if isinstance(pick, ActorPick) else None
    if finder is None or finder_of(pick, parents) is finder:
        return ""
    config = finder.config
    return f", holding what {config.registration_id} at {config.file}:{config.line} gave"


def _placings(place, parents, targets, placing: Placing, stands_at, way: Way) -> list:
    """`targets` of a place node with what keeps the person from putting down there what
    the last pick before it took the `way` the tree went (none when no pick is known to
    come before), and a note of where that came from (`_chosen_object`); `stands_at(pick,
    ways)`: where the person may stand at that pick (the way the tree went to it)."""
    pick = held_at(place, parents, way)
    if not isinstance(pick, ActorPick):
        return targets
    at_pick, picks = stands_at(pick, [way]), all_before(place, parents, ActorPick)
    note = _chosen_object(place, parents, way)
    return [
        (v, p, None if p is None else placing(pick, p, at_pick, picks, way), note)
        for v, p, _ in targets
    ]


def _stands_before(parents, known, resolve, start, node, ways=None) -> list:
    """Where the person may stand when `node` starts, whichever of `ways` (all) the tree
    went to it ([] when not known for one of them)."""
    points: dict[str, tuple] = {}
    for way in ways_to(node, parents, known) if ways is None else ways:
        stand = walk_before(node, parents, way)
        more = [] if stand is UNKNOWN else _stand_points(stand, known, resolve, start)
        if not more:
            return []
        points.update((said, (point, said, value)) for point, said, value in more)
    return list(points.values())


def _stand_points(stand, known, resolve, start) -> list[tuple[np.ndarray, str, Known | None]]:
    """The points the person can stand at (with what says so, and the walk's known target
    there): the walk's known targets, or the start when no walk comes before."""
    if stand is None:
        return [(np.asarray(start, dtype=float), "the person's start", None)]
    points = []
    for value in known.get((id(stand), "target"), ()):
        point = resolve(value)
        if point is None:
            return []
        config = stand.config
        said = f"{value}, {config.registration_id} at {config.file}:{config.line}"
        points.append((point, said, value))
    return points


def point_text(point) -> str:
    """A point as validate's messages give it: (x, y, z) to the centimetre."""
    return "(" + ", ".join(f"{v:.2f}" for v in point) + ")"


def _too_far(value, target, distance: float, stands, limit: float) -> str:
    nearest = min(stands, key=lambda s: np.hypot(*(target[:2] - s[0][:2])))[1]
    return (
        f"{value} at {point_text(target)} is {distance:.2f} m from where the person stands "
        f"({nearest}); a hand reaches at most {limit:.2f} m without walking: walk closer first"
    )
