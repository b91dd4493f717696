"""What `hrc-drake validate` can know of a scenario's safety sensors without simulating: each
problem as (field names below `safety`, message), which the scenario loader and validate
locate in the file (hrc_drake.scenario.checks, hrc_drake.scenario.findings).

- values: a scan plane on or below the floor or above ISO 13855's 1 m, too low for the
  detection capability (H ≥ 15 (d − 50 mm)), a response faster than a scan, fields that are
  no polygons or reach beyond the scanner's range, beams farther apart out there than the
  detection capability, no field set for full speed;
- placement in the cell: a scanner or a light curtain's post inside the cell's geometry, a
  light curtain's beam blocked by it, its lowest beam above 0.3 m or its highest below
  0.9 m (ISO 13855: a person crawls under it, or steps or reaches over it);
- the protective fields against ISO 13855's minimum distance S = K·T + C (+ Z_d): at every
  speed level of the field sets, the fields together, each only where its scanner sees
  past the cell's fixed geometry, must hold every place a person can walk to within S of
  the robot's reach (the reach of the variant plus the tool, about the A1 axis), with T the
  sensor's response time, the monitor's and the command's period and the robot's measured
  stop from that speed (hrc_drake.safety.stopping). Walking distance: the cell's furniture
  is walked round, not through, and so is a light curtain that stands S from the reach
  (crossing it, a person is seen in time). A field's blind part only counts where it is a
  way in: it reaches the walk's edge at S or lies outside every field; a blind pocket that
  the seen field encloses is entered seen. Each such line says where a person is unseen:
  outside every field, or behind which piece of the cell (hrc_drake.safety.ways_in).

The scenario loader refuses a scenario with the first of these; `validate` lists them all
(hrc_drake.scenario.findings). What a scanner cannot see behind objects (they move), and a
person who stands unseen in a blind pocket after being seen on the way in, are not checked
here: that is what a run shows, and what `hrc-drake falsify` searches for.
"""

import math
from collections.abc import Iterable, Iterator
from dataclasses import dataclass

import numpy as np
import shapely
from shapely.geometry import LineString, Point, Polygon
from shapely.ops import unary_union

from hrc_drake.iisy import VARIANTS
from hrc_drake.safety.config import MEASURED, SafetyConfig
from hrc_drake.safety.iso13855 import (
    COARSEST,
    HIGHEST_HORIZONTAL,
    K_WALK,
    LOWEST_BEAM_AT_MOST,
    TOP_BEAM_AT_LEAST,
    horizontal_distance,
    lowest_horizontal_height,
    orthogonal_distance,
)
from hrc_drake.safety.sensors import LaserScanner, LightCurtain, SensorsConfig
from hrc_drake.safety.sensors_cell import Cell, cell_of, inside
from hrc_drake.safety.sensors_raycast import cast
from hrc_drake.safety.sensors_reading import beams
from hrc_drake.safety.sensors_view import active_set
from hrc_drake.safety.stopping import StopModel
from hrc_drake.safety.ways_in import WAVE_STEP, shadows, unseen_places, ways_in
from hrc_drake.station import StationSpec

Problem = tuple[tuple | None, str]


def sensor_problems(
    config: SafetyConfig, station: StationSpec, command_latency: float
) -> Iterator[Problem]:
    """The problems of `config.sensors` in the cell of `station` (see the module
    docstring); `command_latency` is the robot's command period (s)."""
    sensors = config.sensors
    if not sensors.present:
        return
    found = list(_value_problems(config))
    yield from found
    if found or station.variant not in VARIANTS:
        return
    cell = cell_of(station)
    for name, scanner in sensors.scanners.items():
        housing = inside(cell, scanner.origin())
        if housing:
            where = ("sensors", "scanners", name, "pose")
            yield where, f"the scanner at {_xyz(scanner.origin())} is inside {housing}"
    timing = _Timing(config, StopModel.of_variant(station.variant), command_latency)
    barriers = []
    for name, curtain in sensors.light_curtains.items():
        found = [
            *_curtain_placement(curtain, cell),
            *_beam_height_problems(*curtain.heights),
            *_curtain_distance(curtain, cell, timing),
        ]
        yield from _prefixed(("sensors", "light_curtains", name), found)
        if not found:
            barriers.append(_barrier(curtain))
    yield from _field_problems(sensors, cell, timing, tuple(barriers))


