"""The scenario's `workpieces:` section: object types, initial objects, conveyors, surfaces.

Plain dataclasses read with Drake's `yaml_load_typed` (every field has a default; poses are
Drake `Transform`s). `problems()` checks what the schema cannot, as (field path, message)
pairs relative to the section, so the scenario loader can name the file, line and field.
"""

import math
from dataclasses import dataclass, field

from pydrake.common.schema import Transform

from hrc_drake.workpieces.messages import COUPLING, COUPLINGS, Attributes
from hrc_drake.yaml_check import REQUIRED

BOX = "box"
CYLINDER = "cylinder"
SHAPES = (BOX, CYLINDER)
REMOVE = "remove"
QUEUE = "queue"
END_ACTIONS = (REMOVE, QUEUE)


@dataclass
class ObjectType:
    """A kind of object. `size` is [x, y, z] for a box and [radius, length] for a cylinder
    (axis z), as Drake's Box and Cylinder; the object's frame is at its centre. `capacity`
    is how many objects of this type can exist at once (initial ones included)."""

    shape: str = BOX
    size: list[float] = field(default_factory=lambda: [0.1, 0.1, 0.1])
    mass: float = 1.0
    color: list[float] = field(default_factory=lambda: [0.72, 0.55, 0.35, 1.0])
    capacity: int = 10
    attributes: Attributes = field(default_factory=dict)


@dataclass
class PlacedObject:
    """An object present from the start at `pose` (it settles onto what is below it)."""

    type: str = field(default="", metadata=REQUIRED)
    pose: Transform = field(default_factory=Transform)
    attributes: Attributes = field(default_factory=dict)


@dataclass
class GridLayout:
    """Objects in rows (along the origin's y), columns (along x) and layers, e.g. a loaded pallet.

    `origin` is the centre of the grid's bottom face (e.g. the pallet's top frame). `spacing`
    [dx, dy] defaults to the type's footprint (objects touching). Each place holds an object
    with probability `occupancy`; each boolean attribute in `attribute_probabilities` is true
    with its probability. Each attribute in `attribute_counts` is true for exactly that many
    of the grid's objects, never two counted attributes on one object (the last by name get
    fewer if too few places are occupied): every layout shows it, wherever it lands. All are
    drawn from the run's seed.
    """

    type: str = field(default="", metadata=REQUIRED)
    origin: Transform = field(default_factory=Transform)
    rows: int = 1
    columns: int = 1
    layers: int = 1
    spacing: list[float] = field(default_factory=list)
    occupancy: float = 1.0
    attributes: Attributes = field(default_factory=dict)
    attribute_probabilities: dict[str, float] = field(default_factory=dict)
    attribute_counts: dict[str, int] = field(default_factory=dict)


@dataclass
class ConveyorConfig:
    """A horizontal belt from `start` to `end` (points on its surface centre line, metres).

    Objects resting on it move towards `end` at `speed` (m/s). At the end they are removed
    (`remove`) or stop and queue behind each other with `queue_gap` between them (`queue`).
    """

    start: list[float] = field(default_factory=list, metadata=REQUIRED)
    end: list[float] = field(default_factory=list, metadata=REQUIRED)
    width: float = 0.4
    speed: float = 0.2
    at_end: str = QUEUE
    queue_gap: float = 0.0


@dataclass
class SurfaceConfig:
    """A named horizontal rectangle objects can rest on: `pose` is its centre, z up."""

    pose: Transform = field(default_factory=Transform)
    size: list[float] = field(default_factory=lambda: [1.0, 1.0])


@dataclass
class WorkpiecesConfig:
    """Moving objects of a scenario. Support surfaces are the top faces of the cell's static
    collision boxes and vertical cylinders (unless `derive_surfaces` is false), the named
    `surfaces`, the conveyors, the other objects and the floor (z = 0)."""

    types: dict[str, ObjectType] = field(default_factory=dict)
    objects: list[PlacedObject] = field(default_factory=list)
    grids: list[GridLayout] = field(default_factory=list)
    conveyors: dict[str, ConveyorConfig] = field(default_factory=dict)
    surfaces: dict[str, SurfaceConfig] = field(default_factory=dict)
    derive_surfaces: bool = True
    period: float = 0.01
    vacuum_tolerance: float = 0.01
    vacuum_max_tilt_deg: float = 15.0
    hand_tolerance: float = 0.05
    handover_tolerance: float = 0.05


Problem = tuple[tuple, str]


def problems(config: WorkpiecesConfig) -> list[Problem]:
    """Everything wrong with `config` that the schema cannot express, first problem first."""
    found: list[Problem] = []
    for name, object_type in config.types.items():
        found += _prefixed(("types", name), _type_problems(object_type))
    for i, placed in enumerate(config.objects):
        found += _prefixed(("objects", i), _known_type(config, placed.type))
    for i, grid in enumerate(config.grids):
        found += _prefixed(("grids", i), _grid_problems(config, grid))
    for name, conveyor in config.conveyors.items():
        found += _prefixed(("conveyors", name), _conveyor_problems(conveyor))
    for name, surface in config.surfaces.items():
        if len(surface.size) != 2 or min(surface.size) <= 0:
            found.append((("surfaces", name, "size"), "needs two positive lengths [x, y]"))
    found += _capacity_problems(config)
    found += _positive(config, ("period", "vacuum_tolerance", "hand_tolerance"))
    found += _positive(config, ("handover_tolerance",))
    return found


