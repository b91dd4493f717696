"""The capsule broad phase: vectorized segment distances against dense sampling."""

import numpy as np
import pytest

from hrc_drake.safety.kernels import segment_distances

SAMPLES = np.linspace(0.0, 1.0, 401)


def sampled_distance(p, u, q, w) -> float:
    """Closest pair of 401 × 401 points along the two segments (an upper bound)."""
    a = p + SAMPLES[:, None] * u
    b = q + SAMPLES[:, None] * w
    return float(np.linalg.norm(a[:, None] - b[None], axis=-1).min())


def test_segment_distances_match_sampling_including_points_and_parallels():
    rng = np.random.default_rng(7)
    p, u = rng.normal(size=(6, 3)), rng.normal(size=(6, 3))
    q, w = rng.normal(size=(5, 3)), rng.normal(size=(5, 3))
    u[0] = 0.0  # a point
    w[1] = 0.0  # a point
    w[2] = -0.5 * u[2]  # parallel to a_2
    q[3] = p[3] + 0.5 * u[3]  # crossing a_3 at its middle
    w[3] = np.cross(u[3], [0.0, 0.0, 1.0])
    distances = segment_distances(p, u, q, w)
    for i in range(len(p)):
        for j in range(len(q)):
            sampled = sampled_distance(p[i], u[i], q[j], w[j])
            assert distances[i, j] <= sampled + 1e-12
            assert distances[i, j] == pytest.approx(sampled, abs=5e-3)
    assert distances[3, 3] == pytest.approx(0.0, abs=1e-12)
