"""The stored stopping data match a fresh measurement and cover every variant."""

import pytest

from hrc_drake.iisy import VARIANTS
from hrc_drake.motion.stopping import (
    STANDARD_MOTIONS_DEG,
    load_stopping_file,
    measure_stop,
    stopping_data,
)

MOTION = "A1 sweep, arm reaching out"


def test_every_variant_has_plausible_stopping_data():
    for variant in VARIANTS:
        data = stopping_data(variant)
        assert 0.05 < data.time < 2.0 and 0.01 < data.distance < 1.0
        assert data.distance <= data.speed * data.time  # braking, never speeding up


@pytest.mark.parametrize("variant", ["lbr_iisy3_r760"])
def test_stored_stop_matches_a_fresh_measurement(variant):
    stored = load_stopping_file()[variant]["motions"][MOTION]
    fresh = measure_stop(variant, *STANDARD_MOTIONS_DEG[MOTION])
    assert fresh.time == pytest.approx(stored["time"], abs=2e-3)
    assert fresh.distance == pytest.approx(stored["distance"], rel=0.02)
