"""The bundled scenarios' person picks places to stand at random within areas (a spot at the
bench to work at, somewhere in the hall to look around): every place such an area can give
has room to stand there and step round on the spot without any body part entering the
cell's geometry (issue #26: cooperation's bench spots were 0.15 m from the bench, where a
person turning goes into it). `hrc-drake validate` checks the named locations; these areas
only the trees know."""

from math import radians

import numpy as np
import pytest

from hrc_drake.builder import build_diagram
from hrc_drake.scenario import load_scenario

STANDING_AREAS = [
    ("cooperation", "work_area", 90.0),
    ("coexistence", "hall_walk", None),
]
"""(scenario, area, the way its trees face a place there in degrees; None: any way)."""
SPACING = 0.05
"""m: the grid of places tried over each area."""


def navigation_of(name: str):
    built = []
    build_diagram(load_scenario(name), attach=lambda _, station: built.append(station))
    return built[0].human.navigation


def grid_over(area) -> list[tuple[float, float]]:
    corners = area.triangles.reshape(-1, 2)
    (x0, y0), (x1, y1) = corners.min(axis=0), corners.max(axis=0)
    xs = np.arange(x0, x1 + SPACING / 2, SPACING)
    ys = np.arange(y0, y1 + SPACING / 2, SPACING)
    return [(x, y) for x in xs for y in ys if area.contains((x, y))]


@pytest.mark.parametrize(("name", "area_name", "facing"), STANDING_AREAS)
def test_every_place_an_area_gives_the_person_has_room_to_stand_and_turn(name, area_name, facing):
    navigation = navigation_of(name)
    yaw = None if facing is None else radians(facing)
    places = grid_over(load_scenario(name).area(area_name))
    without_room = [
        f"({x:.2f}, {y:.2f}): {problem}"
        for x, y in places
        if (problem := navigation.stand_problem(x, y, yaw)) is not None
    ]
    assert places
    assert not without_room, f"{len(without_room)} of {len(places)}: {without_room[:3]}"