def initial_counts(config: WorkpiecesConfig) -> dict[str, int]:
    """The most objects of each type the initial layout can hold."""
    counts = dict.fromkeys(config.types, 0)
    for placed in config.objects:
        counts[placed.type] = counts.get(placed.type, 0) + 1
    for grid in config.grids:
        counts[grid.type] = counts.get(grid.type, 0) + grid.rows * grid.columns * grid.layers
    return counts


def _prefixed(prefix: tuple, found: list[Problem]) -> list[Problem]:
    return [((*prefix, *path), message) for path, message in found]


def _type_problems(object_type: ObjectType) -> list[Problem]:
    found = []
    if object_type.shape not in SHAPES:
        found.append((("shape",), f"unknown shape '{object_type.shape}'; known: box, cylinder"))
    lengths = 3 if object_type.shape == BOX else 2
    if len(object_type.size) != lengths or min(object_type.size, default=0) <= 0:
        what = "[x, y, z]" if object_type.shape == BOX else "[radius, length]"
        found.append((("size",), f"a {object_type.shape} needs {lengths} positive lengths {what}"))
    if not object_type.mass > 0:
        found.append((("mass",), f"must be positive, got {object_type.mass}"))
    if len(object_type.color) != 4 or not all(0 <= c <= 1 for c in object_type.color):
        found.append((("color",), "needs four values [r, g, b, a] between 0 and 1"))
    if object_type.capacity < 0:
        found.append((("capacity",), f"must not be negative, got {object_type.capacity}"))
    coupling = object_type.attributes.get(COUPLING)
    if coupling is not None and coupling not in COUPLINGS:
        known = ", ".join(COUPLINGS)
        found.append((("attributes", COUPLING), f"unknown coupling '{coupling}'; known: {known}"))
    return found


def _known_type(config: WorkpiecesConfig, name: str) -> list[Problem]:
    if name in config.types:
        return []
    return [(("type",), f"unknown object type '{name}'; known: {', '.join(sorted(config.types))}")]


def _grid_problems(config: WorkpiecesConfig, grid: GridLayout) -> list[Problem]:
    found = _known_type(config, grid.type)
    for name in ("rows", "columns", "layers"):
        if getattr(grid, name) < 1:
            found.append(((name,), f"must be at least 1, got {getattr(grid, name)}"))
    if grid.spacing and (len(grid.spacing) != 2 or min(grid.spacing) <= 0):
        found.append((("spacing",), "needs two positive distances [dx, dy]"))
    probabilities = {"occupancy": grid.occupancy} | {
        f"attribute_probabilities.{k}": p for k, p in grid.attribute_probabilities.items()
    }
    for name, p in probabilities.items():
        if not 0 <= p <= 1:
            found.append(((*name.split("."),), f"a probability must lie in [0, 1], got {p}"))
    return found + _count_problems(grid)


def _count_problems(grid: GridLayout) -> list[Problem]:
    found = []
    for name, count in grid.attribute_counts.items():
        where = ("attribute_counts", name)
        if count < 0:
            found.append((where, f"must not be negative, got {count}"))
        if name in grid.attribute_probabilities:
            found.append((where, "is also in attribute_probabilities; give it one or the other"))
    places = grid.rows * grid.columns * grid.layers
    total = sum(grid.attribute_counts.values())
    if total > places:
        found.append((("attribute_counts",), f"{total} counted objects exceed the {places} places"))
    return found


def _conveyor_problems(conveyor: ConveyorConfig) -> list[Problem]:
    found = []
    for name in ("start", "end"):
        if len(getattr(conveyor, name)) != 3:
            found.append(((name,), "needs a point [x, y, z]"))
    if found:
        return found
    if conveyor.start[2] != conveyor.end[2]:
        found.append((("end",), "the belt must be horizontal: start and end need the same z"))
    if math.dist(conveyor.start[:2], conveyor.end[:2]) <= 0:
        found.append((("end",), "the belt needs a length: end equals start"))
    if conveyor.at_end not in END_ACTIONS:
        found.append((("at_end",), f"unknown end action '{conveyor.at_end}'; known: queue, remove"))
    for name in ("width", "speed", "queue_gap"):
        if getattr(conveyor, name) < 0 or (name == "width" and conveyor.width == 0):
            found.append(((name,), f"must be positive, got {getattr(conveyor, name)}"))
    return found


def _capacity_problems(config: WorkpiecesConfig) -> list[Problem]:
    found = []
    for name, count in initial_counts(config).items():
        object_type = config.types.get(name)
        if object_type is not None and count > object_type.capacity:
            message = f"capacity {object_type.capacity} is less than the {count} initial objects"
            found.append((("types", name, "capacity"), message))
    return found


def _positive(config: WorkpiecesConfig, names: tuple[str, ...]) -> list[Problem]:
    values = {n: getattr(config, n) for n in names}
    return [((n,), f"must be positive, got {v}") for n, v in values.items() if v <= 0]
