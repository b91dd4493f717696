"""`python -m hrc_drake.modelgen` reproduces the shipped files byte for byte.

The quick kinds (models, clips) are regenerated into a temporary folder and compared with
models/; the stopping data take minutes to measure, so tests/motion/test_stopping_data.py
compares one fresh measurement with them instead."""

import pytest

from hrc_drake.modelgen.__main__ import main
from hrc_drake.paths import resource_dir


def _regenerate(kind: str, folder) -> list:
    main([kind, "--models-dir", str(folder)])
    return sorted(path.relative_to(folder) for path in folder.rglob("*") if path.is_file())


@pytest.mark.parametrize("kind", ["models", "clips"])
def test_regenerating_reproduces_the_shipped_files(kind, tmp_path):
    written = _regenerate(kind, tmp_path)
    shipped = resource_dir("models")
    differ = [
        str(path)
        for path in written
        if not (shipped / path).is_file()
        or (tmp_path / path).read_bytes() != (shipped / path).read_bytes()
    ]
    assert written
    assert not differ, f"run `python -m hrc_drake.modelgen {kind}`: {differ} changed"


def test_every_shipped_clip_is_generated(tmp_path):
    """No stale clip: the person loads every file in the animations folder."""
    written = _regenerate("clips", tmp_path)
    folder = resource_dir("models") / "human" / "animations"
    shipped = sorted(path.relative_to(folder.parents[1]) for path in folder.glob("*.json"))
    assert written == shipped
