"""A loaded pallet from a grid layout: the same for the same seed, different for another,
every carton rests on the pallet or on the carton below it, and counted attributes are on
exactly their number of cartons."""

import numpy as np
import pytest
from pydrake.geometry import SceneGraph

from hrc_drake.seeding import stream
from hrc_drake.systems.workpieces import Workpieces
from hrc_drake.wiring import WORKPIECES_SYSTEM
from hrc_drake.workpieces.config import GridLayout
from hrc_drake.workpieces.layouts import grid_placements
from tests.workpieces.workpieces_rig import load_example

PALLET_TOP = 0.144
CARTON_HEIGHT = 0.2


def pallet(seed: int) -> list:
    workpieces = Workpieces(load_example(), SceneGraph(), stream(seed, WORKPIECES_SYSTEM))
    status = workpieces.GetOutputPort("workpieces_status").Eval(workpieces.CreateDefaultContext())
    return [o for o in status.objects if o.type == "carton"]


def layout(cartons) -> list:
    return [(tuple(o.pose.translation()), o.attributes) for o in cartons]


def test_the_same_seed_gives_the_same_layout_and_attributes():
    assert layout(pallet(7)) == layout(pallet(7))


def test_another_seed_gives_another_layout():
    assert layout(pallet(7)) != layout(pallet(8))


@pytest.mark.parametrize("seed", [7, 8])
def test_attributes_are_drawn_per_carton_over_the_type_defaults(seed):
    cartons = pallet(seed)
    assert 0 < len(cartons) <= 32
    assert {"defective", "graspable", "fragile", "label"} == set(cartons[0].attributes)
    assert {o.attributes["label"] for o in cartons} == {"A-113"}
    assert len({o.attributes["defective"] for o in cartons}) == 2


@pytest.mark.parametrize("seed", [7, 8])
def test_every_carton_rests_on_the_pallet_or_on_a_carton(seed):
    cartons = {o.id: o for o in pallet(seed)}
    for carton in cartons.values():
        bottom = carton.pose.translation()[2] - CARTON_HEIGHT / 2
        below = carton.supporting_object
        if below is None:
            assert carton.support == "euro_pallet"
            assert bottom == pytest.approx(PALLET_TOP)
        else:
            assert bottom == pytest.approx(cartons[below].pose.translation()[2] + CARTON_HEIGHT / 2)
            np.testing.assert_allclose(
                carton.pose.translation()[:2], cartons[below].pose.translation()[:2]
            )


COUNTED = GridLayout(
    type="carton", rows=2, columns=2, occupancy=0.85, attribute_counts={"fragile": 1, "porous": 1}
)


def counted_layout(seed: int) -> list:
    carton = load_example().types["carton"]
    return grid_placements(COUNTED, carton, np.random.default_rng(seed))


def test_counted_attributes_are_on_exactly_their_count_of_distinct_objects():
    sizes = set()
    for seed in range(40):
        placements = counted_layout(seed)
        sizes.add(len(placements))
        flags = [(p.attributes["fragile"], p.attributes["porous"]) for p in placements]
        assert [sum(f[0] for f in flags), sum(f[1] for f in flags)] == [1, 1]
        assert (True, True) not in flags
    assert {3, 4} <= sizes, "the seeds should cover pallets with an empty place"


def test_counted_attributes_land_on_places_drawn_with_the_seed():
    def fragile_place(seed: int) -> tuple:
        return next(
            tuple(p.pose.translation()) for p in counted_layout(seed) if p.attributes["fragile"]
        )

    assert fragile_place(3) == fragile_place(3)
    assert len({fragile_place(seed) for seed in range(40)}) == 4
