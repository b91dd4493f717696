"""Running a scenario: simulate the station diagram and write the run directory.

A run directory holds `report.json` (deterministic: same scenario and seed give the same
bytes, so it holds no wall-clock figures), `replay.html` (a standalone Meshcat recording),
`diagram.svg`, and with a safety monitor in the station `safety.npz` (its signals at every
update, `hrc_drake.safety.log`), `timeline.png`, `heatmap.png`, plus `report.html` tying them
together. Wall-clock speed is returned to the caller, never
written to the report.

Optional station parts the runner measures when they exist: `safety_signals` and
`safety_status` (SafetyMonitor); each agent's `<agent>_task_events` and `<agent>_tree_status`
and its BehaviorTreeSystem `bt_<agent>` (node statistics; with a run directory also the
transition logs `bt_<agent>.btlog` for Groot2 and `bt_<agent>.jsonl`); the robot's and the
person's states for the timeline.
"""

import json
import tempfile
import time
from dataclasses import dataclass, field
from importlib.metadata import version
from pathlib import Path

import numpy as np
from pydrake.geometry import Meshcat
from pydrake.systems.analysis import Simulator
from pydrake.systems.framework import DiagramBuilder, LeafSystem
from pydrake.systems.primitives import LogVectorOutput
from tqdm import tqdm

import hrc_drake
from hrc_drake.bt import BTError, BtlogWriter, JsonLinesWriter
from hrc_drake.builder import build_diagram
from hrc_drake.diagram_export import write_diagram
from hrc_drake.evaluation.metrics import (
    bt_metrics,
    person_metrics,
    safety_metrics,
    task_metrics,
    utilisation_metrics,
)
from hrc_drake.evaluation.realism import realism_metrics
from hrc_drake.evaluation.replay import write_replay
from hrc_drake.evaluation.run_report import write_run_html
from hrc_drake.evaluation.timeline import plot_heatmap, plot_timeline
from hrc_drake.ports import message_value
from hrc_drake.safety.config import SafetyConfig
from hrc_drake.safety.log import write_safety_log
from hrc_drake.safety.margin import log_of, margin_metrics, reference_model
from hrc_drake.scenario import Scenario, overridden
from hrc_drake.wiring import HUMAN_MODEL, RECORDER, SAFETY_MONITOR, VISUAL_PREFIX, tree_system
from hrc_drake.yaml_check import InputError

LOG_PERIOD = 0.01
PROGRESS_STEP = 0.1


class RunStopped(InputError):
    """A tree fault (e.g. a blackboard key no node wrote) stopped the run; what the run
    recorded until then is in its report and run directory."""

    def __init__(self, fault: BTError, time: float, out_dir: Path | None, report: "Report"):
        where = f"; what it recorded is in {out_dir}" if out_dir is not None else ""
        super().__init__(f"{fault} (the run stopped at {time:.2f} s{where})")
        self.report = report


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
    serve=None,
) -> Report:
    """Simulates `scenario` once; with `out_dir` (a new or empty directory, so files of
    two runs never mix), writes the run directory. A tree fault ends the run early: the
    run directory is still written, then RunStopped says where the fault is.

    `serve(station)`, if given, starts watchers of the station before the simulation
    (e.g. `hrc_drake.groot.serve_groot`); they are closed when the simulation ends."""
    given = (("seed", seed), ("duration", duration))
    scenario = overridden(scenario, [(name, value) for name, value in given if value is not None])
    out_dir = Path(out_dir) if out_dir is not None else None
    if out_dir is not None:
        prepare_run_directory(out_dir)
    if meshcat is None and out_dir is not None and scenario.visualization.record:
        meshcat = Meshcat()
    station = build_diagram(scenario, meshcat)
    builder = DiagramBuilder()
    builder.AddSystem(station)
    state_log = LogVectorOutput(station.GetOutputPort("robot_state"), builder, LOG_PERIOD)
    signals_log = _optional_log(station, "safety_signals", builder, scenario.safety.period)
    states_log = _add_state_changes(station, scenario, builder)
    diagram = builder.Build()
    servers = serve(station) if serve is not None else None
    tree_logs = _open_tree_logs(station, scenario, out_dir)

    simulator = Simulator(diagram)
    simulator.set_target_realtime_rate(realtime_rate)
    if servers is not None:
        servers.keep_pace(simulator)
    start = time.perf_counter()
    fault = None
    try:
        _advance(simulator, scenario.duration, progress, scenario.name)
    except BTError as error:  # the tree's own message names file, line, node and port
        fault = error
    finally:
        if servers is not None:
            servers.close()
    wall_time = time.perf_counter() - start
    for log in tree_logs:
        log.close()

    context = simulator.get_context()
    outputs = _RunOutputs.collect(station, scenario, context, signals_log, states_log)
    metrics = _metrics(scenario, state_log.FindLog(context))
    metrics.update(outputs.metrics(scenario))
    if fault is not None:
        metrics["stopped"] = {"time": _rounded(context.get_time()), "error": str(fault)}
    report = Report(metrics, out_dir, wall_time)
    if out_dir is not None:
        _write_run_directory(report, station, meshcat, outputs)
    if fault is not None:
        raise RunStopped(fault, context.get_time(), out_dir, report)
    return report


