"""report.html of a run: the figures, the metrics table and a link to replay.html."""

from pathlib import Path

from hrc_drake.evaluation.realism import realism_rows
from hrc_drake.evaluation.sweep_report import html_table, page
from hrc_drake.sweep.rows import flatten


def write_run_html(path: Path, metrics: dict, files: dict[str, Path]) -> Path:
    """`files` are the run directory's other files (figures, replay) by role."""
    title = f"{metrics.get('scenario', '')} seed {metrics.get('seed', '')}"
    parts = [f"<h1>Run: {title}</h1>"]
    if "replay" in files:
        parts.append(f'<p><a href="{files["replay"].name}">Replay (Meshcat)</a></p>')
    for role in ("timeline", "heatmap"):
        if role in files:
            parts.append(f'<img src="{files[role].name}" style="max-width:100%">')
    if metrics.get("realism"):
        header = ["measure", "worst", "limit", "where", "within"]
        parts.append("<h2>Realism</h2>" + html_table(header, realism_rows(metrics["realism"])))
    rows = [[name, value] for name, value in flatten(metrics).items()]
    parts.append("<h2>Metrics</h2>" + html_table(["metric", "value"], rows))
    path.write_text(page(title, "\n".join(parts)))
    return path
