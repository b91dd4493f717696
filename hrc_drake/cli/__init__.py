"""`hrc-drake`: run scenarios, export their diagrams, validate them, list what is bundled.

User errors (bad arguments, bad scenario files) print one line and exit with status 2;
nothing the run already wrote is removed. The commands live in `simulate` (run, sweep,
falsify), `inspection` (diagram, validate, tree, list, clip) and `layout`; `arguments`
holds what they share.
"""

import argparse
import sys

from hrc_drake.cli import inspection, layout, simulate
from hrc_drake.cli.arguments import EXIT_USAGE, PROG
from hrc_drake.drake_logging import quiet_drake_logging
from hrc_drake.yaml_check import InputError


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
        print(f"{PROG}: interrupted", file=sys.stderr)
        return 130


def _make_parser() -> argparse.ArgumentParser:
    parser = _Parser(prog=PROG, description=__doc__.splitlines()[0])
    commands = parser.add_subparsers(required=True, metavar="COMMAND", parser_class=_Parser)
    simulate.add_commands(commands)
    inspection.add_commands(commands, _Parser)
    layout.add_commands(commands)
    return parser
