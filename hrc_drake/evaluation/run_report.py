"""report.html of a run: the figures, the metrics by section side by side, and each behavior
tree summarised by its activities (the nodes at most two levels deep), with the statistics of
every node folded away below."""

from html import escape
from pathlib import Path

from hrc_drake.evaluation.html import html_table, page, verdict
from hrc_drake.evaluation.metrics import flatten
from hrc_drake.evaluation.realism import (
    audits_a_person,
    over_limits,
    realism_rows,
    realism_verdict,
)

SUMMARY_DEPTH = 2
"""Tree nodes down to this depth (the tree's top loop and its activities) are summarised..."""
SUMMARY_ROWS = 10
"""... those that ran longest."""
NODE_COLUMNS = ("ticks", "successes", "failures", "time_running")
SECTIONS_STYLE = "display:flex;flex-wrap:wrap;gap:0 2.5em;align-items:flex-start"


def write_run_html(path: Path, metrics: dict, files: dict[str, Path], sections: str = "") -> Path:
    """`files` are the run directory's other files (figures, replay) by role; `sections`
    is more HTML shown after the realism audit (the ergonomics)."""
    title = f"{metrics.get('scenario', '')} seed {metrics.get('seed', '')}"
    parts = [f"<h1>Run: {escape(title)}</h1>"]
    realism = metrics.get("realism") or {}
    if realism:
        audit = "The person's realism audit" if audits_a_person(realism) else "The realism audit"
        said = f"{audit}: " + "; ".join(realism_verdict(realism))
        parts.append(verdict(said, bool(over_limits(realism)), "realism-verdict"))
    if "replay" in files:
        parts.append(f'<p><a href="{files["replay"].name}">Replay (Meshcat)</a></p>')
    for role in ("timeline", "heatmap"):
        if role in files:
            parts.append(f'<img src="{files[role].name}" style="max-width:100%">')
    parts.append(_layout_section(files))
    if realism:
        header = ["measure", "worst", "limit", "where", "within"]
        rows = realism_rows(realism)
        over = {k for k, row in enumerate(rows) if not row[-1]}
        parts.append("<h2>Realism</h2>" + html_table(header, rows, over))
    if sections:
        parts.append(sections)
    parts.append("<h2>Metrics</h2>" + _metric_sections(metrics))
    trees = metrics.get("bt") or {}
    if trees:
        parts.append("<h2>Behavior trees</h2>")
        parts += [_tree_summary(agent, nodes) for agent, nodes in trees.items()]
    path.write_text(page(title, "\n".join(parts)))
    return path


def _layout_section(files: dict[str, Path]) -> str:
    """The cell from above (hrc_drake.layout): the robot's reach, where the person walks,
    the places and what validate would flag."""
    if "layout" not in files:
        return ""
    return (
        '<h2 id="layout">Layout</h2>'
        f'<img src="{files["layout"].name}" alt="the cell from above" style="max-width:100%">'
    )


def _metric_sections(metrics: dict) -> str:
    """One table per section of the report (safety, tasks, ...); plain values under `run`."""
    run = [[name, value] for name, value in metrics.items() if not isinstance(value, dict)]
    sections = {"run": run} if run else {}
    for name, value in metrics.items():
        if isinstance(value, dict) and name not in ("bt", "realism", "ergonomics") and value:
            sections[name] = [[key, v] for key, v in flatten(value).items()]
    tables = [
        f"<div><h3>{escape(name)}</h3>{html_table(['metric', 'value'], rows)}</div>"
        for name, rows in sections.items()
    ]
    return f'<div style="{SECTIONS_STYLE}">{"".join(tables)}</div>'


def _node_name(path: str) -> str:
    """`Help::6/CarryBoxToConveyor::54` -> `Help/CarryBoxToConveyor` (no node uids)."""
    return "/".join(part.split("::")[0] for part in path.split("/"))


def _tree_summary(agent: str, nodes: dict[str, dict]) -> str:
    every = [[_node_name(path), *(stats[c] for c in NODE_COLUMNS)] for path, stats in nodes.items()]
    top = [row for row, path in zip(every, nodes, strict=True) if path.count("/") < SUMMARY_DEPTH]
    top = sorted(top, key=lambda row: -row[-1])[:SUMMARY_ROWS]
    header = ["node", *(c.replace("_", " ") for c in NODE_COLUMNS)]
    return (
        f"<h3>{escape(agent)}: the {len(top)} activities that ran longest</h3>"
        + html_table(header, top)
        + f"<details><summary>all {len(nodes)} nodes of the {escape(agent)} tree</summary>"
        + html_table(header, every)
        + "</details>"
    )
