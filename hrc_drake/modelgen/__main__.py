"""`python -m hrc_drake.modelgen [KIND ...]`: regenerate the generated files in models/."""

import argparse
from collections.abc import Callable, Sequence
from pathlib import Path

from hrc_drake.drake_logging import quiet_drake_logging
from hrc_drake.modelgen.clips import write_clips
from hrc_drake.modelgen.models import write_models
from hrc_drake.modelgen.stopping import write_stopping
from hrc_drake.paths import resource_dir

KINDS: dict[str, tuple[Callable[[Path], list[Path]], str]] = {
    "models": (write_models, "robot, tool, cell and human SDFormat files (instant)"),
    "clips": (write_clips, "the person's built-in motion clips (seconds)"),
    "stopping": (write_stopping, "the robots' stopping data, measured on RobotMotion (minutes)"),
}
"""Kind -> (writer of its files into a models folder, what it writes)."""


def _parser() -> argparse.ArgumentParser:
    kinds = "\n".join(f"  {kind:9} {what}" for kind, (_, what) in KINDS.items())
    parser = argparse.ArgumentParser(
        prog="python -m hrc_drake.modelgen",
        description="Regenerate the generated files in models/ (every kind unless named).\n"
        "Unless a generator or what it measures changed, they come out byte for byte as\n"
        "committed.",
        epilog=f"kinds:\n{kinds}",
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    parser.add_argument("kinds", nargs="*", metavar="KIND", help="models, clips or stopping")
    parser.add_argument(
        "--models-dir",
        type=Path,
        metavar="DIR",
        help="write into this folder instead of the shipped models (to compare with them)",
    )
    return parser


def main(argv: Sequence[str] | None = None) -> None:
    parser = _parser()
    args = parser.parse_args(argv)
    unknown = [kind for kind in args.kinds if kind not in KINDS]
    if unknown:
        parser.error(f"unknown kind {', '.join(unknown)} (choose from {', '.join(KINDS)})")
    quiet_drake_logging()
    models_dir = args.models_dir or resource_dir("models")
    for kind in args.kinds or KINDS:
        write, _ = KINDS[kind]
        for path in write(models_dir):
            print(f"wrote {path}", flush=True)


if __name__ == "__main__":
    main()
