"""Moving objects: what the `hrc_drake.systems.workpieces.Workpieces` system is made of.

- `config`: the scenario's `workpieces:` section (types, initial objects and grids,
  conveyors, named surfaces, tolerances) and its semantic checks (`problems`).
- `messages`: commands (Spawn, Despawn, Attach, Release, Transfer), HandPoses, and the
  status every other system reads (objects with pose, velocity, holder, support, attributes;
  each issuer's last command result).
- `world`: the plain-Python world (state and update rules) the system steps.
- `geometry`, `surfaces`, `conveyors`, `layouts`: footprints and overlaps, support surfaces
  (derived from the cell's static collision geometry), belts, initial layouts.
"""
