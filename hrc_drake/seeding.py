"""One seed per run: every consumer of randomness gets its own stream spawned from it.

Streams are keyed by a stable name (not by creation order), so adding a system to a
diagram does not change the random choices of the others.
"""

import zlib

import numpy as np


def stream(seed: int, name: str) -> np.random.SeedSequence:
    """The run's independent SeedSequence for the consumer called `name`."""
    return np.random.SeedSequence(seed, spawn_key=(zlib.crc32(name.encode()),))


def generator(seed: int | np.random.SeedSequence, name: str = "") -> np.random.Generator:
    sequence = seed if isinstance(seed, np.random.SeedSequence) else stream(seed, name)
    return np.random.default_rng(sequence)
