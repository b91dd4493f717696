"""timeline.png (separation and S_p, with safety sensors what they sensed and when they did
not see the person; speed scale, speeds, actor states and task events over time) and
heatmap.png (top view: where the person was, where separation was smallest, and the cell's
furniture)."""

import math
from pathlib import Path

import numpy as np

from hrc_drake.evaluation.figures import save_figure
from hrc_drake.evaluation.record import Footprint
from hrc_drake.messages import TaskEvent
from hrc_drake.safety.log import signal

HEAT_CELL = 0.1
"""m per heat-map cell."""
LEGEND_COLUMNS = 4
LEGEND_ROW = 0.22
"""Height of a legend row, in the figure's height ratios."""
SPEEDS = {
    "robot_speed": ("robot: fastest point", "tab:blue"),
    "approach_speed": ("robot: towards the person (v_r)", "tab:cyan"),
    "walking_speed": ("person: walking (pelvis)", "tab:orange"),
    "human_approach": ("person: closest region towards the robot", "tab:red"),
}
"""The speeds panel: signal -> (legend, colour); docs/safety.md defines them."""
FURNITURE = "0.35"
"""The heat map's colour of the cell's furniture (a grey both colour maps set off)."""
LABEL = {"facecolor": "white", "alpha": 0.7, "edgecolor": "none", "pad": 1.0}


def plot_timeline(
    path: Path,
    times: np.ndarray,
    signals: np.ndarray,
    states: dict[str, list[tuple[float, str]]] | None = None,
    events: list[TaskEvent] | None = None,
) -> Path:
    """`states`: per actor, (time, state) changes; `events`: task events from the trees."""
    return save_figure(timeline_figure(times, signals, states, events), path)


def timeline_figure(times, signals, states=None, events=None):
    """The figure of `plot_timeline`; its fourth axes holds the activity rows."""
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(
        5, 1, figsize=(11, 10), height_ratios=(3, 1.6, 2.4, 2.6, 1), layout="constrained"
    )
    for ax in axes[1:4]:
        ax.sharex(axes[0])
    _separation_panel(axes[0], times, signals)
    axes[1].step(times, signal(signals, "scale"), where="post", color="tab:green")
    axes[1].set_ylim(-0.05, 1.05)
    axes[1].set_ylabel("speed scale")
    for name, (label, color) in SPEEDS.items():
        axes[2].plot(times, signal(signals, name), color=color, label=label, lw=1)
    axes[2].set_ylabel("m/s")
    axes[2].legend(fontsize=7, loc="upper right")
    end = float(times[-1]) if times.size else 0.0
    axes[0].set_xlim(0.0, max(end, 1e-3))
    for ax in axes[:3]:
        ax.tick_params(labelbottom=False)
    axes[3].set_xlabel("time (s)")
    fig.get_layout_engine().execute(fig)  # the panels laid out (not drawn): labels measured
    _activity_panel(axes[3], axes[4], states or {}, events or [], end)
    return fig


def _separation_panel(ax, times, signals) -> None:
    ax.plot(times, signal(signals, "separation"), label="separation", color="black")
    ax.plot(times, signal(signals, "protective"), label="S_p", color="tab:red", ls="--")
    seen = signal(signals, "seen")
    if np.isfinite(seen).any():  # safety sensors: what they reported, and when not
        sensed = signal(signals, "sensed_separation")
        ax.plot(times, sensed, label="sensed separation", color="tab:blue", lw=0.9)
        sensed_sp = signal(signals, "sensed_protective")
        ax.plot(times, sensed_sp, label="S_p (sensed)", color="tab:blue", ls=":", lw=0.9)
        _shade(ax, times, seen == 0, "0.6", "person not seen")
    _shade(ax, times, signal(signals, "violation") > 0, "tab:red", "SSM violation")
    _shade(ax, times, signal(signals, "contact") > 0, "purple", "contact")
    ax.set_ylabel("m")
    ax.legend(fontsize=7, loc="upper right")


def activity(actor: str, state: str) -> str:
    """What a timeline row shows of a state: a tree's running path is named by its second
    node (the activity under the tree's top loop, e.g. `CarryBoxToConveyor`), without the
    `::uid` suffixes."""
    if not actor.endswith("tree"):
        return state
    names = [part.split("::")[0] for part in state.split("/") if part]
    return names[min(1, len(names) - 1)] if names else ""


def spans(changes: list[tuple[float, str]], end: float, label) -> list[tuple[float, float, str]]:
    """(start, stop, label) of each stretch with one label; empty labels are gaps."""
    merged: list[list] = []
    for start, state in changes:
        text = label(state)
        if merged and merged[-1][2] == text:
            continue
        if merged:
            merged[-1][1] = start
        merged.append([start, end, text])
    return [(a, b, text) for a, b, text in merged if text and b > a]


