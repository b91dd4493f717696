"""`hrc-drake run`, `sweep` and `falsify`: the commands that simulate, and what they print."""

import sys
from functools import partial
from pathlib import Path

from hrc_drake.bt.groot2 import DEFAULT_PORT
from hrc_drake.cli.arguments import (
    PROG,
    add_execution_options,
    add_set_option,
    port_number,
    positive_float,
    positive_int,
    single_sets,
)
from hrc_drake.yaml_check import InputError

MOSTLY_STOPPED = 0.5
"""The fraction of a run stopped above which the summary says where the person stood."""


def add_commands(commands) -> None:
    run = commands.add_parser("run", help="simulate a scenario and write its run directory")
    run.add_argument("scenario", help="a scenario file, or the name of a bundled scenario")
    run.add_argument("--seed", type=int, help="random seed (default: the scenario's)")
    run.add_argument("--duration", type=float, help="simulated seconds")
    run.add_argument(
        "--out",
        type=Path,
        help="run directory, new or empty (default: runs/<scenario>-seed<N>, or -2, -3... "
        "if that holds an earlier run)",
    )
    run.add_argument(
        "--meshcat", action="store_true", help="show the run live in Meshcat, at real time"
    )
    run.add_argument(
        "--groot",
        nargs="?",
        const=DEFAULT_PORT,
        type=port_number,
        metavar="PORT",
        help=f"serve the trees live to Groot2 at real time: the robot's on PORT "
        f"(default {DEFAULT_PORT}), the person's on the next free pair",
    )
    run.add_argument(
        "--groot-host",
        metavar="ADDRESS",
        help="address the Groot2 servers listen on (default 127.0.0.1: this machine only)",
    )
    run.add_argument(
        "--realtime",
        type=positive_float,
        metavar="RATE",
        help="simulated seconds per wall-clock second (default 1 with --meshcat or "
        "--groot, else as fast as it goes)",
    )
    add_set_option(run)
    run.set_defaults(command=_run)

    sweep = commands.add_parser("sweep", help="run many seeds (and parameter grids) of a scenario")
    sweep.add_argument("scenario", help="a scenario file, or the name of a bundled scenario")
    sweep.add_argument("--seeds", default="0:10", help="START:STOP, N or a comma list (0:10)")
    sweep.add_argument("--duration", type=float, help="simulated seconds of each run")
    add_set_option(sweep)
    add_execution_options(sweep, "sweep", "sweeps")
    sweep.add_argument(
        "--retry-failed", action="store_true", help="run the failed runs of an earlier sweep again"
    )
    sweep.set_defaults(command=_sweep)

    falsify = commands.add_parser(
        "falsify", help="search the person's behaviour for the smallest safety margin"
    )
    falsify.add_argument("scenario", help="a scenario with a falsify: section (file or name)")
    falsify.add_argument("--budget", type=positive_int, required=True, help="runs to spend")
    falsify.add_argument("--seed", type=int, help="seed of the runs and the search")
    falsify.add_argument("--duration", type=float, help="simulated seconds of each run")
    add_set_option(falsify)
    add_execution_options(falsify, "search", "searches")
    falsify.add_argument(
        "--retry-failed", action="store_true", help="run the failed trials of an earlier search"
    )
    falsify.set_defaults(command=_falsify)


def _run(args) -> int:
    from pydrake.geometry import Meshcat

    from hrc_drake.runner import RunStopped, run
    from hrc_drake.scenario import load_scenario, resolve_scenario_path

    overrides, options = single_sets(args, "run", "use sweep for grids")
    live = args.meshcat or args.groot is not None
    realtime = args.realtime or (1.0 if live else None)
    if realtime is not None:
        overrides += (("simulator.target_realtime_rate", realtime),)
        options["simulator.target_realtime_rate"] = f"--realtime {realtime}"
    scenario = load_scenario(args.scenario, overrides, options)
    out = args.out or _fresh_directory(Path("runs") / f"{scenario.name}-seed{scenario.seed}")
    if args.groot_host is not None and args.groot is None:
        raise InputError("run: --groot-host goes with --groot")
    meshcat = Meshcat() if args.meshcat else None
    if meshcat is not None:
        print(f"Meshcat: {meshcat.web_url()}")
    serve = None if args.groot is None else partial(_serve_groot, args.groot, args.groot_host)
    try:
        report = run(
            scenario,
            out_dir=out,
            meshcat=meshcat,
            progress=True,
            serve=serve,
            scenario_file=resolve_scenario_path(args.scenario),
        )
    except RunStopped as stopped:
        _print_node_failures(scenario.name, stopped.report.metrics)
        raise
    _print_node_failures(scenario.name, report.metrics)
    _warn_of_findings(scenario, resolve_scenario_path(args.scenario))
    print(
        f"{scenario.name}: simulated {report.metrics['duration']:.1f} s in "
        f"{report.wall_time:.1f} s (real-time factor {report.real_time_factor:.1f})"
    )
    for line in key_metrics(report.metrics):
        print(f"  {line}")
    print_files(report.files)
    return 0