def prepare_run_directory(out_dir: Path) -> None:
    """Creates the run directory; one that holds anything already is refused."""
    if out_dir.is_dir() and any(out_dir.iterdir()):
        raise InputError(
            f"{out_dir}: the run directory is not empty (it may hold another run); "
            "give a new or empty directory"
        )
    try:
        out_dir.mkdir(parents=True, exist_ok=True)
    except FileExistsError:
        raise InputError(f"{out_dir}: is a file, not a directory") from None
    except OSError as e:
        raise InputError(f"{out_dir}: cannot create the run directory: {e.strerror}") from None
    try:
        with tempfile.TemporaryFile(dir=out_dir):
            pass  # a file can be written there: the run's files will be
    except OSError as e:
        raise InputError(f"{out_dir}: cannot write in the run directory: {e.strerror}") from None


@dataclass
class _RunOutputs:
    """What the optional station outputs recorded over the run."""

    times: np.ndarray
    signals: np.ndarray | None
    status: object | None
    events: list
    states: dict[str, list[tuple[float, str]]]
    bt_statistics: dict | None
    safety_parts: tuple[str, ...]
    """the robot parts the `part` safety signal numbers"""
    realism: object | None

    @classmethod
    def collect(cls, station, scenario, context, signals_log, states_log) -> "_RunOutputs":
        station_context = station.GetMyContextFromRoot(context)
        log = signals_log.FindLog(context) if signals_log is not None else None
        events = [
            event
            for agent in scenario.trees
            for event in station.GetOutputPort(f"{agent}_task_events").Eval(station_context)
        ]
        return cls(
            times=log.sample_times() if log is not None else np.zeros(0),
            signals=log.data() if log is not None else None,
            status=_final(station, station_context, "safety_status"),
            events=sorted(events, key=lambda e: (e.time, e.agent)),
            states=states_log.changes(),
            realism=_final(station, station_context, "realism"),
            bt_statistics={
                agent: _node_statistics(station.GetSubsystemByName(tree_system(agent)))
                for agent in scenario.trees
            },
            safety_parts=station.GetSubsystemByName(SAFETY_MONITOR).part_names if log else (),
        )

    def metrics(self, scenario: Scenario) -> dict:
        safety = getattr(scenario, "safety", SafetyConfig())
        measured = self.signals is not None
        return {
            "safety": safety_metrics(self.status, safety.moving_speed),
            "utilisation": {
                "robot": utilisation_metrics(self.times, self.signals, safety.moving_speed)
                if measured
                else {}
            },
            "person": person_metrics(self.times, self.signals) if measured else {},
            "margin": self._margin(scenario, safety) if measured else {},
            "tasks": task_metrics(self.events, scenario.duration),
            "bt": bt_metrics(self.bt_statistics),
            "realism": realism_metrics(self.realism),
        }

    def _margin(self, scenario: Scenario, safety: SafetyConfig) -> dict:
        return margin_metrics(
            log_of(self.signals),
            reference_model(scenario),
            safety.moving_speed,
            self.status.totals.contact_records,
            self.safety_parts,
        )

    def write_figures(self, out: Path, files: dict[str, Path]) -> None:
        if self.signals is None:
            return
        parts = self.safety_parts
        files["safety_log"] = write_safety_log(out / "safety.npz", self.signals, parts)
        files["timeline"] = plot_timeline(
            out / "timeline.png", self.times, self.signals, self.states, self.events
        )
        heatmap = plot_heatmap(out / "heatmap.png", self.times, self.signals)
        if heatmap is not None:
            files["heatmap"] = heatmap


