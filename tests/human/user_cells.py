"""Cut-down user cells under tests/human/cells, copied where a test runs them."""

from pathlib import Path

CELLS = Path(__file__).resolve().parent / "cells"


def copied(cell: str, to: Path) -> Path:
    """The cell's files in `to`, its `{dir}` there (its own rack model's URL)."""
    for source in (CELLS / cell).iterdir():
        (to / source.name).write_text(source.read_text().replace("{dir}", str(to)))
    return to / "cell.yaml"
