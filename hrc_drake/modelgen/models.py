"""The generated model files: robot, tool, cell objects and the default person (SDFormat).

`python -m hrc_drake.modelgen models` rewrites them all."""

from collections.abc import Callable
from functools import partial
from pathlib import Path

from hrc_drake.human.anthropometry import DEFAULT_HEIGHT, DEFAULT_MASS
from hrc_drake.human.sdf import human_sdf
from hrc_drake.iisy import VARIANTS
from hrc_drake.modelgen.cell import CELL_OBJECTS, cell_sdf
from hrc_drake.modelgen.robot import robot_sdf
from hrc_drake.modelgen.tool import vacuum_gripper_sdf


def generators() -> dict[str, Callable[[], str]]:
    """Model file path (relative to models/) -> function returning its text."""
    files: dict[str, Callable[[], str]] = {"tools/vacuum_gripper.sdf": vacuum_gripper_sdf}
    for variant in VARIANTS.values():
        files[f"iisy/{variant.name}.sdf"] = partial(robot_sdf, variant)
    for name in CELL_OBJECTS:
        files[f"cell/{name}.sdf"] = partial(cell_sdf, name)
    files["human/human.sdf"] = partial(human_sdf, DEFAULT_HEIGHT, DEFAULT_MASS)
    return files


def write_models(models_dir: Path) -> list[Path]:
    """Write every generated model file into `models_dir`; returns the paths written."""
    written = []
    for relative, generate in generators().items():
        path = models_dir / relative
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(generate())
        written.append(path)
    return written
