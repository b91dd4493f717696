"""Running a scenario: `simulate` builds the station, records what happens over the run and
returns it as a `RunRecord`; `run` simulates, evaluates the record
(`hrc_drake.evaluation.report`) and writes the run directory.

The runner records through `build_diagram`'s `attach` hook, from the station's parts: the
arm's state, the monitor's `safety_signals` (with a monitor), the actors' and trees' state
changes (`hrc_drake.systems.state_changes`); after the run it reads the final statuses,
each tree's task events and node counters, and the replay recorder's samples. With a run
directory the trees' transitions are logged there as they happen (`bt_<agent>.btlog` for
Groot2 and `bt_<agent>.jsonl`). Wall-clock time is returned, never written.
"""

import tempfile
import time
from dataclasses import dataclass
from importlib.metadata import version
from pathlib import Path

import numpy as np
from pydrake.geometry import Meshcat
from pydrake.systems.analysis import ApplySimulatorConfig, Simulator
from pydrake.systems.framework import DiagramBuilder
from pydrake.systems.primitives import LogVectorOutput, VectorLogSink
from tqdm import tqdm

import hrc_drake
from hrc_drake.bt import BTError, BtlogWriter, JsonLinesWriter
from hrc_drake.builder import Station, build_diagram
from hrc_drake.evaluation.record import Fault, Footprint, PersonRecord, RunRecord, RunSetup
from hrc_drake.evaluation.report import Report, evaluate, write_run_directory
from hrc_drake.nodes.general import Emit
from hrc_drake.scenario import Scenario, overridden
from hrc_drake.systems.behavior_tree import BehaviorTreeSystem
from hrc_drake.systems.state_changes import StateChanges, add_state_changes
from hrc_drake.wiring import (
    HELD_OBJECTS,
    HUMAN,
    POSTURE_LOG,
    ROBOT,
    ROBOT_STATE_LOG,
    SAFETY,
    SAFETY_SIGNALS_LOG,
    WORKPIECES,
    status_port,
    tree_system,
)
from hrc_drake.yaml_check import InputError

PROGRESS_STEP = 0.1


class RunStopped(InputError):
    """A tree fault (e.g. a blackboard key no node wrote) stopped the run; what the run
    recorded until then is in its report and run directory."""

    def __init__(self, fault: Fault, out_dir: Path | None, report: Report):
        where = f"; what it recorded is in {out_dir}" if out_dir is not None else ""
        super().__init__(f"{fault.error} (the run stopped at {fault.time:.2f} s{where})")
        self.report = report


def run(
    scenario: Scenario,
    seed: int | None = None,
    duration: float | None = None,
    out_dir: Path | str | None = None,
    meshcat: Meshcat | None = None,
    progress: bool = False,
    serve=None,
    scenario_file: Path | None = None,
) -> Report:
    """Simulates `scenario` once and evaluates the run; with `out_dir` (a new or empty
    directory, so files of two runs never mix), writes the run directory. A tree fault ends
    the run early: the run directory is still written, then RunStopped says where the fault
    is. `serve` as for `simulate`; `scenario_file`, where the scenario was read from, lets
    the layout mark what validate finds."""
    given = (("seed", seed), ("duration", duration))
    scenario = overridden(scenario, [(name, value) for name, value in given if value is not None])
    out_dir = Path(out_dir) if out_dir is not None else None
    if out_dir is not None:
        prepare_run_directory(out_dir)
    if meshcat is None and out_dir is not None and scenario.visualization.record:
        meshcat = Meshcat()
    record = simulate(scenario, meshcat, out_dir, progress, serve)
    report = Report(evaluate(record), out_dir, record.wall_time)
    if out_dir is not None:
        from hrc_drake.layout import layout_of, write_layout  # pyplot: only runs that draw

        layout = {
            "layout": write_layout(layout_of(scenario, scenario_file), out_dir / "layout.png")
        }
        report.files = write_run_directory(out_dir, record, report.metrics, layout)
    if record.fault is not None:
        raise RunStopped(record.fault, out_dir, report)
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


