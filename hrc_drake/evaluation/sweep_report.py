"""The aggregate report of a sweep: distributions of every numeric metric per grid point,
the worst seeds (replayable), failures, and for `--set` grids a comparison table.

Writes summary.json, histograms.png and report.html into the sweep directory.
"""

import json
import math
import shlex
from html import escape
from pathlib import Path

import numpy as np

from hrc_drake.evaluation.figures import save_figure
from hrc_drake.evaluation.html import html_table, page
from hrc_drake.evaluation.metrics import flatten
from hrc_drake.evaluation.rows import OK
from hrc_drake.scenario.overrides import label

PERCENTILES = (0, 5, 25, 50, 75, 95, 100)
WORST_CRITERIA = (
    ("margin.value", min),
    ("safety.min_separation.distance", min),
    ("safety.ssm_violations.worst_deficit", max),
    ("safety.contacts.max_force_ratio", max),
)
"""(metric, which end is worst): the runs to replay first."""
WORST_COUNT = 5
MAX_HISTOGRAMS = 30
RUN_SETTINGS = ("seed", "duration", "time_step")
"""Top-level report fields that describe the run rather than measure it."""


def numeric_metrics(row: dict) -> dict[str, float]:
    """The row's finite numeric metrics, flattened (booleans count as 0/1)."""
    values = {}
    for path, value in flatten(row["metrics"]).items():
        if path in RUN_SETTINGS:
            continue
        if isinstance(value, int | float) and math.isfinite(value):
            values[path] = float(value)
    return values


def distribution(values: list[float]) -> dict:
    data = np.asarray(values, dtype=float)
    stats = {f"p{p}": float(np.percentile(data, p)) for p in PERCENTILES}
    stats.update(count=len(values), mean=float(data.mean()), std=float(data.std()))
    return stats


def group_by_point(rows: list[dict]) -> dict[str, list[dict]]:
    """Successful rows per grid point label (insertion order = plan order)."""
    groups: dict[str, list[dict]] = {}
    for row in rows:
        if row["status"] == OK:
            groups.setdefault(_point(row), []).append(row)
    return groups


def summarize(rows: list[dict], scenario_name: str, scenario_path: str) -> dict:
    groups = group_by_point(rows)
    return {
        "scenario": scenario_name,
        "runs": len(rows),
        "failed": [{"key": r["key"], "error": r["error"]} for r in rows if r["status"] != OK],
        "groups": {point: _group_stats(members) for point, members in groups.items()},
        "worst": worst_runs(rows, scenario_path),
    }


def worst_runs(rows: list[dict], scenario_path: str) -> list[dict]:
    """Per criterion, the WORST_COUNT worst successful runs with the command that replays them."""
    worst = []
    for metric, pick in WORST_CRITERIA:
        scored = [(numeric_metrics(r).get(metric), r) for r in rows if r["status"] == OK]
        scored = [(value, r) for value, r in scored if value is not None]
        scored.sort(key=lambda item: item[0], reverse=pick is max)
        for value, row in scored[:WORST_COUNT]:
            worst.append(
                {
                    "metric": metric,
                    "value": value,
                    "key": row["key"],
                    "command": replay_command(scenario_path, row),
                }
            )
    return worst


def replay_command(scenario_path: str, row: dict) -> str:
    """The `hrc-drake run` command line of the row's run (quoted for a POSIX shell)."""
    sets = "".join(f" --set {shlex.quote(f'{path}={value}')}" for path, value in row["set"].items())
    return f"hrc-drake run {shlex.quote(str(scenario_path))} --seed {row['seed']}{sets}"


