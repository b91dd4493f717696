"""`hrc-drake`: run scenarios, export their diagrams, validate them, list what is bundled.

User errors (bad arguments, bad scenario files) print one line and exit with status 2;
nothing the run already wrote is removed.
"""

import argparse
import os
import sys
from functools import partial
from pathlib import Path

from hrc_drake.drake_logging import quiet_drake_logging
from hrc_drake.yaml_check import InputError

EXIT_USAGE = 2
PROG = "hrc-drake"
MAX_WORKERS = 4 * (os.cpu_count() or 1)
"""More local workers than this only share the cores and exhaust the memory."""


class _Parser(argparse.ArgumentParser):
    """argparse, but a usage error is one line (no usage dump) and exit status 2."""

    def error(self, message):
        command = self.prog.removeprefix(PROG).strip()
        raise InputError(f"{command}: {message}" if command else message)


def main(argv: list[str] | None = None) -> int:
    quiet_drake_logging()
    parser = _make_parser()
    try:
        args = parser.parse_args(argv)
        return args.command(args)
    except InputError as e:
        print(f"{PROG}: error: {' '.join(str(e).split())}", file=sys.stderr)
        return EXIT_USAGE
    except KeyboardInterrupt:
        print("hrc-drake: interrupted", file=sys.stderr)
        return 130


def _make_parser() -> argparse.ArgumentParser:
    from hrc_drake.bt.groot2 import DEFAULT_PORT

    parser = _Parser(prog=PROG, description=__doc__.splitlines()[0])
    commands = parser.add_subparsers(required=True, metavar="COMMAND", parser_class=_Parser)

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
        type=_port,
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
        type=_positive_float,
        metavar="RATE",
        help="simulated seconds per wall-clock second (default 1 with --meshcat or "
        "--groot, else as fast as it goes)",
    )
    _add_set_option(run)
    run.set_defaults(command=_run)

    sweep = commands.add_parser("sweep", help="run many seeds (and parameter grids) of a scenario")
    sweep.add_argument("scenario", help="a scenario file, or the name of a bundled scenario")
    sweep.add_argument("--seeds", default="0:10", help="START:STOP, N or a comma list (0:10)")
    _add_set_option(sweep)
    _add_execution_options(sweep, "sweep", "sweeps")
    sweep.add_argument(
        "--retry-failed", action="store_true", help="run the failed runs of an earlier sweep again"
    )
    sweep.set_defaults(command=_sweep)

    falsify = commands.add_parser(
        "falsify", help="search the person's behaviour for the smallest safety margin"
    )
    falsify.add_argument("scenario", help="a scenario with a falsify: section (file or name)")
    falsify.add_argument("--budget", type=_positive_int, required=True, help="runs to spend")
    falsify.add_argument("--seed", type=int, help="seed of the runs and the search")
    falsify.add_argument("--duration", type=float, help="simulated seconds of each run")
    _add_set_option(falsify)
    _add_execution_options(falsify, "search", "searches")
    falsify.add_argument(
        "--retry-failed", action="store_true", help="run the failed trials of an earlier search"
    )
    falsify.set_defaults(command=_falsify)

    diagram = commands.add_parser("diagram", help="export the scenario's system diagram")
    diagram.add_argument("scenario")
    diagram.add_argument("-o", "--output", type=Path, required=True, help=".svg, .png or .dot")
    diagram.set_defaults(command=_diagram)

    validate = commands.add_parser("validate", help="check a scenario without simulating")
    validate.add_argument("scenario")
    validate.set_defaults(command=_validate)

    tree = commands.add_parser("tree", help="render a behavior tree to .svg, .png or .dot")
    tree.add_argument("source", help="a tree XML file, or a scenario (then give --agent)")
    tree.add_argument("--agent", choices=("robot", "human"), help="whose tree in the scenario")
    tree.add_argument("--tree-id", help="which tree of the file (default: its main tree)")
    tree.add_argument("-o", "--output", type=Path, required=True, help=".svg, .png or .dot")
    tree.set_defaults(command=_tree)

    listing = commands.add_parser(
        "list", help="bundled scenarios and robot variants, or the behavior tree nodes"
    )
    listing.add_argument(
        "--nodes", action="store_true", help="every tree node with its ports (the palette)"
    )
    listing.add_argument(
        "--xml",
        nargs="?",
        const="-",
        metavar="FILE",
        help="with --nodes: write Groot2's TreeNodesModel XML (to FILE, default stdout)",
    )
    listing.set_defaults(command=_list)
    _add_clip_commands(commands)
    return parser


