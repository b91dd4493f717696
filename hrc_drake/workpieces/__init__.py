"""Moving objects: what the `hrc_drake.systems.workpieces.Workpieces` system is made of.

- `config`: the scenario's `workpieces:` section (types, initial objects and grids,
  conveyors, named surfaces, tolerances) and its semantic checks (`problems`).
- `messages`: commands (Spawn, Despawn, Attach, Detach, Transfer), HandPoses, and the
  status every other system reads (objects with pose, velocity, holder, support, attributes;
  each issuer's last command result).
- the plain-Python world the system steps: `world` (the fixed rules of a run, the state at
  one time, the status), `update` (how the world starts and the order of an update), `step`
  (an update's working copy), `commands` (carrying out Spawn, Despawn, Attach, Detach,
  Transfer), `settling` (supports, falling, belts).
- `geometry`, `surfaces`, `conveyors`, `layouts`: footprints and overlaps, support surfaces
  (derived from the cell's static collision geometry), belts, initial layouts.
"""
