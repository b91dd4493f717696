"""timeline.png (separation and S_p, speed scale, speeds, actor states and task events over
time) and heatmap.png (top view: where the person was, where separation was smallest)."""

from pathlib import Path

import numpy as np

from hrc_drake.evaluation.figures import save_figure
from hrc_drake.messages import TaskEvent
from hrc_drake.safety.messages import SIGNALS

HEAT_CELL = 0.1
"""m per heat-map cell."""


def _signal(signals: np.ndarray, name: str) -> np.ndarray:
    return signals[SIGNALS.index(name)]


def plot_timeline(
    path: Path,
    times: np.ndarray,
    signals: np.ndarray,
    states: dict[str, list[tuple[float, str]]] | None = None,
    events: list[TaskEvent] | None = None,
) -> Path:
    """`states`: per actor, (time, state) changes; `events`: task events from the trees."""
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(4, 1, figsize=(10, 9), sharex=True)
    _separation_panel(axes[0], times, signals)
    axes[1].step(times, _signal(signals, "scale"), where="post", color="tab:green")
    axes[1].set_ylim(-0.05, 1.05)
    axes[1].set_ylabel("speed scale")
    for name, color in (("robot_speed", "tab:blue"), ("approach_speed", "tab:cyan")):
        axes[2].plot(times, _signal(signals, name), color=color, label=name.replace("_", " "))
    axes[2].plot(times, _signal(signals, "human_speed"), color="tab:orange", label="person speed")
    axes[2].set_ylabel("m/s")
    axes[2].legend(fontsize=7, loc="upper right")
    end = float(times[-1]) if times.size else 0.0
    _activity_panel(axes[3], states or {}, events or [], end)
    axes[3].set_xlim(0.0, max(end, 1e-3))
    axes[3].set_xlabel("time (s)")
    return save_figure(fig, path)


def _separation_panel(ax, times, signals) -> None:
    ax.plot(times, _signal(signals, "separation"), label="separation", color="black")
    ax.plot(times, _signal(signals, "protective"), label="S_p", color="tab:red", ls="--")
    _shade(ax, times, _signal(signals, "violation") > 0, "tab:red", "SSM violation")
    _shade(ax, times, _signal(signals, "contact") > 0, "purple", "contact")
    ax.set_ylabel("m")
    ax.legend(fontsize=7, loc="upper right")


def _activity_panel(ax, states, events, end: float) -> None:
    """One row per actor with its states as labelled spans; task events as markers."""
    names = list(states)
    for row, actor in enumerate(names):
        changes = states[actor]
        for (start, state), (stop, _) in zip(changes, [*changes[1:], (None, None)], strict=True):
            span_end = end if stop is None else stop
            ax.barh(row, span_end - start, left=start, height=0.6, alpha=0.5)
            ax.text(start, row, state, fontsize=6, va="center")
    for event in events:
        ax.axvline(event.time, color="gray", lw=0.6)
        ax.text(event.time, len(names), event.name, fontsize=6, rotation=90, va="bottom")
    ax.set_yticks(range(len(names)), names)
    if not names and not events:
        ax.text(
            0.5,
            0.5,
            "no actor states or task events logged",
            transform=ax.transAxes,
            ha="center",
            va="center",
            color="gray",
        )
    ax.set_ylabel("actors")


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


def plot_heatmap(path: Path, times: np.ndarray, signals: np.ndarray) -> Path | None:
    """Time the person spent per floor cell, and the smallest separation seen from it."""
    import matplotlib.pyplot as plt

    x, y = _signal(signals, "person_x"), _signal(signals, "person_y")
    known = np.isfinite(x) & np.isfinite(y)
    if times.size < 2 or not known.any():
        return None
    dt = np.append(np.diff(times), 0.0)[known]
    x, y = x[known], y[known]
    separation = _signal(signals, "separation")[known]
    edges_x, edges_y = _edges(x), _edges(y)
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
        ax.plot(0, 0, "k+", ms=12)
        ax.set_xlabel("x (m)")
        ax.set_ylabel("y (m)")
        ax.set_title(f"person: {title}")
    return save_figure(fig, path)


def _edges(values: np.ndarray) -> np.ndarray:
    low = np.floor(min(values.min(), 0.0) / HEAT_CELL) * HEAT_CELL - HEAT_CELL
    high = np.ceil(max(values.max(), 0.0) / HEAT_CELL) * HEAT_CELL + HEAT_CELL
    return np.arange(low, high + HEAT_CELL / 2, HEAT_CELL)
