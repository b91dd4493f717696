"""A run's report from what it recorded (`RunRecord`): its metrics, report.json's dict
(`evaluate`), and its run directory (`write_run_directory`).

A run directory holds `report.json` (deterministic: same scenario and seed give the same
bytes, so it holds no wall-clock figures), `diagram.svg`, with a replay recorder
`replay.html` (a standalone Meshcat recording), `layout.png` (the cell from above,
hrc_drake.layout, drawn by the runner), with a safety monitor `safety.npz` (its
signals at every update, `hrc_drake.safety.log`), `timeline.png` and `heatmap.png`, plus
`report.html` tying them together. The runner writes the trees' transition logs
(`bt_<agent>.btlog` for Groot2, `bt_<agent>.jsonl`) there as the trees run.
"""

import json
from dataclasses import dataclass, field
from pathlib import Path

from hrc_drake.diagram_export import write_diagram
from hrc_drake.evaluation.ergonomics import ergonomic_rows, ergonomics_html, ergonomics_metrics
from hrc_drake.evaluation.margin import margin_metrics, margin_model
from hrc_drake.evaluation.metrics import (
    bt_metrics,
    person_metrics,
    robot_metrics,
    rounded,
    safety_metrics,
    sensing_metrics,
    task_metrics,
    utilisation_metrics,
)
from hrc_drake.evaluation.realism import realism_metrics
from hrc_drake.evaluation.record import RunRecord
from hrc_drake.evaluation.recording import meshcat_path
from hrc_drake.evaluation.replay import write_replay
from hrc_drake.evaluation.run_report import write_run_html
from hrc_drake.evaluation.timeline import plot_heatmap, plot_timeline
from hrc_drake.safety.log import log_of, write_safety_log
from hrc_drake.wiring import HUMAN_MODEL, ROBOT, VISUAL_PREFIX


@dataclass
class Report:
    """What a run measured (`metrics`, as in report.json) and where its files are."""

    metrics: dict
    out_dir: Path | None = None
    wall_time: float = 0.0
    files: dict[str, Path] = field(default_factory=dict)

    @property
    def real_time_factor(self) -> float:
        return self.metrics["duration"] / self.wall_time if self.wall_time > 0 else float("inf")


def evaluate(record: RunRecord) -> dict:
    """The run's metrics, as report.json holds them; sections whose source the station
    lacked are empty."""
    setup = record.setup
    metrics = {
        "scenario": setup.scenario,
        "seed": setup.seed,
        "duration": setup.duration,
        "time_step": setup.time_step,
        "versions": record.versions,
        "robot": robot_metrics(setup.robot_variant, setup.initial_positions, record.robot_states),
        "safety": safety_metrics(record.safety_status, setup.safety.moving_speed),
        "tasks": task_metrics(record.events, setup.duration, record.event_names),
        "bt": bt_metrics(record.node_statistics),
        "realism": realism_metrics(record.realism),
        "ergonomics": ergonomics_metrics(record),
        **_signal_metrics(record),
    }
    if record.fault is not None:
        metrics["stopped"] = {"time": rounded(record.fault.time), "error": record.fault.error}
    return metrics


def _signal_metrics(record: RunRecord) -> dict:
    """The sections measured on the monitor's logged signals (empty without a monitor)."""
    if record.signals is None:
        return {"utilisation": {"robot": {}}, "person": {}, "margin": {}, "sensing": {}}
    times, signals = record.signal_times, record.signals
    moving_speed = record.setup.safety.moving_speed
    margin = margin_metrics(
        log_of(signals),
        margin_model(record.setup),
        moving_speed,
        record.safety_status.totals.contact_records,
        record.safety_parts,
    )
    return {
        "utilisation": {
            "robot": utilisation_metrics(times, signals, moving_speed, record.states.get(ROBOT, []))
        },
        "person": person_metrics(times, signals),
        "margin": margin,
        "sensing": sensing_metrics(
            times, signals, record.safety_status, tuple(record.setup.safety.sensors.all())
        ),
    }


def write_run_directory(
    out_dir: Path, record: RunRecord, metrics: dict, figures: dict[str, Path] | None = None
) -> dict[str, Path]:
    """Writes the run's files (see the module docstring) into `out_dir`, an existing
    directory; returns them by role, with `figures` the caller drew there (the layout)."""
    files = {"report": out_dir / "report.json", **(figures or {})}
    files["report"].write_text(json.dumps(metrics, indent=2, sort_keys=True) + "\n")
    files["diagram"] = write_diagram(record.diagram, out_dir / "diagram.svg")
    if record.recording is not None:
        files["replay"] = write_replay(
            out_dir / "replay.html",
            record.meshcat,
            record.recording,
            meshcat_path(VISUAL_PREFIX, HUMAN_MODEL),
        )
    if record.signals is not None:
        files.update(_write_signals(out_dir, record))
    sections = ergonomics_html(record, metrics)
    files["report_html"] = write_run_html(out_dir / "report.html", metrics, files, sections)
    return files


def _write_signals(out_dir: Path, record: RunRecord) -> dict[str, Path]:
    """safety.npz, and the timeline and (when the person was seen) heat map figures."""
    times, signals = record.signal_times, record.signals
    files = {
        "safety_log": write_safety_log(out_dir / "safety.npz", signals, record.safety_parts),
        "timeline": plot_timeline(
            out_dir / "timeline.png",
            times,
            signals,
            {**record.states, **ergonomic_rows(record)},
            record.events,
        ),
    }
    heatmap = plot_heatmap(out_dir / "heatmap.png", times, signals, record.furniture)
    if heatmap is not None:
        files["heatmap"] = heatmap
    return files