def _barrier(curtain: LightCurtain) -> Polygon:
    """The curtain as a wall the walk from the reach goes round (crossing it, a person is
    seen in time): thicker than a step of the walk, which would otherwise step through it
    where it has come round a post."""
    return LineString(curtain.ends).buffer(WAVE_STEP / 2)


def _prefixed(names: tuple, found: Iterable[Problem]) -> Iterator[Problem]:
    return (((*names, *where), message) for where, message in found)


def _xyz(point) -> str:
    return "[" + ", ".join(f"{v:.2f}" for v in point) + "]"


# --- values -------------------------------------------------------------------------------


def _value_problems(config: SafetyConfig) -> Iterator[Problem]:
    sensors = config.sensors
    if config.v_h_rule == MEASURED:
        yield (
            ("v_h_rule",),
            ("a safety sensor measures no body speed: with sensors use iso13855 or constant"),
        )
    if not 0.0 < sensors.reduced_speed <= 1.0:
        yield ("sensors", "reduced_speed"), f"must lie within 0..1, got {sensors.reduced_speed}"
    shared = set(sensors.scanners) & set(sensors.light_curtains)
    for name in sorted(shared):
        yield ("sensors", "light_curtains", name), f"'{name}' is already a scanner's name"
    for name, scanner in sensors.scanners.items():
        yield from _prefixed(("sensors", "scanners", name), _scanner_values(scanner))
    for name, curtain in sensors.light_curtains.items():
        yield from _prefixed(("sensors", "light_curtains", name), _curtain_values(curtain))


def _positive(scanner_or_curtain, names: tuple[str, ...]) -> Iterator[Problem]:
    for name in names:
        value = getattr(scanner_or_curtain, name)
        if not value > 0.0:
            yield (name,), f"must be positive, got {value}"


def _scanner_values(scanner: LaserScanner) -> Iterator[Problem]:
    if len(scanner.pose) != 3:
        yield ("pose",), "needs [x, y, yaw_deg]"
        return
    numbers = ("resolution_deg", "range", "scan_time", "detection_capability")
    found = list(_positive(scanner, numbers))
    yield from found
    if scanner.measurement_error < 0.0:
        yield ("measurement_error",), f"must not be negative, got {scanner.measurement_error}"
    if scanner.response_time < scanner.scan_time:
        yield (
            ("response_time",),
            (
                f"{scanner.response_time} s is shorter than a scan ({scanner.scan_time} s): "
                "the scanner reports a scan when it is done"
            ),
        )
    if found:
        return
    yield from _height_problems(scanner)
    low, high = scanner.angles_deg if len(scanner.angles_deg) == 2 else (0.0, -1.0)
    if not low < high <= low + 360.0:
        yield ("angles_deg",), f"needs [first, last] within one turn, got {scanner.angles_deg}"
    yield from _field_set_problems(scanner)


def _height_problems(scanner: LaserScanner) -> Iterator[Problem]:
    height, capability = scanner.height, scanner.detection_capability
    lowest = lowest_horizontal_height(capability)
    if height <= 0.0:
        yield ("height",), f"the scan plane lies on or below the floor ({height} m)"
    elif height > HIGHEST_HORIZONTAL:
        yield (
            ("height",),
            (
                f"{height} m: ISO 13855 puts a horizontal detection zone at most "
                f"{HIGHEST_HORIZONTAL} m high"
            ),
        )
    elif height < lowest - 1e-9:
        yield (
            ("height",),
            (
                f"{height} m is too low for a detection capability of {capability * 1000:g} mm: "
                f"ISO 13855 needs H ≥ 15 (d − 50 mm) = {lowest:.3f} m, so that a leg crosses "
                "the scan plane"
            ),
        )


def _field_set_problems(scanner: LaserScanner) -> Iterator[Problem]:
    if scanner.fields and max(s.speed for s in scanner.fields) != 1.0:
        yield ("fields",), "no field set guards full speed: the highest `speed` must be 1"
    for k, field_set in enumerate(scanner.fields):
        if not 0.0 < field_set.speed <= 1.0:
            yield ("fields", k, "speed"), f"must lie within 0..1, got {field_set.speed}"
        for kind in ("protective", "warning"):
            polygon, problem = _polygon(getattr(field_set, kind))
            problem = problem or (_reach_problem(scanner, polygon) if polygon else "")
            if problem:
                yield ("fields", k, kind), problem


