"""Picks of what a belt carries off, known before a run: an ActorPick whose object a
NextObject finds in an area lying on a belt that carries its objects off its end (`at_end:
remove`) takes an object that is moving, and the person refuses such a pick when it starts
(hrc_drake.nodes.targeted.riding): aimed where it was, the hands would close where it no
longer is (a user's palm went 14.4 cm into a carton). `validate` says so at the pick."""

from collections.abc import Iterator

from hrc_drake.areas import Area
from hrc_drake.bt import TreeNode
from hrc_drake.nodes.objects import NextObject
from hrc_drake.nodes.targeted import ActorPick
from hrc_drake.scenario.located import Finding, Locator
from hrc_drake.scenario.tree_ways import object_source, parents_of, ways_before
from hrc_drake.tree_types import AreaRef
from hrc_drake.workpieces.config import WorkpiecesConfig
from hrc_drake.workpieces.conveyors import Belt

AROUND = 0.1
"""m: an area drawn round a belt up to this far beyond its edges lies on it."""


def belt_pick_findings(
    nodes: list[TreeNode], known: dict, areas: dict[str, Area], workpieces: WorkpiecesConfig
) -> Iterator[Finding]:
    """A Finding at each pick's `object_id` for each area on a removing belt that the
    NextObject it takes from, each way the tree goes to it, looks in (`known`: the known
    values by (id(node), port); `areas`: the scenario's areas by name)."""
    belts = [Belt.of(name, c) for name, c in workpieces.conveyors.items()]
    carrying_off = [belt for belt in belts if not belt.queues]
    if not carrying_off:
        return
    parents = parents_of(nodes)
    for pick in (n for n in nodes if isinstance(n, ActorPick)):
        for finder, area, belt in _on_belts(pick, parents, known, areas, carrying_off):
            yield Locator.node(pick, "object_id", _message(finder, area, belt))


def _on_belts(pick: ActorPick, parents: dict, known: dict, areas: dict, belts: list[Belt]):
    """(the NextObject, the area's name, the belt it lies on) of each area on one of
    `belts` that a NextObject the pick takes from looks in, each once."""
    finders = [object_source(pick, parents, way) for way in ways_before(pick, parents)]
    said = set()
    for finder in (f for f in finders if isinstance(f, NextObject)):
        for area in known.get((id(finder), "area"), ()):
            name = area.value.name if isinstance(area.value, AreaRef) else None
            belt = _belt_under(areas.get(name), belts)
            if belt is not None and (id(finder), name) not in said:
                said.add((id(finder), name))
                yield finder, name, belt


def _belt_under(area: Area | None, belts: list[Belt]) -> Belt | None:
    """The belt the whole area lies on (within AROUND of its edges), if any: an area that
    reaches beyond it (the whole cell) may find objects elsewhere."""
    if area is None:
        return None
    corners = area.triangles.reshape(-1, 2)
    for belt in belts:
        e, half = belt.extent(corners), belt.width / 2 + AROUND
        if e.back > -AROUND and e.front < belt.length + AROUND and -half < e.right < e.left < half:
            return belt
    return None


def _message(finder: NextObject, area: str, belt: Belt) -> str:
    config = finder.config
    return (
        f"takes what {config.registration_id} ({config.file}:{config.line}) finds in area "
        f"'{area}', which lies on belt '{belt.name}': that belt carries its objects off its "
        "end (at_end: remove), so what the pick takes is moving and the person refuses it "
        "when the pick starts; have the belt queue them (at_end: queue) and take one where "
        "it comes to rest, or take it before it goes on the belt"
    )