class _StateChanges(LeafSystem):
    """Samples status ports and keeps, per actor, the times its state changed."""

    def __init__(self, fields: dict[str, str], period: float):
        super().__init__()
        self._inputs = {
            actor: (self.DeclareAbstractInputPort(actor, message_value()), attribute)
            for actor, attribute in fields.items()
        }
        self._changes: dict[str, list[tuple[float, str]]] = {}
        self.DeclarePeriodicPublishEvent(period, 0.0, self._sample)

    def _sample(self, context) -> None:
        for actor, (port, attribute) in self._inputs.items():
            state = str(getattr(port.Eval(context), attribute))
            history = self._changes.setdefault(actor, [])
            if not history or history[-1][1] != state:
                history.append((context.get_time(), state))

    def changes(self) -> dict[str, list[tuple[float, str]]]:
        return self._changes


STATE_FIELDS = {"robot": ("robot_status", "mode"), "person": ("human_status", "state")}
"""Actor -> (station output, status attribute) drawn as the actor's state in the timeline."""


def _add_state_changes(station, scenario, builder) -> _StateChanges:
    fields = {
        actor: (port, attribute)
        for actor, (port, attribute) in STATE_FIELDS.items()
        if station.HasOutputPort(port)
    }
    fields |= {
        f"{agent} tree": (f"{agent}_tree_status", "running_path") for agent in scenario.trees
    }
    sampler = builder.AddSystem(
        _StateChanges({actor: attribute for actor, (_, attribute) in fields.items()}, LOG_PERIOD)
    )
    for actor, (port, _) in fields.items():
        builder.Connect(station.GetOutputPort(port), sampler.GetInputPort(actor))
    return sampler


def _node_statistics(tree_system) -> dict:
    """Per node path: how often it was ticked, succeeded, failed, and how long it ran."""
    counts = tree_system.counters.counts()
    return {
        path: {
            "ticks": counts[uid].ticks,
            "successes": counts[uid].successes,
            "failures": counts[uid].failures,
            "time_running": counts[uid].time_running,
            **({"first_failure": counts[uid].first_failure} if counts[uid].first_failure else {}),
        }
        for uid, path, _ in tree_system.tree.nodes()
        if uid in counts
    }


def _open_tree_logs(station, scenario, out_dir: Path | None) -> list:
    """Groot2 and JSON-lines transition logs of every tree, in the run directory."""
    if out_dir is None:
        return []
    logs = []
    for agent in scenario.trees:
        tree = station.GetSubsystemByName(tree_system(agent)).tree
        for log in (
            BtlogWriter(out_dir / f"bt_{agent}.btlog"),
            JsonLinesWriter(out_dir / f"bt_{agent}.jsonl"),
        ):
            tree.add_observer(log)
            logs.append(log)
    return logs


def _optional_log(station, port: str, builder, period: float):
    if not station.HasOutputPort(port):
        return None
    return LogVectorOutput(station.GetOutputPort(port), builder, period)


def _final(station, station_context, port: str):
    """The port's value at the end of the run, or None when the station lacks it."""
    if not station.HasOutputPort(port):
        return None
    return station.GetOutputPort(port).Eval(station_context)


def _recording(station):
    """What the station's ReplayRecorder sampled, or None when it records no replay."""
    if not station.HasSubsystemNamed(RECORDER):
        return None
    return station.GetSubsystemByName(RECORDER).recording


def _advance(simulator: Simulator, duration: float, progress: bool, name: str) -> None:
    """AdvanceTo in slices so a progress bar (shown after 2 s of wall time) can follow."""
    with tqdm(
        total=round(duration, 3),
        unit="sim s",
        desc=name,
        disable=None if progress else True,  # None: only on a terminal
        delay=2.0,
        bar_format="{l_bar}{bar}| {n:.1f}/{total:.1f} sim s [{elapsed}<{remaining}]",
    ) as bar:
        t = 0.0
        while t < duration:
            t = min(duration, t + PROGRESS_STEP)
            simulator.AdvanceTo(t)
            bar.update(round(t - bar.n, 6))


def _metrics(scenario: Scenario, log) -> dict:
    q0 = scenario.station.initial_positions
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


def _write_run_directory(report: Report, station, meshcat, outputs) -> None:
    out = report.out_dir
    report.files["report"] = out / "report.json"
    report.files["report"].write_text(json.dumps(report.metrics, indent=2, sort_keys=True) + "\n")
    report.files["diagram"] = write_diagram(station, out / "diagram.svg")
    recording = _recording(station)
    if recording is not None:
        report.files["replay"] = write_replay(
            out / "replay.html", meshcat, recording, f"/drake/{VISUAL_PREFIX}/{HUMAN_MODEL}"
        )
    outputs.write_figures(out, report.files)
    report.files["report_html"] = write_run_html(out / "report.html", report.metrics, report.files)