def _warn_of_findings(scenario, path) -> None:
    """What `validate` finds, as warnings after a run that completed: a user who runs a
    cell without validating it learns of its mistakes with the run's outcome (a user's
    palletizing cell ran 120 s with 6 of validate's lines unread). A finding may be a false
    alarm (validate cannot know a tree's conditions), so it does not stop a run; a run that
    stops says only why, in one line."""
    from hrc_drake.scenario.findings import findings

    found = findings(scenario, path)
    for finding in found:
        print(f"{PROG}: warning: {finding}", file=sys.stderr)
    if found:
        lines = f"{len(found)} line{'s' if len(found) != 1 else ''}"
        print(f"{PROG}: warning: validate finds {lines} above in the cell as run", file=sys.stderr)


def _serve_groot(port: int, host: str | None, station):
    """Groot2 servers for the run's trees, bound before anything is simulated or written."""
    from hrc_drake.bt.groot2 import ServeError
    from hrc_drake.groot import LOCALHOST, serve_groot

    try:
        servers = serve_groot(station, port, host or LOCALHOST)
    except ServeError as error:
        raise InputError(str(error)) from None
    print(servers, flush=True)
    return servers


def _fresh_directory(path: Path) -> Path:
    """`path`, or `path-2`, `path-3`... : the first that is missing or empty."""
    candidate, n = path, 1
    while candidate.is_dir() and any(candidate.iterdir()) or candidate.is_file():
        n += 1
        candidate = path.with_name(f"{path.name}-{n}")
    return candidate


def _print_node_failures(name: str, metrics: dict) -> None:
    """Before anything else: the actions that went wrong, and why."""
    from hrc_drake.evaluation.metrics import WHY_NODES_FAIL, node_failures

    failures = node_failures(metrics.get("bt", {}))
    if failures:
        count = f"{len(failures)} tree node{'s' if len(failures) != 1 else ''}"
        print(f"{name}: {count} failed {WHY_NODES_FAIL}:")
    for line in failures:
        print(f"  {line}")


def _sweep(args) -> int:
    from hrc_drake.evaluation.sweep_report import verdicts
    from hrc_drake.scenario import resolve_scenario_path
    from hrc_drake.sweep import parse_seeds, plan, sweep

    fixed, options = (), {}
    if args.duration is not None:
        fixed, options = (("duration", args.duration),), {"duration": f"--duration {args.duration}"}
    path = resolve_scenario_path(args.scenario)
    specs = plan(path, parse_seeds(args.seeds), args.set, fixed, options)
    out = args.out or Path("sweeps") / specs.name
    result = sweep(
        specs, out, args.workers, args.dask, progress=True, retry_failed=args.retry_failed
    )
    for warning in result.warnings:
        print(f"{PROG}: warning: {warning}", file=sys.stderr)
    print(
        f"{specs.name}: {len(result.rows)} runs ({result.skipped} already done, "
        f"{len(result.failed)} failed)"
    )
    for line in verdicts(result.rows):
        print(f"  {line}")
    print_files(result.files)
    return 0


def _falsify(args) -> int:
    from hrc_drake.falsify import falsify, prepare

    overrides, options = single_sets(args, "falsify", "a falsify: parameter searches a field")
    search = prepare(args.scenario, args.seed, overrides, options)
    out = args.out or Path("searches") / search.name
    result = falsify(
        search,
        args.budget,
        out,
        args.workers,
        args.dask,
        progress=True,
        retry_failed=args.retry_failed,
    )
    for warning in result.warnings:
        print(f"{PROG}: warning: {warning}", file=sys.stderr)
    for line in falsify_lines(result):
        print(line)
    print_files(result.files)
    return 0