def simulate(
    scenario: Scenario,
    meshcat: Meshcat | None = None,
    log_dir: Path | None = None,
    progress: bool = False,
    serve=None,
) -> RunRecord:
    """Simulates `scenario` for its duration and returns what the run recorded. A tree
    fault ends the run early: the record holds it and what came before it.

    `log_dir`, if given (an existing directory), receives the trees' transition logs.
    `serve(diagram)`, if given, starts watchers of the station before the simulation
    (e.g. `hrc_drake.groot.serve_groot`); they are closed when the simulation ends."""
    probes = _Probes(scenario)
    diagram = build_diagram(scenario, meshcat, attach=probes.attach)
    servers = serve(diagram) if serve is not None else None
    tree_logs = _open_tree_logs(probes.station.trees, log_dir)
    simulator = Simulator(diagram)
    ApplySimulatorConfig(scenario.simulator, simulator)
    if servers is not None:
        servers.keep_pace(simulator)
    start = time.perf_counter()
    fault = None
    try:
        _advance(simulator, scenario.duration, progress, scenario.name)
    except BTError as error:  # the tree's own message names file, line, node and port
        fault = Fault(simulator.get_context().get_time(), str(error))
    finally:
        if servers is not None:
            servers.close()
        for log in tree_logs:
            log.close()
    wall_time = time.perf_counter() - start
    return probes.record(simulator.get_context(), diagram, meshcat, fault, wall_time)


def run_setup(scenario: Scenario) -> RunSetup:
    """What the evaluation of a run of `scenario` needs to know of it."""
    return RunSetup(
        scenario=scenario.name,
        seed=scenario.seed,
        duration=scenario.duration,
        time_step=scenario.plant.time_step,
        robot_variant=scenario.robot.variant,
        initial_positions=tuple(scenario.station.initial_positions),
        safety=scenario.safety,
        command_latency=scenario.robot.motion.period,
        ergonomics=scenario.ergonomics,
    )


@dataclass
class _Probes:
    """What the runner attaches to the station (`attach`), and the record it reads from
    them after the run."""

    scenario: Scenario
    station: Station | None = None
    robot_log: VectorLogSink | None = None
    signals_log: VectorLogSink | None = None
    states: StateChanges | None = None
    posture_log: VectorLogSink | None = None
    held: StateChanges | None = None

    def attach(self, builder: DiagramBuilder, station: Station) -> None:
        self.station = station
        self.robot_log = LogVectorOutput(
            station.plant.get_state_output_port(station.arm), builder, self.scenario.report.period
        )
        self.robot_log.set_name(ROBOT_STATE_LOG)
        if station.safety is not None:
            self.signals_log = LogVectorOutput(
                station.safety.GetOutputPort("safety_signals"),
                builder,
                self.scenario.safety.period,
            )
            self.signals_log.set_name(SAFETY_SIGNALS_LOG)
        period = self.scenario.report.period
        self.states = add_state_changes(builder, _state_sources(station), period)
        if station.human is not None:
            self._attach_person(builder, station)

    def _attach_person(self, builder: DiagramBuilder, station: Station) -> None:
        """The person's joint positions and what their hands hold, every
        `ergonomics.period` (a C++ logger; the hands are sampled in Python at that rate)."""
        period = self.scenario.ergonomics.period
        positions = station.human.GetOutputPort("human_positions")
        self.posture_log = LogVectorOutput(positions, builder, period)
        self.posture_log.set_name(POSTURE_LOG)
        if station.workpieces is not None:
            status = station.workpieces.GetOutputPort(status_port(WORKPIECES))
            sources = {HELD_OBJECTS: (status, "person_holds")}
            self.held = add_state_changes(builder, sources, period, HELD_OBJECTS, as_text=False)

    def record(self, context, diagram, meshcat, fault: Fault | None, wall_time) -> RunRecord:
        station = self.station
        robot = self.robot_log.FindLog(context)
        measured = self.signals_log is not None
        signals = self.signals_log.FindLog(context) if measured else None
        trees = station.trees
        return RunRecord(
            setup=run_setup(self.scenario),
            versions={"hrc_drake": hrc_drake.__version__, "drake": version("drake")},
            robot_times=np.array(robot.sample_times()),
            robot_states=np.array(robot.data()),
            signal_times=np.array(signals.sample_times()) if measured else np.zeros(0),
            signals=np.array(signals.data()) if measured else None,
            safety_parts=station.safety.part_names if measured else (),
            safety_status=_final(station.safety, status_port(SAFETY), context),
            realism=_final(station.realism_audit, "realism", context),
            events=_events(trees, context),
            event_names=_event_names(trees),
            states=self.states.changes(),
            node_statistics={agent: _node_statistics(tree) for agent, tree in trees.items()},
            recording=station.recorder.recording if station.recorder is not None else None,
            furniture=_furniture(station),
            person=self._person(context),
            meshcat=meshcat,
            diagram=diagram,
            fault=fault,
            wall_time=wall_time,
        )

    def _person(self, context) -> PersonRecord | None:
        if self.posture_log is None:
            return None
        log = self.posture_log.FindLog(context)
        height, mass = self.scenario.human.size()
        holds = self.held.changes().get(HELD_OBJECTS, []) if self.held is not None else []
        return PersonRecord(height, mass, np.array(log.sample_times()), np.array(log.data()), holds)


