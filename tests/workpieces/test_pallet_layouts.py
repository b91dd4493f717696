"""A loaded pallet from a grid layout: the same for the same seed, different for another,
and every carton rests on the pallet or on the carton below it."""

import numpy as np
import pytest
from pydrake.geometry import SceneGraph
from workpieces_rig import load_example

from hrc_drake.systems.workpieces import Workpieces

PALLET_TOP = 0.144
CARTON_HEIGHT = 0.2


def pallet(seed: int) -> list:
    workpieces = Workpieces(load_example(), SceneGraph(), seed=seed)
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
