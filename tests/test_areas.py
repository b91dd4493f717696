"""Named areas: polygons triangulated for containment and uniform sampling."""

import numpy as np
import pytest

from hrc_drake.areas import Area

L_SHAPE = [[0, 0], [2, 0], [2, 1], [1, 1], [1, 2], [0, 2]]


def test_l_shape_triangulation_covers_its_area():
    area = Area.from_polygon(L_SHAPE)
    assert area.area == pytest.approx(3.0)
    assert area.contains([0.5, 1.5]) and area.contains([1.5, 0.5])
    assert not area.contains([1.5, 1.5])


def test_clockwise_polygon_gives_the_same_area():
    assert Area.from_polygon(L_SHAPE[::-1]).area == pytest.approx(3.0)


def test_samples_fall_inside_and_spread_evenly():
    area = Area.from_polygon(L_SHAPE)
    rng = np.random.default_rng(1)
    points = np.array([area.sample(rng) for _ in range(3000)])
    assert all(area.contains(p) for p in points)
    per_square = [
        np.sum((points[:, 0] // 1 == i) & (points[:, 1] // 1 == j))
        for i, j in [(0, 0), (1, 0), (0, 1)]
    ]
    assert min(per_square) > 900 and max(per_square) < 1100


@pytest.mark.parametrize(
    "points", [[[0, 0], [1, 1]], [[0, 0], [1, 1], [2, 2]], [[0, 0], [1, 1], [1, 0], [0, 1]]]
)
def test_invalid_polygons_are_rejected(points):
    with pytest.raises(ValueError):
        Area.from_polygon(points)
