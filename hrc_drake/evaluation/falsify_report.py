"""What a falsification search found: every trial, the worst cases and how to replay them.

Writes into the search directory: trials.csv (one line a trial: its parameters, margin and
key metrics), falsify.json (the same, the worst cases with their commands and run
directories, warnings), margin.png (the margin of every trial and the lowest so far),
worst_cases.png (each worst case's separation and S_p over time) and falsify.html.
"""

import csv
import json
import math
import textwrap
from html import escape
from pathlib import Path

import numpy as np

from hrc_drake.evaluation.figures import save_figure
from hrc_drake.evaluation.html import html_table, page
from hrc_drake.evaluation.margin import margin_model
from hrc_drake.evaluation.record import RunSetup
from hrc_drake.safety.log import read_safety_log
from hrc_drake.safety.reference import reference_protective

KEY_METRICS = (
    ("margin", ("margin", "value")),
    ("ssm_margin", ("margin", "ssm")),
    ("contact_ratio", ("margin", "contact_ratio")),
    ("violation", ("margin", "violation")),
    ("least_margin_time", ("margin", "at", "time")),
    ("least_margin_region", ("margin", "at", "region")),
    ("least_margin_part", ("margin", "at", "part")),
    ("min_separation", ("safety", "min_separation", "distance")),
    ("monitor_ssm_violations", ("safety", "ssm_violations", "count")),
    ("contacts", ("safety", "contacts", "count")),
    ("time_stopped", ("safety", "time_stopped")),
    ("rula_max", ("ergonomics", "rula", "max", "score")),
    ("reba_max", ("ergonomics", "reba", "max", "score")),
    ("lifting_index_max", ("ergonomics", "lifting_index_max", "value")),
)
"""(column, path in the run's metrics) of each trial's line."""
MAX_SEPARATION_SHOWN = 4.0
"""m: higher separations are cut off (the encounter is what matters)."""
TITLE_WIDTH = 120
"""Characters per line of a worst case's title (its parameter values)."""


def trial_record(trial) -> dict:
    """A trial as trials.csv and falsify.json show it."""
    record = {"trial": trial.number, "status": trial.row["status"], **trial.values}
    for column, path in KEY_METRICS:
        record[column] = _at(trial.row["metrics"], path)
    record["error"] = trial.row["error"]
    return record


def _at(metrics: dict, path: tuple):
    for name in path:
        if not isinstance(metrics, dict) or name not in metrics:
            return None
        metrics = metrics[name]
    return metrics


def summary(search, result) -> dict:
    lowest = result.worst[0] if result.worst else None
    return {
        "name": search.name,
        "scenario": str(search.scenario_path),
        "seed": search.seed,
        "sampler": search.config.sampler,
        "batch": search.config.batch,
        "fixed": dict(search.fixed),
        "parameters": {
            name: {
                "bind": p.bind,
                "low": p.low,
                "high": p.high,
                "step": p.step,
                "choices": p.choices,
            }
            for name, p in search.config.parameters.items()
        },
        "trials": [trial_record(t) for t in result.trials],
        "failed": len(result.failed),
        "violations": len(result.violations),
        "lowest_margin": lowest.margin.get("value") if lowest else None,
        "worst": [
            {
                **trial_record(t),
                "command": search.command(t.values),
                "run_directory": str(result.cases[t.number]) if t.number in result.cases else None,
            }
            for t in result.worst
        ],
        "warnings": result.warnings,
    }


def write_trials(out_dir: Path, trials) -> Path:
    records = [trial_record(t) for t in trials]
    path = out_dir / "trials.csv"
    columns = list(dict.fromkeys(name for record in records for name in record))
    with path.open("w", newline="") as f:
        writer = csv.DictWriter(f, columns)
        writer.writeheader()
        writer.writerows(records)
    return path


def write_falsify_report(
    out_dir: Path, search, result, setups: dict[int, RunSetup]
) -> dict[str, Path]:
    """`setups`: of each worst case's run, by trial number."""
    found = summary(search, result)
    files = {"trials": write_trials(out_dir, result.trials), "summary": out_dir / "falsify.json"}
    files["summary"].write_text(json.dumps(found, indent=2, sort_keys=True) + "\n")
    if any(t.ok for t in result.trials):
        files["margin_plot"] = plot_margins(result.trials, out_dir / "margin.png")
    cases = [
        (t, result.cases[t.number], setups[t.number])
        for t in result.worst
        if t.number in result.cases
    ]
    if cases:
        files["worst_plot"] = plot_worst_cases(cases, out_dir / "worst_cases.png")
    files["report_html"] = out_dir / "falsify.html"
    files["report_html"].write_text(falsify_html(found, files, out_dir))
    return files


def plot_margins(trials, path: Path) -> Path:
    """Each trial's margin (failed trials left out) and the lowest margin so far."""
    import matplotlib.pyplot as plt

    numbers = [t.number for t in trials if t.ok and t.margin.get("value") is not None]
    margins = [t.margin["value"] for t in trials if t.number in set(numbers)]
    fig, ax = plt.subplots(figsize=(8, 3.6))
    ax.axhline(0.0, color="firebrick", lw=1, label="violation below")
    if numbers:
        ax.scatter(numbers, margins, s=14, color="tab:blue", label="trial")
        ax.step(
            numbers,
            np.minimum.accumulate(margins),
            where="post",
            color="black",
            label="lowest so far",
        )
    ax.set_xlabel("trial")
    ax.set_ylabel("safety margin (m)")
    ax.legend(fontsize=8)
    return save_figure(fig, path)