def _add_clip_commands(commands) -> None:
    clip = commands.add_parser(
        "clip", help="the person's motion clips: list them, export to BVH, import from BVH"
    )
    actions = clip.add_subparsers(required=True, metavar="ACTION", parser_class=_Parser)
    listing = actions.add_parser("list", help="the built-in clips (and a scenario's own)")
    listing.add_argument("scenario", nargs="?", help="also list this scenario's human.clips")
    listing.set_defaults(command=_clip_list)
    export = actions.add_parser("export", help="write a clip as BVH (our skeleton, cm, Y up)")
    export.add_argument("name", help="a clip name (see `clip list`)")
    export.add_argument("-o", "--output", type=Path, required=True, help="a .bvh file")
    export.add_argument("--scenario", help="also look among this scenario's human.clips")
    export.set_defaults(command=_clip_export)
    imported = actions.add_parser(
        "import", help="map a BVH take (Mixamo/CMU bone names) onto the person, as clip JSON"
    )
    imported.add_argument("bvh", type=Path, help="a .bvh file")
    imported.add_argument(
        "-o", "--output", type=Path, help="clip .json to write (default: NAME.json here)"
    )
    imported.add_argument("--name", help="the clip's name (default: the file's name)")
    imported.add_argument("--loop", action="store_true", help="the take loops")
    imported.set_defaults(command=_clip_import)


def _add_set_option(parser) -> None:
    parser.add_argument(
        "--set",
        action="append",
        default=[],
        metavar="PATH=VALUE[,VALUE...]",
        help="change a scenario field, e.g. duration=5 or safety.v_h=1.6,2.0 (a sweep grid)",
    )


def _add_execution_options(parser, what: str, directory: str) -> None:
    """Where the runs of a sweep or a search go, and where its directory is."""
    parser.add_argument(
        "--workers",
        type=_worker_count,
        default=os.cpu_count(),
        help=f"local worker processes (at most {MAX_WORKERS}: each holds a whole simulation)",
    )
    parser.add_argument("--dask", metavar="ADDRESS", help="run on this Dask scheduler instead")
    parser.add_argument(
        "--out",
        type=Path,
        help=f"{what} directory, new or an earlier {what}'s ({directory}/<scenario>)",
    )


def _positive_int(text: str) -> int:
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"'{text}' is not a whole number") from None
    if value < 1:
        raise argparse.ArgumentTypeError(f"must be at least 1, got {text}")
    return value


def _worker_count(text: str) -> int:
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"'{text}' is not a whole number") from None
    if not 1 <= value <= MAX_WORKERS:
        raise argparse.ArgumentTypeError(f"must lie within 1..{MAX_WORKERS}, got {text}")
    return value


def _port(text: str) -> int:
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"'{text}' is not a port number") from None
    if not 1 <= value <= 65534:
        raise argparse.ArgumentTypeError(f"port {text} is out of range (1 to 65534: it uses two)")
    return value


def _positive_float(text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"'{text}' is not a number") from None
    if not value > 0:
        raise argparse.ArgumentTypeError(f"must be positive, got {text}")
    return value


def _run(args) -> int:
    from pydrake.geometry import Meshcat

    from hrc_drake.runner import RunStopped, run
    from hrc_drake.scenario import load_scenario

    overrides, options = _single_sets(args, "run", "use sweep for grids")
    scenario = load_scenario(args.scenario, overrides, options)
    out = args.out or _fresh_directory(Path("runs") / f"{scenario.name}-seed{scenario.seed}")
    if args.groot_host is not None and args.groot is None:
        raise InputError("run: --groot-host goes with --groot")
    meshcat = Meshcat() if args.meshcat else None
    if meshcat is not None:
        print(f"Meshcat: {meshcat.web_url()}")
    live = args.meshcat or args.groot is not None
    serve = None if args.groot is None else partial(_serve_groot, args.groot, args.groot_host)
    try:
        report = run(
            scenario,
            out_dir=out,
            meshcat=meshcat,
            progress=True,
            realtime_rate=args.realtime or (1.0 if live else 0.0),
            serve=serve,
        )
    except RunStopped as stopped:
        _print_node_failures(stopped.report.metrics)
        raise
    print(
        f"{scenario.name}: simulated {report.metrics['duration']:.1f} s in "
        f"{report.wall_time:.1f} s (real-time factor {report.real_time_factor:.1f})"
    )
    for line in key_metrics(report.metrics):
        print(f"  {line}")
    _print_node_failures(report.metrics)
    _print_files(report.files)
    return 0


