"""Running a scenario: simulate the station diagram and write the run directory.

A run directory holds `report.json` (deterministic: same scenario and seed give the same
bytes, so it holds no wall-clock figures), `replay.html` (a standalone Meshcat recording),
`diagram.svg`, and with a safety monitor in the station `timeline.png`, `heatmap.png`, plus
`report.html` tying them together. Wall-clock speed is returned to the caller, never
written to the report.

Optional station outputs the runner measures when they exist: `safety_signals` and
`safety_status` (SafetyMonitor), `task_events` (a sequence of objects with `time`, `name`,
`agent`), `actor_states` (a dict actor -> current state name) and `bt_statistics` (a dict
agent -> node -> figures).
"""

import json
import time
from dataclasses import dataclass, field
from importlib.metadata import version
from pathlib import Path

import numpy as np
from pydrake.common.value import AbstractValue
from pydrake.geometry import Meshcat
from pydrake.systems.analysis import Simulator
from pydrake.systems.framework import DiagramBuilder, LeafSystem
from pydrake.systems.primitives import LogVectorOutput
from tqdm import tqdm

import hrc_drake
from hrc_drake.builder import VISUALIZER, build_diagram
from hrc_drake.diagram_export import write_diagram
from hrc_drake.evaluation.metrics import (
    bt_metrics,
    person_metrics,
    safety_metrics,
    task_metrics,
    utilisation_metrics,
)
from hrc_drake.evaluation.run_report import write_run_html
from hrc_drake.evaluation.timeline import plot_heatmap, plot_timeline
from hrc_drake.safety.config import SafetyConfig
from hrc_drake.scenario import Scenario

LOG_PERIOD = 0.01
PROGRESS_STEP = 0.1


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


def run(
    scenario: Scenario,
    seed: int | None = None,
    duration: float | None = None,
    out_dir: Path | str | None = None,
    meshcat: Meshcat | None = None,
    progress: bool = False,
    realtime_rate: float = 0.0,
) -> Report:
    """Simulates `scenario` once; with `out_dir`, writes the run directory."""
    scenario = scenario.with_overrides(seed=seed, duration=duration)
    out_dir = Path(out_dir) if out_dir is not None else None
    if meshcat is None and out_dir is not None and scenario.visualization.record:
        meshcat = Meshcat()
    station = build_diagram(scenario, meshcat)
    builder = DiagramBuilder()
    builder.AddSystem(station)
    state_log = LogVectorOutput(station.GetOutputPort("robot_state"), builder, LOG_PERIOD)
    signals_log = _optional_log(station, "safety_signals", builder)
    states_log = _optional_abstract_log(station, "actor_states", builder)
    diagram = builder.Build()

    simulator = Simulator(diagram)
    simulator.set_target_realtime_rate(realtime_rate)
    visualizer = _visualizer(station)
    if visualizer is not None:
        visualizer.StartRecording(set_transforms_while_recording=realtime_rate > 0)
    start = time.perf_counter()
    _advance(simulator, scenario.duration, progress, scenario.name)
    wall_time = time.perf_counter() - start

    context = simulator.get_context()
    outputs = _RunOutputs.collect(station, context, signals_log, states_log)
    metrics = _metrics(scenario, state_log.FindLog(context))
    metrics.update(outputs.metrics(scenario))
    report = Report(metrics, out_dir, wall_time)
    if out_dir is not None:
        _write_run_directory(report, station, visualizer, meshcat, outputs)
    return report


@dataclass
class _RunOutputs:
    """What the optional station outputs recorded over the run."""

    times: np.ndarray
    signals: np.ndarray | None
    status: object | None
    events: list
    states: dict[str, list[tuple[float, str]]]
    bt_statistics: dict | None

    @classmethod
    def collect(cls, station, context, signals_log, states_log) -> "_RunOutputs":
        station_context = station.GetMyContextFromRoot(context)
        log = signals_log.FindLog(context) if signals_log is not None else None
        return cls(
            times=log.sample_times() if log is not None else np.zeros(0),
            signals=log.data() if log is not None else None,
            status=_final(station, station_context, "safety_status"),
            events=[e for e in _final(station, station_context, "task_events") or ()],
            states=states_log.changes() if states_log is not None else {},
            bt_statistics=_final(station, station_context, "bt_statistics"),
        )

    def metrics(self, scenario: Scenario) -> dict:
        safety = getattr(scenario, "safety", SafetyConfig())
        measured = self.signals is not None
        return {
            "safety": safety_metrics(self.status),
            "utilisation": {
                "robot": utilisation_metrics(self.times, self.signals, safety.moving_speed)
                if measured
                else {}
            },
            "person": person_metrics(self.times, self.signals) if measured else {},
            "tasks": task_metrics(self.events, scenario.duration),
            "bt": bt_metrics(self.bt_statistics),
        }

    def write_figures(self, out: Path, files: dict[str, Path]) -> None:
        if self.signals is None:
            return
        files["timeline"] = plot_timeline(
            out / "timeline.png", self.times, self.signals, self.states, self.events
        )
        heatmap = plot_heatmap(out / "heatmap.png", self.times, self.signals)
        if heatmap is not None:
            files["heatmap"] = heatmap