def _reach_problem(scanner: LaserScanner, polygon: Polygon) -> str:
    """A field beyond the scanner's range, or where its beams spread wider than what it is
    rated to detect."""
    far = max(math.dist(scanner.pose[:2], p) for p in polygon.exterior.coords)
    spread = far * math.radians(scanner.resolution_deg)
    where = f"reaches {far:.2f} m from the scanner"
    if far > scanner.range:
        return f"{where}, beyond its range of {scanner.range} m"
    if spread > scanner.detection_capability:
        return (
            f"{where}, where beams {scanner.resolution_deg}° apart are {spread * 1000:.0f} mm "
            f"apart: more than its detection capability of "
            f"{scanner.detection_capability * 1000:g} mm"
        )
    return ""


def _polygon(corners) -> tuple[Polygon | None, str]:
    """The field's polygon (None: no field), or what is wrong with it."""
    if not corners:
        return None, ""
    if len(corners) < 3 or any(len(p) != 2 for p in corners):
        return None, "needs at least three corners [x, y] (or none: no field)"
    polygon = Polygon(corners)
    if not polygon.is_valid or polygon.area <= 0.0:
        return None, f"is not a simple polygon: {shapely.is_valid_reason(polygon)}"
    return polygon, ""


def _curtain_values(curtain: LightCurtain) -> Iterator[Problem]:
    if len(curtain.ends) != 2 or any(len(p) != 2 for p in curtain.ends):
        yield ("ends",), "needs the two posts [[x, y], [x, y]]"
    elif math.dist(*curtain.ends) <= 0.0:
        yield ("ends",), "the two posts stand in one place"
    if len(curtain.heights) != 2 or not 0.0 < curtain.heights[0] <= curtain.heights[1]:
        yield ("heights",), (f"needs [lowest, highest] beam above the floor, got {curtain.heights}")
    if not 0.0 < curtain.resolution <= COARSEST:
        yield (
            ("resolution",),
            (
                f"must lie within 0..{COARSEST} m (the detection capabilities ISO 13855 places "
                f"light curtains for), got {curtain.resolution}"
            ),
        )
    yield from _positive(curtain, ("response_time",))


def _beam_height_problems(lowest: float, highest: float) -> Iterator[Problem]:
    """A curtain a person crawls under or steps or reaches over (ISO 13855 clause 6.2, a
    curtain against whole-body access; Table 1 has no upper edge below 0.9 m)."""
    if lowest > LOWEST_BEAM_AT_MOST + 1e-9:
        yield (
            ("heights",),
            _beam_height("lowest", lowest, "crawls under", "at most", LOWEST_BEAM_AT_MOST),
        )
    if highest < TOP_BEAM_AT_LEAST - 1e-9:
        yield (
            ("heights",),
            _beam_height(
                "highest", highest, "steps or reaches over", "at least", TOP_BEAM_AT_LEAST
            ),
        )


def _beam_height(beam: str, height: float, how: str, bound: str, limit: float) -> str:
    return (
        f"the {beam} beam is {height} m above the floor: a person {how} it (ISO 13855 puts "
        f"it {bound} {limit} m high)"
    )


def _curtain_placement(curtain: LightCurtain, cell: Cell) -> Iterator[Problem]:
    for k, (x, y) in enumerate(curtain.ends):
        for height in (curtain.heights[0], curtain.heights[1]):
            housing = inside(cell, np.array([x, y, height]))
            if housing:
                yield ("ends", k), f"the post at [{x:.2f}, {y:.2f}] is inside {housing}"
                return
    origins, directions, length = beams(curtain)
    ranges, which = cast(origins, directions, length, cell.shapes, cell.poses)
    for k in np.flatnonzero(which >= 0):
        yield (
            ("heights",),
            (
                f"the beam {origins[k][2]:.2f} m high is blocked by the cell's "
                f"{cell.names[which[k]]} {ranges[k]:.2f} m from the first post"
            ),
        )
        return


# --- ISO 13855's minimum distance ----------------------------------------------------------