def plot_worst_cases(cases: list[tuple], path: Path) -> Path:
    """Per worst case (trial, run directory, RunSetup) over time: the separation, S_p as
    the margin takes it and as the monitor had it, when the robot moved; the least margin
    marked."""
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(len(cases), 1, figsize=(9, 2.8 * len(cases)), squeeze=False)
    for ax, (trial, directory, setup) in zip(axes[:, 0], cases, strict=True):
        log = read_safety_log(directory / "safety.npz")
        time = log["time"]
        ax.plot(time, log["separation"], color="tab:blue", lw=1, label="separation")
        ax.plot(
            time,
            reference_protective(log, margin_model(setup)),
            color="tab:orange",
            lw=1,
            label="S_p (ISO 13855 v_h)",
        )
        ax.plot(time, log["protective"], color="tab:orange", lw=0.8, ls=":", label="S_p (monitor)")
        moving = log["robot_speed"] > setup.safety.moving_speed
        ax.fill_between(
            time,
            0,
            1,
            where=moving,
            transform=ax.get_xaxis_transform(),
            color="0.9",
            label="robot moving",
        )
        at = trial.margin.get("at")
        if at:
            ax.axvline(at["time"], color="firebrick", lw=1)
            ax.annotate(
                f"margin {trial.margin['value']:.3f} m",
                (at["time"], at["separation"]),
                fontsize=8,
                color="firebrick",
            )
        seen = log["separation"][np.isfinite(log["separation"])]
        ax.set_ylim(0, min(MAX_SEPARATION_SHOWN, 1.05 * seen.max()) if seen.size else 1.0)
        values = ", ".join(f"{k}={v}" for k, v in trial.values.items())
        ax.set_title(
            textwrap.fill(f"trial {trial.number}: {values}", TITLE_WIDTH),
            fontsize=9,
        )
        ax.set_ylabel("m")
        ax.legend(fontsize=7, loc="upper right")
    axes[-1, 0].set_xlabel("time (s)")
    return save_figure(fig, path)


def falsify_html(found: dict, files: dict[str, Path], out_dir: Path) -> str:
    verdict = (
        f"{found['violations']} of {len(found['trials'])} trials violate ISO/TS 15066"
        if found["violations"]
        else f"no violation in {len(found['trials'])} trials"
    )
    lowest = found["lowest_margin"]
    parts = [
        f"<h1>Worst cases of {escape(found['name'])}</h1>",
        f"<p>{verdict}; lowest margin {_number(lowest)} m (seed {found['seed']}, sampler "
        f"{escape(found['sampler'])}). The margin is the least separation minus S_p while the "
        "robot moves, or less for a contact near its limit; below 0 is a violation.</p>",
    ]
    for name in ("margin_plot", "worst_plot"):
        if name in files:
            parts.append(f'<img src="{files[name].name}" style="max-width:100%">')
    parts.append("<h2>Worst cases</h2>" + _worst_cases(found["worst"], out_dir))
    columns = [c for c in found["trials"][0] if c != "error"] if found["trials"] else []
    rows = [[record[c] for c in columns] for record in found["trials"]]
    parts.append("<h2>All trials</h2>" + html_table(columns, rows))
    if found["warnings"]:
        parts.append(
            "<h2>Warnings</h2><ul>"
            + "".join(f"<li>{escape(w)}</li>" for w in found["warnings"])
            + "</ul>"
        )
    return page(f"falsify {found['name']}", "\n".join(parts))


def _worst_cases(worst: list[dict], out_dir: Path) -> str:
    rows = []
    for case in worst:
        links = ""
        if case["run_directory"]:
            where = Path(case["run_directory"]).relative_to(out_dir)
            links = " ".join(
                f'<a href="{escape(str(where / name))}">{label}</a>'
                for name, label in (
                    ("report.html", "report"),
                    ("replay.html", "replay"),
                    ("timeline.png", "timeline"),
                )
            )
        rows.append(
            f"<tr><td>{case['trial']}</td><td>{_number(case['margin'])}</td>"
            f"<td>{escape(_where(case))}</td><td>{links}</td>"
            f"<td style='text-align:left'><code>{escape(case['command'])}</code></td></tr>"
        )
    head = "".join(
        f"<th>{h}</th>" for h in ("trial", "margin (m)", "where, when", "run", "reproduce")
    )
    return f"<table><tr>{head}</tr>{''.join(rows)}</table>"


def _where(case: dict) -> str:
    if case["least_margin_time"] is None:
        return ""
    pair = f"{case['least_margin_region']} / {case['least_margin_part']}"
    return f"{pair} at {_number(case['least_margin_time'])} s"


def _number(value) -> str:
    return f"{value:.4g}" if isinstance(value, float) and math.isfinite(value) else str(value)
