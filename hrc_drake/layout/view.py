"""The layout view: a top view of the cell per height the robot's tool works at, drawn with
matplotlib (no simulation), and written as PNG or SVG.

Each panel shows the furniture with its name and heights, the floor the person may not walk
on (the body's clearance round the furniture and the robot's inner space), the robot's reach
with the tool down at that height (green, darker where more of the tool's orientation range
reaches; red where the arm reaches but would touch the cell), the robot targets at that
height, the named places, areas and starting objects, the safety sensors with their fields
(the whole cell), and every finding of `validate` numbered at its point (listed below the
panels).
"""

import hashlib
import io
import math
import pickle
import textwrap
from pathlib import Path

import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.colors import ListedColormap  # noqa: E402
from matplotlib.figure import Figure  # noqa: E402
from matplotlib.patches import FancyArrowPatch, PathPatch  # noqa: E402
from matplotlib.path import Path as MplPath  # noqa: E402
from shapely.geometry import MultiPolygon, Polygon  # noqa: E402

from hrc_drake.layout.cell import CellLayout  # noqa: E402
from hrc_drake.layout.reach_map import DIRECTIONS, TILT, ReachMap  # noqa: E402

PANEL_INCHES = 6.0
DPI = 110
CHARS_PER_INCH = 14
"""Of the 8 pt monospace text under the panels."""
TEXT_LINE_INCHES = 0.16
MARGIN = 0.4
"""m round everything drawn."""
PERSON_RADIUS = 0.2
REACH_COLOURS = plt.get_cmap("Greens")
BLOCKED_COLOUR = "#e7298a"
FINDING_COLOUR = "#d7301f"
PROTECTIVE_COLOUR, WARNING_COLOUR = "#cb181d", "#fd8d3c"
DRAWN_KEPT = 8
"""Drawn layout files kept per process (the last ones)."""
_drawn: dict[tuple[str, str], bytes] = {}
"""The files this process drew lately, by the layout's content and the file type."""


def draw_layout(layout: CellLayout) -> Figure:
    """The whole cell (with the reach at the lowest height), then the robot's working area
    at each height its tool works at."""
    panels = [(layout.reach[0] if layout.reach else None, _bounds(layout), True)]
    panels += [(reach, _reach_bounds(reach), False) for reach in layout.reach]
    width = PANEL_INCHES * len(panels)
    chars = int(width * CHARS_PER_INCH)
    notes = [*textwrap.wrap(_legend(), chars), *_finding_lines(layout, chars)]
    text_inches = TEXT_LINE_INCHES * (len(notes) + 1)
    height = PANEL_INCHES + text_inches + 0.6
    figure = plt.figure(figsize=(width, height))
    bottom = (text_inches + 0.5) / height
    grid = figure.add_gridspec(
        1,
        len(panels),
        left=0.06 / len(panels) + 0.02,
        right=0.98,
        bottom=bottom,
        top=1 - 0.6 / height,
        wspace=0.25,
    )
    for i, (reach, bounds, whole) in enumerate(panels):
        _panel(figure.add_subplot(grid[0, i]), layout, reach, bounds, whole)
    figure.text(
        0.01,
        (text_inches + 0.05) / height,
        "\n".join(notes),
        va="top",
        ha="left",
        family="monospace",
        fontsize=8,
    )
    figure.suptitle(f"{layout.name}: the cell from above ({layout.variant})")
    return figure


def write_layout(layout: CellLayout, path: Path) -> Path:
    """PNG or SVG by the file's suffix; the same layout gives the same bytes (drawn once
    per process: every run directory of a scenario shows the same layout)."""
    kind = path.suffix.lower().lstrip(".")
    key = (hashlib.sha256(pickle.dumps(layout)).hexdigest(), kind)
    if key not in _drawn:
        if len(_drawn) >= DRAWN_KEPT:
            del _drawn[next(iter(_drawn))]
        _drawn[key] = _layout_file(layout, kind)
    path.write_bytes(_drawn[key])
    return path


