"""Short (and `-m long`) runs of the three bundled scenarios."""
