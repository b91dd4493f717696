"""Generators of the model files in models/: `python -m hrc_drake.modelgen` rewrites them all."""

from collections.abc import Callable
from functools import partial
from pathlib import Path

from hrc_drake.iisy import VARIANTS
from hrc_drake.modelgen.cell import CELL_OBJECTS, cell_sdf
from hrc_drake.modelgen.robot import robot_sdf
from hrc_drake.modelgen.tool import vacuum_gripper_sdf
from hrc_drake.paths import resource_dir


def generators() -> dict[str, Callable[[], str]]:
    """Model file path (relative to models/) -> function returning its text."""
    files: dict[str, Callable[[], str]] = {"tools/vacuum_gripper.sdf": vacuum_gripper_sdf}
    for variant in VARIANTS.values():
        files[f"iisy/{variant.name}.sdf"] = partial(robot_sdf, variant)
    for name in CELL_OBJECTS:
        files[f"cell/{name}.sdf"] = partial(cell_sdf, name)
    return files


def write_all(models_dir: Path | None = None) -> list[Path]:
    """Write every generated model file; returns the paths written."""
    root = models_dir or resource_dir("models")
    written = []
    for relative, generate in generators().items():
        path = root / relative
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(generate())
        written.append(path)
    return written
