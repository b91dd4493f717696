"""`hrc-drake`: run scenarios, export their diagrams, validate them, list what is bundled.

User errors (bad arguments, bad scenario files) print one line and exit with status 2;
nothing the run already wrote is removed.
"""

import argparse
import os
import sys
from pathlib import Path

from hrc_drake.yaml_check import InputError

EXIT_USAGE = 2


class _Parser(argparse.ArgumentParser):
    """argparse, but a usage error is one line (no usage dump) and exit status 2."""

    def error(self, message):
        raise InputError(f"{self.prog}: {message}")


def main(argv: list[str] | None = None) -> int:
    parser = _make_parser()
    try:
        args = parser.parse_args(argv)
        return args.command(args)
    except InputError as e:
        print(f"hrc-drake: error: {e}", file=sys.stderr)
        return EXIT_USAGE
    except KeyboardInterrupt:
        print("hrc-drake: interrupted", file=sys.stderr)
        return 130


def _make_parser() -> argparse.ArgumentParser:
    parser = _Parser(prog="hrc-drake", description=__doc__.splitlines()[0])
    commands = parser.add_subparsers(required=True, metavar="COMMAND", parser_class=_Parser)

    run = commands.add_parser("run", help="simulate a scenario and write its run directory")
    run.add_argument("scenario", help="a scenario file, or the name of a bundled scenario")
    run.add_argument("--seed", type=int, help="random seed (default: the scenario's)")
    run.add_argument("--duration", type=_positive_float, help="simulated seconds")
    run.add_argument("--out", type=Path, help="run directory (default: runs/<scenario>-seed<N>)")
    run.add_argument(
        "--meshcat", action="store_true", help="show the run live in Meshcat, at real time"
    )
    _add_set_option(run)
    run.set_defaults(command=_run)

    sweep = commands.add_parser("sweep", help="run many seeds (and parameter grids) of a scenario")
    sweep.add_argument("scenario", help="a scenario file, or the name of a bundled scenario")
    sweep.add_argument("--seeds", default="0:10", help="START:STOP, N or a comma list (0:10)")
    _add_set_option(sweep)
    sweep.add_argument(
        "--workers", type=_positive_int, default=os.cpu_count(), help="local worker processes"
    )
    sweep.add_argument("--dask", metavar="ADDRESS", help="run on this Dask scheduler instead")
    sweep.add_argument("--out", type=Path, help="sweep directory (default: sweeps/<scenario>)")
    sweep.set_defaults(command=_sweep)

    diagram = commands.add_parser("diagram", help="export the scenario's system diagram")
    diagram.add_argument("scenario")
    diagram.add_argument("-o", "--output", type=Path, required=True, help=".svg, .png or .dot")
    diagram.set_defaults(command=_diagram)

    validate = commands.add_parser("validate", help="check a scenario without simulating")
    validate.add_argument("scenario")
    validate.set_defaults(command=_validate)

    listing = commands.add_parser("list", help="bundled scenarios and robot variants")
    listing.set_defaults(command=_list)
    return parser


def _add_set_option(parser) -> None:
    parser.add_argument(
        "--set",
        action="append",
        default=[],
        metavar="PATH=VALUE[,VALUE...]",
        help="change a scenario field, e.g. duration=5 or safety.v_h=1.6,2.0 (a sweep grid)",
    )


def _positive_int(text: str) -> int:
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"'{text}' is not a whole number") from None
    if value < 1:
        raise argparse.ArgumentTypeError(f"must be at least 1, got {text}")
    return value


def _positive_float(text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"'{text}' is not a number") from None
    if not value > 0:
        raise argparse.ArgumentTypeError(f"must be positive, got {text}")
    return value


def _load(name_or_path: str):
    from hrc_drake.scenario import load_scenario

    return load_scenario(name_or_path)


def _run(args) -> int:
    from pydrake.geometry import Meshcat

    from hrc_drake.runner import run
    from hrc_drake.scenario import Scenario
    from hrc_drake.sweep.overrides import apply, parse_sets

    axes = parse_sets(args.set, Scenario)
    if any(len(values) > 1 for _, values in axes):
        raise InputError("run: --set takes one value per field (use sweep for grids)")
    scenario = apply(_load(args.scenario), tuple((path, values[0]) for path, values in axes))
    seed = scenario.seed if args.seed is None else args.seed
    out = args.out or Path("runs") / f"{scenario.name}-seed{seed}"
    meshcat = Meshcat() if args.meshcat else None
    report = run(
        scenario,
        seed=seed,
        duration=args.duration,
        out_dir=out,
        meshcat=meshcat,
        progress=True,
        realtime_rate=1.0 if args.meshcat else 0.0,
    )
    print(
        f"{scenario.name}: simulated {report.metrics['duration']:.1f} s in "
        f"{report.wall_time:.1f} s (real-time factor {report.real_time_factor:.1f})"
    )
    _print_files(report.files)
    return 0


def _sweep(args) -> int:
    from hrc_drake.scenario import resolve_scenario_path
    from hrc_drake.sweep import parse_seeds, plan, sweep

    scenario = _load(args.scenario)
    specs = plan(resolve_scenario_path(args.scenario), parse_seeds(args.seeds), args.set)
    out = args.out or Path("sweeps") / scenario.name
    result = sweep(specs, out, args.workers, args.dask, progress=True, scenario_name=scenario.name)
    print(
        f"{scenario.name}: {len(result.rows)} runs ({result.skipped} already done, "
        f"{len(result.failed)} failed)"
    )
    _print_files(result.files)
    return 0


def _print_files(files: dict[str, Path]) -> None:
    width = max(map(len, files), default=0)
    for name, path in files.items():
        print(f"  {name:{width}s} {path}")


def _diagram(args) -> int:
    from hrc_drake.builder import build_diagram
    from hrc_drake.diagram_export import FORMATS, write_diagram

    if args.output.suffix.lstrip(".").lower() not in FORMATS:
        raise InputError(f"{args.output}: use a .svg, .png or .dot file name")
    write_diagram(build_diagram(_load(args.scenario)), args.output)
    print(args.output)
    return 0


def _validate(args) -> int:
    from hrc_drake.builder import build_diagram

    scenario = _load(args.scenario)
    build_diagram(scenario)
    print(f"{args.scenario}: ok ({scenario.name})")
    return 0


def _list(args) -> int:
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


if __name__ == "__main__":
    sys.exit(main())