def _single_sets(args, command: str, grids: str) -> tuple[tuple, dict]:
    """`--set`, `--seed` and `--duration` as overrides (checked like the scenario's own
    fields), and the options that gave them."""
    from hrc_drake.scenario import Scenario
    from hrc_drake.scenario.overrides import parse_sets

    axes = parse_sets(args.set, Scenario)
    if any(len(values) > 1 for _, values in axes):
        raise InputError(f"{command}: --set takes one value per field ({grids})")
    overrides = [(path, values[0]) for path, values in axes]
    options = {}
    for name in ("seed", "duration"):
        if getattr(args, name) is not None:
            overrides.append((name, getattr(args, name)))
            options[name] = f"--{name} {getattr(args, name)}"
    return tuple(overrides), options


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


def _print_node_failures(metrics: dict) -> None:
    from hrc_drake.evaluation.metrics import node_failures

    failures = node_failures(metrics.get("bt", {}))
    if failures:
        print("  tree nodes that failed:")
    for line in failures:
        print(f"    {line}")


def _sweep(args) -> int:
    from hrc_drake.scenario import load_scenario, resolve_scenario_path
    from hrc_drake.sweep import parse_seeds, plan, sweep

    scenario = load_scenario(args.scenario)
    specs = plan(resolve_scenario_path(args.scenario), parse_seeds(args.seeds), args.set)
    out = args.out or Path("sweeps") / scenario.name
    result = sweep(
        specs,
        out,
        args.workers,
        args.dask,
        progress=True,
        scenario_name=scenario.name,
        retry_failed=args.retry_failed,
    )
    for warning in result.warnings:
        print(f"{PROG}: warning: {warning}", file=sys.stderr)
    print(
        f"{scenario.name}: {len(result.rows)} runs ({result.skipped} already done, "
        f"{len(result.failed)} failed)"
    )
    _print_files(result.files)
    return 0


def _falsify(args) -> int:
    from hrc_drake.falsify import falsify, prepare

    overrides, options = _single_sets(args, "falsify", "a falsify: parameter searches a field")
    search = prepare(args.scenario, args.seed, overrides, options)
    name = search.scenario_path.stem
    out = args.out or Path("searches") / name
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
    for line in falsify_lines(name, result):
        print(line)
    _print_files(result.files)
    return 0


def falsify_lines(name: str, result) -> list[str]:
    """What a search found, in a few lines: the verdict and the worst cases."""
    verdict = (
        f"{len(result.violations)} violate ISO/TS 15066" if result.violations else "no violation"
    )
    lines = [f"{name}: {len(result.trials)} trials ({len(result.failed)} failed), {verdict}"]
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


