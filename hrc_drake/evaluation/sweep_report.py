"""The aggregate report of a sweep: per grid point, safety and productivity first (how many
runs broke ISO/TS 15066, the least margins and separations, stops, output), how many runs
the realism audit failed, then the distributions of every numeric metric, the
worst seeds (replayable), failures, and last, folded, the behaviour trees' statistics.

A metric that counts what happened (a task event, a tree node's ticks) is absent from a
run in which it never happened: it counts 0 there, never left out. Any other metric a run
lacks (no margin where the robot never moved near the person) is left out, and the report
says over how many runs it is.

Writes summary.json, histograms.png and report.html into the sweep directory.
"""

import json
import math
import shlex
from html import escape
from pathlib import Path

import numpy as np

from hrc_drake.evaluation.figures import save_figure
from hrc_drake.evaluation.html import html_table, page, verdict
from hrc_drake.evaluation.metrics import flatten
from hrc_drake.evaluation.realism import over_limits
from hrc_drake.evaluation.rows import OK
from hrc_drake.scenario.overrides import label

PERCENTILES = (0, 5, 25, 50, 75, 95, 100)
WORST_CRITERIA = (
    ("margin.value", min),
    ("safety.min_separation.distance", min),
    ("safety.ssm_violations.worst_deficit", max),
    ("safety.contacts.max_force_ratio", max),
    ("realism.penetration_static.max", max),
)
"""(metric, which end is worst): the runs to replay first."""
WORST_COUNT = 5
MAX_HISTOGRAMS = 30
RUN_SETTINGS = ("seed", "duration", "time_step")
"""Top-level report fields that describe the run rather than measure it."""
COUNTED = ("tasks.events.", "tasks.throughput_per_hour.", "bt.")
"""Metrics of what happened, absent from a run where it never did: 0 there."""
SECTIONS = (
    ("Safety", ("margin.", "safety.")),
    ("Productivity", ("tasks.", "utilisation.", "person.")),
    ("Realism", ("realism.",)),
    ("The robot", ("robot.",)),
)
"""The report's metric tables in the order a reader wants them; other metrics follow, and
the behaviour trees' statistics (`TREES`) come last, folded."""
TREES = "bt."
HEADLINE = (
    ("safety margin (m)", "margin.value"),
    ("least separation (m)", "safety.min_separation.distance"),
    ("SSM violations seen by the monitor", "safety.ssm_violations.count"),
    ("contacts begun by the moving robot", "safety.contacts.robot_moving"),
    ("contacts over their limits", "safety.contacts.violations"),
    ("stops", "safety.stops"),
    ("time stopped (s)", "safety.time_stopped"),
    ("time at reduced speed (s)", "safety.time_reduced"),
    ("robot moving (fraction of the run)", "utilisation.robot.moving"),
)
"""(what the reader is told, metric) of the headline table; task events follow them."""


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
        "groups": {point: group_summary(members) for point, members in groups.items()},
        "worst": worst_runs(rows, scenario_path),
    }


def group_summary(rows: list[dict]) -> dict:
    """One grid point's successful runs: how many, how many broke ISO/TS 15066 (a safety
    margin below 0), the realism audit's counts, and every metric's distribution."""
    return {
        "runs": len(rows),
        "violating_runs": sum(bool(r["metrics"].get("margin", {}).get("violation")) for r in rows),
        "realism": realism_counts(rows),
        "metrics": {m: distribution(v) for m, v in sorted(_metric_values(rows).items())},
    }


