"""Values no workcell can mean, with what was probably meant: sizes and masses in
millimetres and grams, places in millimetres, belt speeds in mm/s, angles in radians where
degrees are asked for (a located Finding each)."""

import math
from collections.abc import Iterator

import numpy as np
from pydrake.common.schema import Rotation, Transform

from hrc_drake.ergonomics.niosh import METRIC
from hrc_drake.scenario.located import Finding, Locator
from hrc_drake.scenario.schema import Scenario
from hrc_drake.yaml_check import schema_fields

LARGEST_OBJECT = 2.0
"""m: no side of an object the robot or person handles is longer (a euro pallet is 1.2 m)."""
HEAVIEST_LIFT = METRIC.load_constant
"""kg: the NIOSH lifting equation's load constant, the most anyone should lift under ideal
conditions (docs/ergonomics.md); the iisy's largest payload is 15 kg."""
FARTHEST = 50.0
"""m: no place in a workcell is farther from its origin."""
FASTEST_BELT = 2.0
"""m/s: faster than any conveyor a person works beside."""
RADIAN_TOLERANCE = 0.005
"""An angle in degrees within this of a multiple of pi/4 radians (0.785, 1.571, 3.142, ...)
looks like radians."""


def magnitude_findings(scenario: Scenario, at: Locator) -> Iterator[Finding]:
    """Values no cell can mean, with what was probably meant: sizes and masses in
    millimetres and grams, places in millimetres, angles in radians where degrees are
    asked for."""
    for name, kind in scenario.workpieces.types.items():
        where = ("workpieces", "types", name)
        if max(kind.size) > LARGEST_OBJECT:
            metres = [v / 1000 for v in kind.size]
            yield at.field(
                (*where, "size"),
                f"{_listed(kind.size)} m is larger than a workcell (sizes are in metres: "
                f"{_listed(metres)} for millimetres?)",
            )
        if kind.mass > HEAVIEST_LIFT:
            yield at.field(
                (*where, "mass"),
                f"{kind.mass:g} kg is more than a person may lift ({HEAVIEST_LIFT:g} kg, the "
                f"NIOSH load constant) or an iisy carry (masses are in kilograms: "
                f"{kind.mass / 1000:g} for grams?)",
            )
    for names, point in _points(scenario):
        if np.abs(point).max() > FARTHEST:
            yield at.field(names, _far(point))
    for name, belt in scenario.workpieces.conveyors.items():
        if belt.speed > FASTEST_BELT:
            yield at.field(
                ("workpieces", "conveyors", name, "speed"),
                f"{belt.speed:g} m/s is faster than any belt beside a person (in m/s: "
                f"{belt.speed / 1000:g} for mm/s?)",
            )
    for names, transform in _transforms(scenario, ()):
        yield from _transform_findings(names, transform, at)
    yield from _human_findings(scenario, at)
    yield from _configuration_findings(scenario, at)


def _human_findings(scenario: Scenario, at: Locator) -> Iterator[Finding]:
    if scenario.human is None:
        return
    x, y, yaw = scenario.human.start
    if max(abs(x), abs(y)) > FARTHEST:
        yield at.field(("human", "start"), _far(np.array([x, y])))
    if _looks_like_radians(yaw):
        yield at.field(("human", "start", 2), _radians(yaw))


def _configuration_findings(scenario: Scenario, at: Locator) -> Iterator[Finding]:
    """Joint angles are degrees; a configuration whose angles all lie within a turn in
    radians, some of them fractions, was written in radians."""
    for name, q in scenario.robot.configurations_deg.items():
        small = all(abs(v) <= 2 * math.pi + RADIAN_TOLERANCE for v in q)
        if small and any(v != round(v) for v in q):
            degrees = _listed(np.round(np.degrees(q)).tolist())
            yield at.field(
                ("robot", "configurations_deg", name),
                f"{_listed(q)} looks like radians; the angles are degrees: {degrees}?",
            )


def _transform_findings(names: tuple, transform: Transform, at: Locator) -> Iterator[Finding]:
    translation = np.asarray(transform.translation, dtype=float)
    if translation.size and np.abs(translation).max() > FARTHEST:
        yield at.field((*names, "translation"), _far(translation))
    rotation = transform.rotation.value
    if isinstance(rotation, Rotation.Rpy):
        for i, value in enumerate(rotation.deg):
            if _looks_like_radians(value):
                yield at.field((*names, "rotation", "deg", i), _radians(value))
    elif isinstance(rotation, Rotation.AngleAxis) and _looks_like_radians(rotation.angle_deg):
        yield at.field((*names, "rotation", "angle_deg"), _radians(rotation.angle_deg))


def _transforms(value, names: tuple) -> Iterator[tuple[tuple, Transform]]:
    """Every fixed Transform in the scenario with its field names (locations, the robot's
    base, the cell's welds, the objects' poses)."""
    if isinstance(value, Transform):
        if value.IsDeterministic():
            yield names, value
    elif isinstance(value, list | tuple):
        for i, item in enumerate(value):
            yield from _transforms(item, (*names, i))
    elif isinstance(value, dict):
        for key, item in value.items():
            yield from _transforms(item, (*names, key))
    elif (fields := schema_fields(type(value))) is not None:
        for name in fields:
            yield from _transforms(getattr(value, name), (*names, name))


def _points(scenario: Scenario) -> Iterator[tuple[tuple, np.ndarray]]:
    """The points given as lists: the areas' corners, the belts' ends."""
    for name, corners in scenario.areas.items():
        yield ("areas", name), np.asarray(corners, dtype=float)
    for name, belt in scenario.workpieces.conveyors.items():
        for end in ("start", "end"):
            yield ("workpieces", "conveyors", name, end), np.asarray(getattr(belt, end), float)


def _looks_like_radians(degrees: float) -> bool:
    quarter_turns = degrees / (math.pi / 4)
    near = abs(quarter_turns - round(quarter_turns)) * math.pi / 4 < RADIAN_TOLERANCE
    return near and 0 < abs(degrees) <= 2 * math.pi + RADIAN_TOLERANCE


def _radians(value: float) -> str:
    return (
        f"{value:g} looks like radians; the angle is in degrees: "
        f"{math.degrees(value):.0f} for {value:g} rad?"
    )


def _far(points: np.ndarray) -> str:
    """A point far off (or an area's corners), and what it is in millimetres."""
    farthest = np.abs(points).max()
    if points.ndim > 1:
        return (
            f"its corners lie up to {farthest:g} m from the origin (places are in metres: "
            "is the area in millimetres?)"
        )
    metres = _listed((points / 1000).round(4).tolist())
    return (
        f"{_listed(points.tolist())} lies {farthest:g} m from the origin (places are in "
        f"metres: {metres} for millimetres?)"
    )


def _listed(values) -> str:
    return "[" + ", ".join(f"{v:g}" for v in values) + "]"
