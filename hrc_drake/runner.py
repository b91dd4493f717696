"""Running a scenario: simulate the station diagram and write the run directory.

A run directory holds `report.json` (deterministic: same scenario and seed give the same
bytes, so it holds no wall-clock figures), `replay.html` (a standalone Meshcat recording)
and `diagram.svg`. Wall-clock speed is returned to the caller, never written to the report.
"""

import json
import time
from dataclasses import dataclass, field
from importlib.metadata import version
from pathlib import Path

import numpy as np
from pydrake.geometry import Meshcat
from pydrake.systems.analysis import Simulator
from pydrake.systems.framework import DiagramBuilder
from pydrake.systems.primitives import LogVectorOutput
from tqdm import tqdm

import hrc_drake
from hrc_drake.builder import VISUALIZER, build_diagram
from hrc_drake.diagram_export import write_diagram
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
    diagram = builder.Build()

    simulator = Simulator(diagram)
    simulator.set_target_realtime_rate(realtime_rate)
    visualizer = _visualizer(station)
    if visualizer is not None:
        visualizer.StartRecording(set_transforms_while_recording=realtime_rate > 0)
    start = time.perf_counter()
    _advance(simulator, scenario.duration, progress, scenario.name)
    wall_time = time.perf_counter() - start

    log = state_log.FindLog(simulator.get_context())
    report = Report(_metrics(scenario, log), out_dir, wall_time)
    if out_dir is not None:
        _write_run_directory(report, station, visualizer, meshcat)
    return report


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


def _write_run_directory(report: Report, station, visualizer, meshcat) -> None:
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