def _layout_file(layout: CellLayout, kind: str) -> bytes:
    figure = draw_layout(layout)
    written = io.BytesIO()
    with plt.rc_context({"svg.hashsalt": "hrc_drake-layout"}):
        metadata = {"Date": None} if kind == "svg" else None
        figure.savefig(written, format=kind, dpi=DPI, metadata=metadata)
    plt.close(figure)
    return written.getvalue()


def _panel(ax, layout: CellLayout, reach: ReachMap | None, bounds, whole: bool) -> None:
    _fill(ax, layout.blocked, facecolor="#eeeeee", edgecolor="#bbbbbb", hatch="///", lw=0.5)
    if reach is not None:
        _reach(ax, reach)
    xs, ys, no_room = layout.no_room
    if no_room.any():
        ax.contour(
            xs,
            ys,
            no_room.astype(float),
            levels=[0.5],
            colors="#756bb1",
            linewidths=0.8,
            linestyles=":",
        )
    for piece in layout.furniture:
        _fill(ax, piece.outline, facecolor="#d9c7a3", edgecolor="#5b4a2f", lw=1.0, alpha=0.8)
        heights = f"{piece.surface:.2f} m"
        if piece.top - piece.surface > 0.005:
            heights += f" (top {piece.top:.2f})"
        point = piece.outline.representative_point()
        ax.text(
            point.x,
            point.y,
            f"{piece.name}\n{heights}",
            ha="center",
            va="center",
            fontsize=7,
            color="#3b2f1e",
            clip_on=True,
        )
    for name, area in layout.areas.items():
        _fill(ax, area, facecolor="none", edgecolor="#3182bd", lw=1.0, ls="--")
        x, y = area.exterior.coords[0]
        ax.text(x, y, f" {name}", fontsize=7, color="#3182bd", va="bottom", clip_on=True)
    _objects(ax, layout)
    if whole:
        _sensors(ax, layout)
    _places(ax, layout, whole)
    if reach is not None and not whole:
        _targets(ax, layout, reach)
    ax.plot(*layout.robot_xy, marker="P", color="black", ms=8)
    _findings(ax, layout)
    (x0, y0), (x1, y1) = bounds
    ax.set_xlim(x0, x1)
    ax.set_ylim(y0, y1)
    ax.set_aspect("equal", adjustable="box")
    ax.grid(True, lw=0.3, alpha=0.5)
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_title(_title(reach, whole), fontsize=9)


def _title(reach: ReachMap | None, whole: bool) -> str:
    if whole:
        return "the whole cell: walkable floor, places, areas"
    how = "a linear move's end" if reach.linear else "keeping clearance"
    title = f"tool down at z = {reach.height:.3f} m ({how})"
    if not (reach.share.any() or reach.blocked.any()):
        title += ": out of the arm's reach"
    return title


def _reach(ax, reach: ReachMap) -> None:
    """The reach map's cells as a polar mesh round the base axis."""
    step_r = reach.radii[1] - reach.radii[0]
    step_a = reach.azimuths[1] - reach.azimuths[0]
    radii = np.append(reach.radii - step_r / 2, reach.radii[-1] + step_r / 2)
    azimuths = np.append(reach.azimuths - step_a / 2, reach.azimuths[-1] + step_a / 2)
    A, R = np.meshgrid(azimuths, radii, indexing="ij")
    X = reach.centre[0] + R * np.cos(A)
    Y = reach.centre[1] + R * np.sin(A)
    share = np.ma.masked_equal(reach.share, 0.0)
    ax.pcolormesh(
        X,
        Y,
        share,
        cmap=REACH_COLOURS,
        vmin=-0.3,
        vmax=1.0,
        alpha=0.75,
        shading="flat",
        edgecolors="none",
        antialiased=False,
        rasterized=True,
        gid="reach",
    )
    blocked = np.ma.masked_equal(reach.blocked.astype(float), 0.0)
    ax.pcolormesh(
        X,
        Y,
        blocked,
        cmap=ListedColormap([BLOCKED_COLOUR]),
        alpha=0.35,
        shading="flat",
        edgecolors="none",
        antialiased=False,
        rasterized=True,
    )