def _furniture(station: Station) -> tuple[Footprint, ...]:
    """The floor outlines the person's navigation map walks round (the cell's furniture)."""
    navigation = station.human.navigation if station.human is not None else None
    if navigation is None:
        return ()
    return tuple(
        Footprint(o.name, tuple((float(x), float(y)) for x, y in o.outline.exterior.coords[:-1]))
        for o in navigation.obstacles
    )


def _state_sources(station: Station) -> dict:
    """Actor (or tree) -> (its status output, the attribute that is its state), as the
    timeline draws them."""
    sources = {ROBOT: (station.robot_motion.GetOutputPort(status_port(ROBOT)), "mode")}
    if station.human is not None:
        sources["person"] = (station.human.GetOutputPort(status_port(HUMAN)), "state")
    for agent, tree in station.trees.items():
        sources[f"{agent} tree"] = (tree.GetOutputPort("tree_status"), "running_path")
    return sources


def _final(system, port: str, context):
    """The system's output at the end of the run, or None when the station lacks it."""
    if system is None:
        return None
    return system.GetOutputPort(port).Eval(system.GetMyContextFromRoot(context))


def _events(trees: dict[str, BehaviorTreeSystem], context) -> list:
    """Every tree's task events, by time (then agent)."""
    events = [event for tree in trees.values() for event in _final(tree, "task_events", context)]
    return sorted(events, key=lambda e: (e.time, e.agent))


def _event_names(trees: dict[str, BehaviorTreeSystem]) -> tuple[str, ...]:
    """The task events the trees' Emit nodes name as constants: a report counts them even
    where none happened (a user's robot never finished a kit in a run, and the summary
    said nothing of kits)."""
    named = {
        node.constant_input("event")
        for tree in trees.values()
        for _, _, node in tree.tree.nodes()
        if isinstance(node, Emit)
    }
    return tuple(sorted(named - {None}))


def _node_statistics(system: BehaviorTreeSystem) -> dict:
    """Per node path: how often it was ticked, succeeded, failed, and how long it ran."""
    counts = system.counters.counts()
    return {
        path: {
            "ticks": counts[uid].ticks,
            "successes": counts[uid].successes,
            "failures": counts[uid].failures,
            "time_running": counts[uid].time_running,
            **({"first_failure": counts[uid].first_failure} if counts[uid].first_failure else {}),
        }
        for uid, path, _ in system.tree.nodes()
        if uid in counts
    }


def _open_tree_logs(trees: dict[str, BehaviorTreeSystem], log_dir: Path | None) -> list:
    """Groot2 and JSON-lines transition logs of every tree, in `log_dir`. Opened once the
    watchers are up, so a run refused for a taken port writes nothing."""
    if log_dir is None:
        return []
    logs = []
    for agent, system in trees.items():
        for log in (
            BtlogWriter(log_dir / f"{tree_system(agent)}.btlog"),
            JsonLinesWriter(log_dir / f"{tree_system(agent)}.jsonl"),
        ):
            system.tree.add_observer(log)
            logs.append(log)
    return logs


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