def write_sweep_report(
    out_dir: Path, rows: list[dict], scenario_path: str, scenario_name: str
) -> dict[str, Path]:
    summary = summarize(rows, scenario_name, scenario_path)
    files = {"summary": out_dir / "summary.json", "report_html": out_dir / "report.html"}
    files["summary"].write_text(json.dumps(summary, indent=2, sort_keys=True) + "\n")
    histograms = plot_histograms(group_by_point(rows), out_dir / "histograms.png")
    if histograms is not None:
        files["histograms"] = histograms
    files["report_html"].write_text(sweep_html(summary, histograms))
    return files


def plot_histograms(groups: dict[str, list[dict]], path: Path) -> Path | None:
    """One panel per metric that varies, grid points overlaid."""
    import matplotlib.pyplot as plt

    per_metric = _values_per_metric(groups)
    varying = [m for m, by_point in per_metric.items() if _varies(by_point)][:MAX_HISTOGRAMS]
    if not varying:
        return None
    columns = min(3, len(varying))
    rows = math.ceil(len(varying) / columns)
    fig, axes = plt.subplots(rows, columns, figsize=(4.5 * columns, 3.0 * rows), squeeze=False)
    for ax, metric in zip(axes.flat, varying, strict=False):
        for point, values in per_metric[metric].items():
            ax.hist(values, bins=20, alpha=0.6, label=point or "as written")
        ax.set_title(metric, fontsize=8)
    for ax in axes.flat[len(varying) :]:
        ax.axis("off")
    if len(groups) > 1:
        axes.flat[0].legend(fontsize=7)
    return save_figure(fig, path)


def sweep_html(summary: dict, histograms: Path | None) -> str:
    parts = [f"<h1>Sweep of {escape(summary['scenario'])}: {summary['runs']} runs</h1>"]
    if histograms is not None:
        parts.append(f'<img src="{histograms.name}" style="max-width:100%">')
    parts.append(_comparison_table(summary["groups"]))
    parts.append(_worst_table(summary["worst"]))
    if summary["failed"]:
        failed = [[f["key"], f["error"]] for f in summary["failed"]]
        parts.append("<h2>Failed runs</h2>" + html_table(["run", "error"], failed))
    return page(f"sweep {summary['scenario']}", "\n".join(parts))


def _comparison_table(groups: dict[str, dict]) -> str:
    """Metric rows; per grid point the median and the 5–95 % range."""
    points = list(groups)
    metrics = sorted({m for stats in groups.values() for m in stats})
    header = ["metric"] + [f"{p or 'as written'}: median [p5, p95]" for p in points]
    rows = []
    for metric in metrics:
        cells = [metric]
        for point in points:
            s = groups[point].get(metric)
            cells.append(f"{s['p50']:.4g} [{s['p5']:.4g}, {s['p95']:.4g}]" if s else "")
        rows.append(cells)
    return "<h2>Metrics</h2>" + html_table(header, rows)


def _worst_table(worst: list[dict]) -> str:
    rows = [[w["metric"], w["value"], w["key"], w["command"]] for w in worst]
    return "<h2>Worst runs</h2>" + html_table(["metric", "value", "run", "replay"], rows)


def _metric_values(rows: list[dict]) -> dict[str, list[float]]:
    per_metric: dict[str, list[float]] = {}
    for row in rows:
        for metric, value in numeric_metrics(row).items():
            per_metric.setdefault(metric, []).append(value)
    return per_metric


def _group_stats(rows: list[dict]) -> dict[str, dict]:
    return {m: distribution(v) for m, v in sorted(_metric_values(rows).items())}


def _values_per_metric(groups: dict[str, list[dict]]) -> dict[str, dict[str, list[float]]]:
    per_metric: dict[str, dict[str, list[float]]] = {}
    for point, rows in groups.items():
        for metric, values in _metric_values(rows).items():
            per_metric.setdefault(metric, {})[point] = values
    return per_metric


def _varies(by_point: dict[str, list[float]]) -> bool:
    values = [v for vs in by_point.values() for v in vs]
    return max(values) > min(values)


def _point(row: dict) -> str:
    return label(tuple(row["set"].items()))
