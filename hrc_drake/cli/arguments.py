"""The arguments the commands share: `--set`, where runs go, numbers checked as they are
parsed, output files checked before any work, and one-value `--set`/`--seed`/`--duration`
as scenario overrides."""

import argparse
import os
from pathlib import Path

from hrc_drake.yaml_check import InputError

PROG = "hrc-drake"
EXIT_USAGE = 2
"""The exit status of a mistake in what the user gave (arguments, scenario, trees)."""
MAX_WORKERS = 4 * (os.cpu_count() or 1)
"""More local workers than this only share the cores and exhaust the memory."""


def add_set_option(parser) -> None:
    parser.add_argument(
        "--set",
        action="append",
        default=[],
        metavar="PATH=VALUE[,VALUE...]",
        help="change a scenario field, e.g. duration=5 or safety.v_h=1.6,2.0 (a sweep grid)",
    )


def add_execution_options(parser, what: str, directory: str) -> None:
    """Where the runs of a sweep or a search go, and where its directory is."""
    parser.add_argument(
        "--workers",
        type=worker_count,
        default=os.cpu_count(),
        help=f"local worker processes (at most {MAX_WORKERS}: each holds a whole simulation)",
    )
    parser.add_argument("--dask", metavar="ADDRESS", help="run on this Dask scheduler instead")
    parser.add_argument(
        "--out",
        type=Path,
        help=f"{what} directory, new or an earlier {what}'s ({directory}/<scenario>)",
    )


def _parsed(text: str, convert, noun: str):
    """`text` as `convert` reads it, or the one-line reason it is not `noun`."""
    try:
        return convert(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"'{text}' is not {noun}") from None


def positive_int(text: str) -> int:
    value = _parsed(text, int, "a whole number")
    if value < 1:
        raise argparse.ArgumentTypeError(f"must be at least 1, got {text}")
    return value


def worker_count(text: str) -> int:
    value = _parsed(text, int, "a whole number")
    if not 1 <= value <= MAX_WORKERS:
        raise argparse.ArgumentTypeError(f"must lie within 1..{MAX_WORKERS}, got {text}")
    return value


def port_number(text: str) -> int:
    value = _parsed(text, int, "a port number")
    if not 1 <= value <= 65534:
        raise argparse.ArgumentTypeError(f"port {text} is out of range (1 to 65534: it uses two)")
    return value


def positive_float(text: str) -> float:
    value = _parsed(text, float, "a number")
    if not value > 0:
        raise argparse.ArgumentTypeError(f"must be positive, got {text}")
    return value


def check_output(path: Path, option: str, suffixes: tuple[str, ...]) -> None:
    """An output file the command can write, checked before any work is done."""
    if suffixes and path.suffix.lower() not in suffixes:
        raise InputError(f"{option} {path}: use a {', '.join(suffixes)} file name")
    if path.is_dir():
        raise InputError(f"{option} {path}: is a directory; give a file name")
    if not path.parent.is_dir():
        raise InputError(f"{option} {path}: directory '{path.parent}' does not exist")
    if not os.access(path.parent, os.W_OK) or (path.exists() and not os.access(path, os.W_OK)):
        raise InputError(f"{option} {path}: cannot write there: permission denied")


def single_sets(args, command: str, grids: str) -> tuple[tuple, dict]:
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