def _activity_panel(ax, legend_ax, states, events, end: float) -> None:
    """One row per actor, its states as coloured spans, labelled where the label fits in
    its span; the others, and the task events, are named in the legend below."""
    import matplotlib.pyplot as plt
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch

    palette = plt.get_cmap("tab20").colors
    renderer = ax.figure.canvas.get_renderer()
    unlabelled: dict[str, tuple] = {}
    for row, (actor, changes) in enumerate(states.items()):
        colours: dict[str, tuple] = {}
        for start, stop, text in spans(changes, end, lambda state, a=actor: activity(a, state)):
            colour = colours.setdefault(text, palette[len(colours) % len(palette)])
            ax.barh(row, stop - start, left=start, height=0.7, color=colour, alpha=0.7)
            label = ax.text((start + stop) / 2, row, text, fontsize=6, ha="center", va="center")
            if not _fits(ax, label, stop - start, renderer):
                label.remove()
                unlabelled.setdefault(f"{actor}: {text}", colour)
    names = sorted({event.name for event in events})
    event_colours = {name: plt.get_cmap("Dark2").colors[i % 8] for i, name in enumerate(names)}
    for event in events:
        ax.axvline(event.time, color=event_colours[event.name], lw=0.9)
    ax.set_yticks(range(len(states)), list(states))
    ax.set_ylim(-0.6, max(len(states), 1) - 0.4)
    ax.set_ylabel("actors")
    legend_ax.axis("off")
    handles = [Patch(color=c, alpha=0.7, label=text) for text, c in unlabelled.items()]
    handles += [Line2D([], [], color=c, label=f"event: {n}") for n, c in event_colours.items()]
    if handles:
        legend_ax.legend(
            handles=handles, loc="upper center", ncol=LEGEND_COLUMNS, fontsize=6, frameon=False
        )
    ratios = list(legend_ax.get_gridspec().get_height_ratios())
    ratios[-1] = 0.3 + LEGEND_ROW * math.ceil(len(handles) / LEGEND_COLUMNS)
    legend_ax.get_gridspec().set_height_ratios(ratios)
    if not handles:
        legend_ax.text(0.5, 0.5, "no actor states or task events logged", ha="center", color="gray")


def _fits(ax, label, width: float, renderer) -> bool:
    """Whether `label` is narrower than `width` (data units along x) on the drawn axes."""
    span = ax.transData.transform([(0.0, 0.0), (width, 0.0)])
    return label.get_window_extent(renderer).width < 0.9 * (span[1, 0] - span[0, 0])


def _shade(ax, times, mask, color, label) -> None:
    if mask.any():
        ax.fill_between(
            times,
            0,
            1,
            where=mask,
            color=color,
            alpha=0.2,
            label=label,
            transform=ax.get_xaxis_transform(),
            step="post",
        )


def plot_heatmap(
    path: Path, times: np.ndarray, signals: np.ndarray, furniture: tuple[Footprint, ...] = ()
) -> Path | None:
    """Time the person spent per floor cell, and the smallest separation seen from it, with
    the cell's furniture drawn over both (a walk through a table shows inside its outline);
    None when the person was never seen."""
    fig = heatmap_figure(times, signals, furniture)
    return save_figure(fig, path) if fig is not None else None


def heatmap_figure(times, signals, furniture=()):
    """The figure of `plot_heatmap` (None when the person was never seen)."""
    import matplotlib.pyplot as plt

    x, y = signal(signals, "person_x"), signal(signals, "person_y")
    known = np.isfinite(x) & np.isfinite(y)
    if times.size < 2 or not known.any():
        return None
    dt = np.append(np.diff(times), 0.0)[known]
    x, y = x[known], y[known]
    separation = signal(signals, "separation")[known]
    corners = np.array([c for piece in furniture for c in piece.outline]).reshape(-1, 2)
    edges_x, edges_y = _edges(np.append(x, corners[:, 0])), _edges(np.append(y, corners[:, 1]))
    time_spent, _, _ = np.histogram2d(x, y, [edges_x, edges_y], weights=dt)
    closest = np.full(time_spent.shape, np.nan)
    ix = np.clip(np.digitize(x, edges_x) - 1, 0, len(edges_x) - 2)
    iy = np.clip(np.digitize(y, edges_y) - 1, 0, len(edges_y) - 2)
    for i, j, d in zip(ix, iy, separation, strict=True):
        if np.isfinite(d):
            closest[i, j] = d if np.isnan(closest[i, j]) else min(closest[i, j], d)
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.8))
    extent = (edges_x[0], edges_x[-1], edges_y[0], edges_y[-1])
    panels = ((time_spent, "time spent (s)", "viridis"), (closest, "min separation (m)", "magma"))
    for ax, (grid, title, cmap) in zip(axes, panels, strict=True):
        shown = np.where(grid > 0, grid, np.nan) if grid is time_spent else grid
        image = ax.imshow(shown.T, origin="lower", extent=extent, cmap=cmap, aspect="equal")
        fig.colorbar(image, ax=ax, label=title)
        _draw_furniture(ax, furniture)
        ax.plot(0, 0, "k+", ms=12)
        ax.set_xlabel("x (m)")
        ax.set_ylabel("y (m)")
        ax.set_title(f"person: {title}")
    return fig


def _draw_furniture(ax, furniture: tuple[Footprint, ...]) -> None:
    """Each piece's outline, hatched, and its name once at the middle of its pieces."""
    from matplotlib.patches import Polygon

    by_name: dict[str, list] = {}
    for piece in furniture:
        ax.add_patch(
            Polygon(
                piece.outline, closed=True, fill=False, edgecolor=FURNITURE, hatch="///", lw=1.0
            )
        )
        by_name.setdefault(piece.name, []).extend(piece.outline)
    for name, corners in by_name.items():
        centre = np.mean(corners, axis=0)
        ax.text(*centre, name, fontsize=6, ha="center", va="center", color=FURNITURE, bbox=LABEL)


def _edges(values: np.ndarray) -> np.ndarray:
    low = np.floor(min(values.min(), 0.0) / HEAT_CELL) * HEAT_CELL - HEAT_CELL
    high = np.ceil(max(values.max(), 0.0) / HEAT_CELL) * HEAT_CELL + HEAT_CELL
    return np.arange(low, high + HEAT_CELL / 2, HEAT_CELL)