def _objects(ax, layout: CellLayout) -> None:
    labelled = set()
    for obj in layout.objects:
        _fill(ax, obj.outline, facecolor="#6baed6", edgecolor="#08519c", lw=0.6)
        if obj.group not in labelled:
            labelled.add(obj.group)
            count = sum(o.group == obj.group for o in layout.objects)
            name = obj.label.split(" ")[0] + (f" x{count}" if count > 1 else "")
            x, y = obj.outline.centroid.coords[0]
            ax.text(
                x,
                y,
                f" {name} (top {obj.top:.2f})",
                fontsize=6,
                color="#08519c",
                va="top",
                clip_on=True,
            )


def _places(ax, layout: CellLayout, whole: bool) -> None:
    """Places to stand everywhere; places above the floor on the whole cell (the robot's
    show as its targets on the others)."""
    for place in layout.places:
        x, y, z = place.position
        if place.yaw is not None or abs(z) < 1e-6:
            _person(ax, x, y, place.yaw, "#756bb1")
            ax.text(
                x,
                y - PERSON_RADIUS,
                place.name,
                fontsize=7,
                color="#54278f",
                ha="center",
                va="top",
                clip_on=True,
            )
        elif whole:
            ax.plot(x, y, marker="D", ms=4, color="#54278f")
            ax.text(x, y, f" {place.name} (z {z:.2f})", fontsize=7, color="#54278f", clip_on=True)
    if layout.person_start is not None:
        x, y, yaw = layout.person_start
        _person(ax, x, y, yaw, "#fd8d3c")
        ax.text(
            x,
            y + PERSON_RADIUS,
            "person's start",
            fontsize=7,
            color="#a63603",
            ha="center",
            va="bottom",
            clip_on=True,
        )


def _sensors(ax, layout: CellLayout) -> None:
    """Each scanner (a triangle, named) with its protective (red) and warning (orange)
    fields, one outline per speed set labelled with its speed, the slower sets dashed; each
    light curtain a red line."""
    for name, scanner in layout.sensors.scanners.items():
        x, y = scanner.pose[:2]
        ax.plot(x, y, marker="^", ms=8, color=PROTECTIVE_COLOUR, gid=f"scanner-{name}")
        ax.text(x, y, f" {name}", fontsize=7, color=PROTECTIVE_COLOUR, va="top", clip_on=True)
        fastest = max((s.speed for s in scanner.fields), default=0.0)
        for fields in scanner.fields:
            style = {"ls": "-" if fields.speed == fastest else "--", "lw": 1.0}
            for kind, colour in (("protective", PROTECTIVE_COLOUR), ("warning", WARNING_COLOUR)):
                points = getattr(fields, kind)
                if len(points) < 3:
                    continue
                gid = f"{name}-{kind}-{fields.speed:g}"
                _fill(ax, Polygon(points), facecolor="none", edgecolor=colour, gid=gid, **style)
                px, py = points[0]
                label = f"{name} {kind} {fields.speed:.0%}"
                ax.text(px, py, label, fontsize=6, color=colour, va="bottom", clip_on=True)
    for name, curtain in layout.sensors.light_curtains.items():
        (x0, y0), (x1, y1) = curtain.ends
        ax.plot([x0, x1], [y0, y1], color=PROTECTIVE_COLOUR, lw=2.0)
        ax.text((x0 + x1) / 2, (y0 + y1) / 2, f" {name}", fontsize=7, color=PROTECTIVE_COLOUR)


def _person(ax, x, y, yaw, colour) -> None:
    ax.add_patch(plt.Circle((x, y), PERSON_RADIUS, fill=False, color=colour, lw=1.0))
    if yaw is not None:
        ahead = (x + 0.35 * math.cos(yaw), y + 0.35 * math.sin(yaw))
        ax.add_patch(
            FancyArrowPatch((x, y), ahead, arrowstyle="->", mutation_scale=10, color=colour)
        )