@dataclass(frozen=True)
class _Timing:
    """What T is made of besides the sensor's response: the monitor's period and the
    command's latency, and the robot's stop from a speed."""

    config: SafetyConfig
    stop: StopModel
    command_latency: float

    def stopping_time(self, response_time: float, speed: float) -> float:
        return response_time + self.config.period + self.command_latency + self.stop.time(speed)

    def explain(self, response_time: float, speed: float) -> str:
        total = self.stopping_time(response_time, speed)
        lead = self.config.period + self.command_latency
        return (
            f"T = {total:.3f} s: response {response_time:g} s, monitor and command {lead:g} s, "
            f"stop from {speed:.0%} speed {self.stop.time(speed):.3f} s"
        )


def scanner_distance(scanner: LaserScanner, timing: _Timing, speed: float) -> float:
    """ISO 13855's S of the scanner's protective field for the robot at `speed`, with its
    measurement error Z_d added."""
    stopping_time = timing.stopping_time(scanner.response_time, speed)
    return horizontal_distance(stopping_time, scanner.height) + scanner.measurement_error


def _field_problems(
    sensors: SensorsConfig, cell: Cell, timing: _Timing, barriers: tuple[Polygon, ...]
) -> Iterator[Problem]:
    """At each speed level, the scanners' active protective fields, each only where its
    scanner sees past the cell's fixed geometry, together against the largest S among
    them; the way through a light curtain that stands at its own S (`barriers`) is the
    curtain's to guard."""
    guarded = {name: s for name, s in sensors.scanners.items() if s.fields}
    levels = sorted({f.speed for s in guarded.values() for f in s.fields}, reverse=True)
    hazard = Point(*cell.base).buffer(cell.reach)
    blind = {name: shadows(scanner, cell) for name, scanner in guarded.items()}
    hidden = {name: unary_union(list(by_blocker.values())) for name, by_blocker in blind.items()}
    for speed in levels:
        chosen = {name: active_set(s.fields, speed) for name, s in guarded.items()}
        fields = {n: _polygon(s.fields[chosen[n]].protective)[0] for n, s in guarded.items()}
        drawn = unary_union([f for f in fields.values() if f])
        covered = unary_union([f.difference(hidden[n]) for n, f in fields.items() if f])
        name, scanner = max(guarded.items(), key=lambda i: scanner_distance(i[1], timing, speed))
        distance = scanner_distance(scanner, timing, speed)
        gap = ways_in(hazard, distance, (*cell.obstacles, *barriers), covered, drawn, scanner)
        if not gap.is_empty:
            where = ("sensors", "scanners", name, "fields", chosen[name], "protective")
            places = unseen_places(gap, hazard, drawn, fields, blind)
            yield where, f"{_too_small(scanner, timing, speed, cell)}; {places}"


def _too_small(scanner, timing: _Timing, speed: float, cell: Cell) -> str:
    distance = scanner_distance(scanner, timing, speed)
    return (
        f"too small for ISO 13855's minimum distance at {speed:.0%} speed: S = K·T + C + Z_d "
        f"= {distance:.2f} m round the robot's reach ({cell.reach:.2f} m about its base), "
        f"with K {K_WALK} m/s, {timing.explain(scanner.response_time, speed)}, "
        f"C {scanner.intrusion:.2f} m {scanner.height} m high, Z_d {scanner.measurement_error} m"
    )


def _curtain_distance(curtain: LightCurtain, cell: Cell, timing: _Timing) -> Iterator[Problem]:
    """The curtain closer to the robot's reach than ISO 13855's S."""
    hazard = Point(*cell.base).buffer(cell.reach)
    stopping_time = timing.stopping_time(curtain.response_time, 1.0)
    distance = orthogonal_distance(stopping_time, curtain.resolution)
    apart = LineString(curtain.ends).distance(hazard)
    if apart < distance:
        yield (
            ("ends",),
            (
                f"{apart:.2f} m from the robot's reach ({cell.reach:.2f} m about its base), "
                f"closer than ISO 13855's minimum distance S = K·T + C = {distance:.2f} m "
                f"({timing.explain(curtain.response_time, 1.0)}, C {curtain.intrusion:.3f} m "
                f"for a resolution of {curtain.resolution * 1000:g} mm)"
            ),
        )