class _StateChanges(LeafSystem):
    """Samples an abstract `dict actor -> state` port and keeps each actor's changes."""

    def __init__(self, period: float):
        super().__init__()
        self._input = self.DeclareAbstractInputPort("states", AbstractValue.Make(object()))
        self._changes: dict[str, list[tuple[float, str]]] = {}
        self.DeclarePeriodicPublishEvent(period, 0.0, self._sample)

    def _sample(self, context) -> None:
        for actor, state in dict(self._input.Eval(context)).items():
            history = self._changes.setdefault(actor, [])
            if not history or history[-1][1] != state:
                history.append((context.get_time(), str(state)))

    def changes(self) -> dict[str, list[tuple[float, str]]]:
        return self._changes


def _optional_log(station, port: str, builder):
    if not station.HasOutputPort(port):
        return None
    return LogVectorOutput(station.GetOutputPort(port), builder, LOG_PERIOD)


def _optional_abstract_log(station, port: str, builder):
    if not station.HasOutputPort(port):
        return None
    sampler = builder.AddSystem(_StateChanges(LOG_PERIOD))
    builder.Connect(station.GetOutputPort(port), sampler.get_input_port())
    return sampler


def _final(station, station_context, port: str):
    """The port's value at the end of the run, or None when the station lacks it."""
    if not station.HasOutputPort(port):
        return None
    return station.GetOutputPort(port).Eval(station_context)


def _visualizer(station):
    return station.GetSubsystemByName(VISUALIZER) if station.HasSubsystemNamed(VISUALIZER) else None


def _advance(simulator: Simulator, duration: float, progress: bool, name: str) -> None:
    """AdvanceTo in slices so a progress bar (shown after 2 s of wall time) can follow."""
    with tqdm(
        total=round(duration, 3),
        unit="sim s",
        desc=name,
        disable=not progress,
        delay=2.0,
        bar_format="{l_bar}{bar}| {n:.1f}/{total:.1f} sim s [{elapsed}<{remaining}]",
    ) as bar:
        t = 0.0
        while t < duration:
            t = min(duration, t + PROGRESS_STEP)
            simulator.AdvanceTo(t)
            bar.update(round(t - bar.n, 6))


def _metrics(scenario: Scenario, log) -> dict:
    q0 = scenario.configuration(scenario.robot.initial_configuration)
    n = len(q0)
    q = log.data()[:n]
    deviation = np.abs(q - q0[:, None]).max() if q.size else 0.0
    return {
        "scenario": scenario.name,
        "seed": scenario.seed,
        "duration": scenario.duration,
        "time_step": scenario.time_step,
        "versions": _versions(),
        "robot": {
            "variant": scenario.robot.variant,
            "max_deviation_from_initial_rad": _rounded(deviation),
            "final_joint_positions_rad": [_rounded(x) for x in q[:, -1]],
        },
    }


def _rounded(x: float) -> float:
    """Rounded so the report is stable across platforms' last-bit differences."""
    return round(float(x), 9) + 0.0  # + 0.0 turns -0.0 into 0.0


def _versions() -> dict:
    return {"hrc_drake": hrc_drake.__version__, "drake": version("drake")}


def _write_run_directory(report: Report, station, visualizer, meshcat, outputs) -> None:
    out = report.out_dir
    out.mkdir(parents=True, exist_ok=True)
    report.files["report"] = out / "report.json"
    report.files["report"].write_text(json.dumps(report.metrics, indent=2, sort_keys=True) + "\n")
    report.files["diagram"] = write_diagram(station, out / "diagram.svg")
    if visualizer is not None:
        visualizer.StopRecording()
        visualizer.PublishRecording()
        report.files["replay"] = out / "replay.html"
        report.files["replay"].write_text(meshcat.StaticHtml())
    outputs.write_figures(out, report.files)
    report.files["report_html"] = write_run_html(out / "report.html", report.metrics, report.files)