def _targets(ax, layout: CellLayout, reach: ReachMap) -> None:
    heights = sorted({r.height for r in layout.reach})
    upper = next((h for h in heights if h > reach.height), math.inf)
    for target in layout.targets:
        if reach.height <= target.position[2] < upper:
            x, y, z = target.position
            ax.plot(x, y, marker="o", ms=4, color="black")
            if target.label:
                ax.text(x, y, f" {target.label}", fontsize=7, fontweight="bold", clip_on=True)


def _findings(ax, layout: CellLayout) -> None:
    """An X at each finding's point, numbered as listed (one label for those at one point)."""
    numbers: dict[tuple, list[int]] = {}
    for n, finding in enumerate(layout.findings, 1):
        if finding.point is None:
            continue
        x, y = finding.point[:2]
        ax.plot(x, y, marker="X", ms=11, color=FINDING_COLOUR, mec="white", gid=f"finding-{n}")
        numbers.setdefault((round(x, 2), round(y, 2)), []).append(n)
    for (x, y), ns in numbers.items():
        ax.text(
            x,
            y,
            "  " + ",".join(map(str, ns)),
            color=FINDING_COLOUR,
            fontsize=9,
            fontweight="bold",
            va="center",
            clip_on=True,
        )


def _finding_lines(layout: CellLayout, chars: int) -> list[str]:
    if not layout.findings:
        return ["validate finds nothing in this scenario."]
    lines = [f"validate's findings ({len(layout.findings)}, marked X where they are):"]
    for n, finding in enumerate(layout.findings, 1):
        lines += textwrap.wrap(f"{n}. {finding}", chars, subsequent_indent="   ")
    return lines


def _legend() -> str:
    return (
        "green: the tool reaches straight down (darker: it can also tilt "
        f"{math.degrees(TILT):.0f}° every way; {DIRECTIONS} directions); pink: the arm "
        "reaches but would touch the cell; hatched: no walking (the body's clearance, "
        "the robot's inner space); "
        "dotted purple: closer than this, a person has no room to stand and turn; "
        "circles: places to stand (arrow: facing); dots: robot targets at that height; "
        "red triangle: a safety scanner, red and orange outlines: its protective and warning "
        "fields per speed set (dashed: the slower sets); red line: a light curtain"
    )


def _bounds(layout: CellLayout):
    points = [layout.robot_xy]
    for shape in [f.outline for f in layout.furniture] + list(layout.areas.values()):
        x0, y0, x1, y1 = shape.bounds
        points += [(x0, y0), (x1, y1)]
    points += [p.position[:2] for p in layout.places]
    points += [f.point[:2] for f in layout.findings if f.point is not None]
    for scanner in layout.sensors.scanners.values():
        points += [scanner.pose[:2]]
        points += [p for s in scanner.fields for p in (*s.protective, *s.warning)]
    points += [end for curtain in layout.sensors.light_curtains.values() for end in curtain.ends]
    if layout.person_start is not None:
        points.append(layout.person_start[:2])
    for reach in layout.reach:
        points += list(_reach_bounds(reach))
    xy = np.array(points, dtype=float)
    return xy.min(axis=0) - MARGIN, xy.max(axis=0) + MARGIN


def _reach_bounds(reach: ReachMap):
    """Round the reach map's cells that reach or touch, square."""
    k = np.nonzero(reach.share.any(axis=0) | reach.blocked.any(axis=0))[0]
    r = (reach.radii[k.max()] if k.size else reach.radii[-1]) + MARGIN
    centre = np.array(reach.centre)
    return centre - r, centre + r


def _fill(ax, shape, **style) -> None:
    """A shapely polygon (or several, with holes) as one patch."""
    polygons = shape.geoms if isinstance(shape, MultiPolygon) else [shape]
    for polygon in polygons:
        if not isinstance(polygon, Polygon) or polygon.is_empty:
            continue
        rings = [polygon.exterior, *polygon.interiors]
        vertices = np.concatenate([np.asarray(r.coords) for r in rings])
        codes = np.concatenate(
            [
                [MplPath.MOVETO] + [MplPath.LINETO] * (len(r.coords) - 2) + [MplPath.CLOSEPOLY]
                for r in rings
            ]
        )
        ax.add_patch(PathPatch(MplPath(vertices, codes), **style))