def key_metrics(metrics: dict) -> list[str]:
    """The figures a user looks at first: output, safety, how much the robot was slowed."""
    lines = [
        f"{name}: {count} ({metrics['tasks']['throughput_per_hour'][name]:g}/h)"
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
    margin = metrics.get("margin") or {}
    if "value" in margin:
        at = margin.get("at")
        where = f" ({at['region']} / {at['part']} at {at['time']:.1f} s)" if at else ""
        lines.append(f"safety margin: {_metres(margin['value'])}{where}")
    return lines


def _print_files(files: dict[str, Path]) -> None:
    width = max(map(len, files), default=0)
    for name, path in files.items():
        print(f"  {name:{width}s} {path}")


def _diagram(args) -> int:
    from hrc_drake.builder import build_diagram
    from hrc_drake.diagram_export import write_diagram
    from hrc_drake.scenario import load_scenario

    _check_output(args.output, "-o", (".svg", ".png", ".dot"))
    write_diagram(build_diagram(load_scenario(args.scenario)), args.output)
    print(args.output)
    return 0


def _check_output(path: Path, option: str, suffixes: tuple[str, ...]) -> None:
    """An output file the command can write, checked before any work is done."""
    if suffixes and path.suffix.lower() not in suffixes:
        raise InputError(f"{option} {path}: use a {', '.join(suffixes)} file name")
    if path.is_dir():
        raise InputError(f"{option} {path}: is a directory; give a file name")
    if not path.parent.is_dir():
        raise InputError(f"{option} {path}: directory '{path.parent}' does not exist")
    if not os.access(path.parent, os.W_OK) or (path.exists() and not os.access(path, os.W_OK)):
        raise InputError(f"{option} {path}: cannot write there: permission denied")


def _validate(args) -> int:
    from hrc_drake.builder import build_diagram
    from hrc_drake.scenario import load_scenario

    scenario = load_scenario(args.scenario)
    built = []
    build_diagram(scenario, attach=lambda _, station: built.append(station))
    _check_stand_spots(args.scenario, scenario, built[0])
    trees = ", ".join(f"{agent}: {Path(tree.file).name}" for agent, tree in scenario.trees.items())
    print(f"{args.scenario}: ok ({scenario.name}{'; trees ' + trees if trees else ''})")
    return 0


def _check_stand_spots(name_or_path: str, scenario, station) -> None:
    """Places to stand where the person would stand in the cell's geometry (file:line)."""
    from hrc_drake.human.navigation import stand_problems
    from hrc_drake.scenario import resolve_scenario_path
    from hrc_drake.yaml_check import compose, located_error, node_at

    if station.human is None:
        return
    navigation = station.human.navigation
    locations = {name: scenario.location(name) for name in scenario.locations}
    problems = stand_problems(navigation, locations)
    if problems:
        path = resolve_scenario_path(name_or_path)
        root = compose(path, path.read_text())
        raise InputError(
            "\n".join(
                str(
                    located_error(
                        path, node_at(root, ("locations", name)), f"locations.{name}", why
                    )
                )
                for name, why in problems
            )
        )


def _tree(args) -> int:
    from hrc_drake.bt import BTError, load_tree, render_tree
    from hrc_drake.nodes import hrc_registry
    from hrc_drake.scenario import load_scenario

    _check_output(args.output, "-o", (".svg", ".png", ".dot"))
    if args.source.endswith(".xml"):
        try:
            tree = load_tree(Path(args.source), hrc_registry(), tree_id=args.tree_id)
        except BTError as error:
            raise InputError(str(error)) from None
    else:
        scenario = load_scenario(args.source)
        if args.agent not in scenario.trees:
            known = ", ".join(scenario.trees) or "none"
            raise InputError(f"{args.source}: give --agent, one of: {known}")
        tree, _ = scenario.agent_tree(args.agent)
    render_tree(tree, args.output)
    print(args.output)
    return 0


def _list(args) -> int:
    if args.nodes:
        return _list_nodes(args.xml)
    if args.xml:
        raise InputError("--xml goes with --nodes")
    from hrc_drake.iisy import VARIANTS
    from hrc_drake.scenario import bundled_scenarios, load_scenario

    print("scenarios:")
    for name in bundled_scenarios():
        print(f"  {name:16s} {load_scenario(name).description}")
    print("robot variants:")
    for name, variant in VARIANTS.items():
        print(
            f"  {name:16s} payload {variant.payload:g} kg, reach {variant.reach:g} m, "
            f"{variant.total_mass:g} kg"
        )
    return 0


def _list_nodes(xml_file: str | None) -> int:
    from hrc_drake.bt import tree_nodes_model_xml
    from hrc_drake.nodes import hrc_registry, palette_text

    registry = hrc_registry()
    if xml_file is None:
        print(palette_text(registry))
    elif xml_file == "-":
        print(tree_nodes_model_xml(registry))
    else:
        _check_output(Path(xml_file), "--xml", ())
        Path(xml_file).write_text(tree_nodes_model_xml(registry) + "\n")
        print(xml_file)
    return 0


def _scenario_clips(scenario: str | None) -> dict:
    from hrc_drake.human.clip_files import clip_catalog
    from hrc_drake.scenario import load_scenario

    human = load_scenario(scenario).human if scenario else None
    return clip_catalog(human.clips if human is not None else ())


def _clip_list(args) -> int:
    from hrc_drake.human.clip_files import describe

    for name, clip in sorted(_scenario_clips(args.scenario).items()):
        print(f"  {name:12s} {describe(clip)}")
    return 0


def _clip_export(args) -> int:
    from hrc_drake.human.bvh import export_bvh

    _check_output(args.output, "-o", (".bvh",))
    clips = _scenario_clips(args.scenario)
    if args.name not in clips:
        raise InputError(f"clip export: no clip '{args.name}' (known: {', '.join(sorted(clips))})")
    export_bvh(clips[args.name], args.output)
    print(args.output)
    return 0


def _clip_import(args) -> int:
    from hrc_drake.human.clip import clip_to_json
    from hrc_drake.human.clip_files import describe, read_clip_file

    if args.bvh.suffix.lower() != ".bvh":
        raise InputError(f"{args.bvh}: use a .bvh file")
    output = args.output or Path(f"{args.name or args.bvh.stem}.json")
    _check_output(output, "-o", (".json",))
    clip = read_clip_file(args.bvh, name=args.name, loop=args.loop)
    output.write_text(clip_to_json(clip))
    print(f"{output}: {clip.name}, {describe(clip)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