def falsify_lines(result) -> list[str]:
    """What a search found, in a few lines: the verdict and the worst cases."""
    verdict = (
        f"{len(result.violations)} violate ISO/TS 15066" if result.violations else "no violation"
    )
    trials = f"{len(result.trials)} trials ({len(result.failed)} failed)"
    lines = [f"{result.search.name}: {trials}, {verdict}"]
    for trial in result.worst:
        margin = trial.margin
        at = margin.get("at")
        where = f" ({at['region']} / {at['part']} at {at['time']:.1f} s)" if at else ""
        lines.append(f"  trial {trial.number}: margin {_metres(margin.get('value'))}{where}")
        if trial.number in result.cases:
            lines.append(f"    {result.cases[trial.number]}")
        lines.append(f"    {result.search.command(trial.values)}")
    return lines


def _metres(value) -> str:
    return "none (the robot never moved near the person)" if value is None else f"{value:.3f} m"


def _margin_line(margin: dict) -> str:
    """The safety margin and what set it: the least separation - S_p (where and when), or a
    contact (its ratio to ISO/TS 15066's limit; the SSM margin and its place beside it: a
    margin of -5.10 m printed with where the separation was least read as a miscalculation
    next to 'SSM violations: 0')."""
    at = margin.get("at")
    where = f"{at['region']} / {at['part']} at {at['time']:.1f} s" if at else ""
    line = f"safety margin: {_metres(margin['value'])}"
    value, ssm = margin["value"], margin.get("ssm")
    if value is not None and (ssm is None or value < ssm):
        beside = f"; SSM margin {_metres(ssm)} ({where})" if where else ""
        return f"{line}, set by a contact at {margin['contact_ratio']:g} × its limit{beside}"
    return f"{line} ({where})" if where else line


def _stopped_line(utilisation: dict) -> list[str]:
    """A hint when the robot stood stopped with a move to make for most of the run: where
    the person stood then (a person who waits there for the robot keeps it stopped: a user's
    cell stood still 95 % of its run, and the summary gave no hint why). Stopped with
    nothing to do, it lost nothing, and nothing is said."""
    place = utilisation.get("stopped_with_person_at")
    if utilisation.get("stopped", 0.0) < MOSTLY_STOPPED or place is None:
        return []
    return [
        f"the robot was stopped {100 * utilisation['stopped']:.0f} % of the run with a move "
        f"to make, the person near it, most of that time at ({place[0]:.2f}, {place[1]:.2f}): "
        "a person who waits there for the robot keeps it stopped"
    ]


def _per_hour(rate: float) -> str:
    """An hourly rate to three figures, whole from 100 on ("51.4", not "51.4286": a
    user's 70 s run)."""
    return f"{rate:.0f}" if rate >= 100 else f"{rate:.3g}"


def key_metrics(metrics: dict) -> list[str]:
    """The figures a user looks at first: output, safety, how much the robot was slowed,
    and whether the person moved as a person does (the realism audit)."""
    from hrc_drake.evaluation.realism import realism_verdict

    lines = [
        f"{name}: {count} ({_per_hour(metrics['tasks']['throughput_per_hour'][name])}/h)"
        for name, count in metrics.get("tasks", {}).get("events", {}).items()
    ]
    safety = metrics.get("safety") or {}
    if safety.get("min_separation"):
        closest = safety["min_separation"]
        lines += [
            f"min separation: {closest['distance']:.3f} m ({closest['region']} / "
            f"{closest['link']} at {closest['time']:.1f} s)",
            f"SSM violations: {safety['ssm_violations']['count']}, "
            f"contacts: {safety['contacts']['robot_moving']} by the moving robot, "
            f"{safety['contacts']['robot_at_rest']} with it at rest, stops: {safety['stops']}, "
            f"reduced {safety['time_reduced']:.1f} s, stopped {safety['time_stopped']:.1f} s",
        ]
    lines += _stopped_line((metrics.get("utilisation") or {}).get("robot") or {})
    sensing = metrics.get("sensing") or {}
    if sensing.get("sensors"):
        lines.append(
            f"the monitor saw the person through {', '.join(sensing['sensors'])}: seen "
            f"{sensing['time_seen']:.1f} s, not seen {sensing['time_not_seen']:.1f} s"
        )
    elif sensing:
        lines.append("the monitor knew every point of the person's body (no safety sensors)")
    margin = metrics.get("margin") or {}
    if "value" in margin:
        lines.append(_margin_line(margin))
    verdict = realism_verdict(metrics.get("realism") or {})
    if verdict:
        lines.append(f"realism: {verdict[0]}")
        lines += [f"  {line}" for line in verdict[1:]]
    return lines


def print_files(files: dict[str, Path]) -> None:
    width = max(map(len, files), default=0)
    for name, path in files.items():
        print(f"  {name:{width}s} {path}")
