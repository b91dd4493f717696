"""Ergonomic evaluation of the person's work: RULA and REBA posture scores and the revised
NIOSH lifting equation (pure domain code; docs/ergonomics.md has the methods' sources and
how every input is taken from the simulated skeleton)."""