def realism_counts(rows: list[dict]) -> dict:
    """How many runs had a person or objects to audit (a robot-only cell's objects count),
    how many of them went over the realism audit's limits, and how many runs each measure was
    over its limit in."""
    audited = [r["metrics"]["realism"] for r in rows if r["metrics"].get("realism")]
    measures: dict[str, int] = {}
    for realism in audited:
        for check in over_limits(realism):
            measures[check.measure] = measures.get(check.measure, 0) + 1
    return {
        "audited": len(audited),
        "over_limits": sum(bool(over_limits(realism)) for realism in audited),
        "measures": dict(sorted(measures.items())),
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
    """One panel per metric that varies (safety and productivity first, no tree
    statistics), grid points overlaid."""
    import matplotlib.pyplot as plt

    per_metric = _values_per_metric(groups)
    shown = [m for m in _in_sections(per_metric) if _varies(per_metric[m])]
    varying = shown[:MAX_HISTOGRAMS]
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
    """Verdicts first, then safety and productivity, the figures, the runs to replay and
    the failures, every metric by section, and the behaviour trees' statistics folded."""
    groups = summary["groups"]
    failed = len(summary["failed"])
    title = f"Sweep of {escape(summary['scenario'])}: {summary['runs']} runs ({failed} failed)"
    parts = [f"<h1>{title}</h1>"]
    for k, (point, group) in enumerate(groups.items()):
        parts.append(_verdict(point, group, f"verdict-{k}"))
    parts.append("<h2>Safety and productivity</h2>" + _headline_table(groups))
    if histograms is not None:
        parts.append(f'<img src="{histograms.name}" style="max-width:100%">')
    parts.append(_worst_table(summary["worst"]))
    if summary["failed"]:
        rows = [[f["key"], f["error"]] for f in summary["failed"]]
        parts.append("<h2>Failed runs</h2>" + html_table(["run", "error"], rows))
    metrics = sorted({m for group in groups.values() for m in group["metrics"]})
    parts.append("<h2>Every metric</h2>")
    for title, prefixes in (*SECTIONS, ("Other", ())):
        chosen = _section(metrics, prefixes)
        if chosen:
            parts.append(f"<h3>{escape(title)}</h3>" + _metric_table(groups, chosen))
    trees = [m for m in metrics if m.startswith(TREES)]
    if trees:
        parts.append(
            f'<details id="tree-statistics"><summary>The behaviour trees: {len(trees)} '
            f"statistics of their nodes</summary>{_metric_table(groups, trees)}</details>"
        )
    return page(f"sweep {summary['scenario']}", "\n".join(parts))


def _verdict(point: str, group: dict, element_id: str) -> str:
    flagged = bool(group["violating_runs"] or group["realism"]["over_limits"])
    return verdict(group_verdict(point, group), flagged, element_id)


def group_verdict(point: str, group: dict) -> str:
    """One grid point's verdict on safety and on the realism audit, in a line."""
    runs, violating, realism = group["runs"], group["violating_runs"], group["realism"]
    said = [
        f"{violating} of {runs} runs violate ISO/TS 15066 (a safety margin below 0)"
        if violating
        else f"none of {runs} runs violates ISO/TS 15066"
    ]
    if realism["audited"]:
        over, audited = realism["over_limits"], realism["audited"]
        said.append(
            f"{over} of {audited} runs over the realism audit's limits ({_measures(realism)})"
            if over
            else f"all {audited} runs within the realism audit's limits"
        )
    return f"{point or 'as written'}: " + "; ".join(said)


def verdicts(rows: list[dict]) -> list[str]:
    """Each grid point's verdict (what `hrc-drake sweep` prints)."""
    return [
        group_verdict(point, group_summary(members))
        for point, members in group_by_point(rows).items()
    ]


def _measures(realism: dict) -> str:
    return ", ".join(f"{name} in {n}" for name, n in realism["measures"].items())


def _headline_table(groups: dict[str, dict]) -> str:
    """Per grid point: the runs, how many broke the standard, the key safety figures, the
    output per task event, and how many runs failed the realism audit."""
    points = list(groups)
    header = ["median [p5, p95] over the runs", *(p or "as written" for p in points)]
    rows = [
        ["runs", *(g["runs"] for g in groups.values())],
        [
            "runs that violate ISO/TS 15066",
            *(f"{g['violating_runs']} of {g['runs']}" for g in groups.values()),
        ],
        ["lowest safety margin (m)", *(_lowest(g, "margin.value") for g in groups.values())],
    ]
    rows += [[text, *(_cell(g, metric) for g in groups.values())] for text, metric in HEADLINE]
    events = sorted(
        {m for g in groups.values() for m in g["metrics"] if m.startswith("tasks.events.")}
    )
    for metric in events:
        event = metric.removeprefix("tasks.events.")
        rate = f"tasks.throughput_per_hour.{event}"
        rows.append([f"{event} per run", *(_cell(g, metric) for g in groups.values())])
        rows.append([f"{event} per hour", *(_cell(g, rate) for g in groups.values())])
    rows.append(["runs over the realism audit's limits", *map(_realism_cell, groups.values())])
    flagged = {1} if any(g["violating_runs"] for g in groups.values()) else set()
    if any(g["realism"]["over_limits"] for g in groups.values()):
        flagged.add(len(rows) - 1)
    return html_table(header, rows, flagged)


def _realism_cell(group: dict) -> str:
    realism = group["realism"]
    if not realism["audited"]:
        return "no person or object to audit"
    counted = f"{realism['over_limits']} of {realism['audited']}"
    return f"{counted} ({_measures(realism)})" if realism["over_limits"] else counted


def _lowest(group: dict, metric: str) -> str:
    stats = group["metrics"].get(metric)
    return f"{stats['p0']:.4g}" if stats else ""


def _cell(group: dict, metric: str) -> str:
    """`median [p5, p95]`, and over how many runs where some lack the metric."""
    stats = group["metrics"].get(metric)
    if not stats:
        return ""
    text = f"{stats['p50']:.4g} [{stats['p5']:.4g}, {stats['p95']:.4g}]"
    return (
        text
        if stats["count"] == group["runs"]
        else f"{text} ({stats['count']} of {group['runs']} runs)"
    )


def _metric_table(groups: dict[str, dict], metrics: list[str]) -> str:
    header = ["metric", *(f"{p or 'as written'}: median [p5, p95]" for p in groups)]
    rows = [[metric, *(_cell(g, metric) for g in groups.values())] for metric in metrics]
    return html_table(header, rows)


def _section(metrics: list[str], prefixes: tuple[str, ...]) -> list[str]:
    """The metrics of a section; with no prefixes, those of no section (trees aside)."""
    if prefixes:
        return [m for m in metrics if m.startswith(prefixes)]
    known = tuple(p for _, section in SECTIONS for p in section) + (TREES,)
    return [m for m in metrics if not m.startswith(known)]


def _in_sections(metrics) -> list[str]:
    """Every metric but the trees' statistics: the headline's first, then the task events,
    then the rest in the order of the report's sections."""
    names = sorted(metrics)
    first = [m for _, m in HEADLINE if m in metrics] + _section(names, ("tasks.events.",))
    ordered = [m for _, prefixes in SECTIONS for m in _section(names, prefixes)]
    return list(dict.fromkeys(first + ordered + _section(names, ())))


def _worst_table(worst: list[dict]) -> str:
    rows = [[w["metric"], w["value"], w["key"], w["command"]] for w in worst]
    return "<h2>Worst runs</h2>" + html_table(["metric", "value", "run", "replay"], rows)


def _metric_values(rows: list[dict]) -> dict[str, list[float]]:
    """Each metric's values over the rows: a count a run lacks is 0 there (`COUNTED`),
    any other metric it lacks is left out."""
    per_row = [numeric_metrics(row) for row in rows]
    names = sorted({metric for values in per_row for metric in values})
    per_metric = {}
    for metric in names:
        absent = 0.0 if metric.startswith(COUNTED) else None
        values = [values.get(metric, absent) for values in per_row]
        per_metric[metric] = [v for v in values if v is not None]
    return per_metric


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
