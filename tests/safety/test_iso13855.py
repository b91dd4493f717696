"""ISO 13855's minimum distances and intrusion distances against the worked examples that
sensor makers publish in their operating instructions (hrc_drake.safety.iso13855; the
figures in docs/safety.md). Every expected value below is the source's own number, in mm.
"""

import pytest

from hrc_drake.safety.iso13855 import (
    horizontal_distance,
    horizontal_intrusion,
    lowest_horizontal_height,
    orthogonal_distance,
    orthogonal_intrusion,
)

MM = 1e-3


@pytest.mark.parametrize(
    ("stopping_time", "capability", "expected_mm", "source"),
    [
        # SICK C4000 operating instructions (8009861, 2012), "How to calculate the minimum
        # distance": machine 290 ms + curtain 30 ms, d = 14 mm: S = 2000 × 0.32 = 640 mm
        # > 500 mm, so S = 1600 × 0.32 = 512 mm.
        (0.32, 14, 512.0, "SICK C4000"),
        # SICK miniTwin4 operating instructions (8012624, 2018): the same example.
        (0.290 + 0.030, 14, 512.0, "SICK miniTwin4"),
        # Panasonic SF4-AH instruction manual (MJE-SF4A), calculation example 1: d = 30 mm,
        # curtain 11 ms; machine 0.1 s: S = 2000 × 0.111 + 128 = 350 mm.
        (0.1 + 0.011, 30, 350.0, "Panasonic SF4 (0.1 s)"),
        # ... machine 0.3 s: 2000 × 0.311 + 128 > 500, so 1600 × 0.311 + 128 = 626 mm.
        (0.3 + 0.011, 30, 626.0, "Panasonic SF4 (0.3 s)"),
        # wenglor SEMG412 manual, 5.4: d = 30 mm, t = 0.25 + 0.01 s: 648 mm > 500 mm,
        # so 1600 × 0.26 + 8 (30 − 14) = 544 mm.
        (0.25 + 0.01, 30, 544.0, "wenglor SEMG412"),
    ],
)
def test_light_curtain_minimum_distance(stopping_time, capability, expected_mm, source):
    assert orthogonal_distance(stopping_time, capability * MM) / MM == pytest.approx(
        expected_mm, abs=0.5
    ), source


@pytest.mark.parametrize(
    ("capability", "expected_mm"),
    [
        (14, 0.0),  # finger protection: no intrusion (SICK C4000, miniTwin4)
        (30, 128.0),  # 8 × (30 − 14) (Panasonic SF4, wenglor SEMG412)
        (40, 208.0),  # the largest d of C = 8 (d − 14) (ISO 13855, 6.2.3)
        (50, 850.0),  # reaching through with the arm (ISO 13855, 6.2.3)
    ],
)
def test_light_curtain_intrusion(capability, expected_mm):
    assert orthogonal_intrusion(capability * MM) / MM == pytest.approx(expected_mm, abs=1e-6)


@pytest.mark.parametrize(
    ("height_mm", "expected_mm"),
    [
        # C = 1200 mm − 0.4 H, at least 850 mm (Keyence SZ safety laser scanner, "Laser
        # scanner installation and safety distance"; SICK microScan3 operating
        # instructions, "Calculating the supplement C").
        (0, 1200.0),
        (300, 1080.0),
        (500, 1000.0),
        (875, 850.0),
        (1000, 850.0),  # 1200 − 400 = 800 is below the least C
    ],
)
def test_scanner_intrusion(height_mm, expected_mm):
    assert horizontal_intrusion(height_mm * MM) / MM == pytest.approx(expected_mm, abs=1e-6)


@pytest.mark.parametrize(
    ("capability", "expected_mm"),
    [
        # H ≥ 15 (d − 50 mm) (Keyence SZ; ISO 13855, 6.3). SICK microScan3: "for
        # hazardous area protection with a resolution of 70 mm, mount the safety laser
        # scanner at a height of at least 300 mm".
        (70, 300.0),
        (50, 0.0),
        (40, 0.0),  # finer than 50 mm may lie on the floor
        (116, 990.0),  # about the coarsest a 1000 mm high zone allows
    ],
)
def test_lowest_scan_plane(capability, expected_mm):
    assert lowest_horizontal_height(capability * MM) / MM == pytest.approx(expected_mm, abs=1e-6)


def test_scanner_minimum_distance():
    """S = 1600 mm/s × T + C (SICK S3000 and nanoScan3: "S = 1600 mm/s × T + 850 mm" for a
    scan plane high enough that C is the least; Keyence SZ: K × T + C)."""
    assert horizontal_distance(0.5, 0.875) / MM == pytest.approx(1600 * 0.5 + 850)
    # a 300 mm high scan plane (d = 70 mm), T = 0.5 s: 800 + 1080 mm
    assert horizontal_distance(0.5, 0.3) / MM == pytest.approx(1880.0)
