"""One seed per run: every consumer of randomness gets its own stream spawned from it.

Streams are keyed by a stable name (not by creation order), so adding a system to a
diagram does not change the random choices of the others; a consumer that needs many
independent draws (one per spawned object, say) keys substreams of its own stream.
"""

import zlib

import numpy as np


def stream(seed: int, name: str) -> np.random.SeedSequence:
    """The run's independent SeedSequence for the consumer called `name`."""
    return np.random.SeedSequence(seed, spawn_key=(zlib.crc32(name.encode()),))


def substream(sequence: np.random.SeedSequence, *key: int) -> np.random.SeedSequence:
    """The independent part of `sequence` keyed by whole numbers `key`."""
    return np.random.SeedSequence(sequence.entropy, spawn_key=(*sequence.spawn_key, *key))
