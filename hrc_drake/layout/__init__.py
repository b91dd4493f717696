"""`hrc-drake layout`: the cell from above as the robot and the person can use it, without
simulating (hrc_drake.layout.cell gathers it, hrc_drake.layout.view draws it, the robot's
reach comes from hrc_drake.layout.reach_map). Each run's report.html shows it too."""

import dataclasses
from pathlib import Path

from pydrake.common.yaml import yaml_dump_typed

from hrc_drake.layout.cell import CellLayout, cell_layout
from hrc_drake.layout.view import draw_layout, write_layout

__all__ = ["CellLayout", "cell_layout", "draw_layout", "layout_of", "write_layout"]

_layouts: dict[tuple, CellLayout] = {}
"""The layouts this process gathered, by what they were gathered from: the runs of a sweep
share their scenario's (its duration does not change the cell)."""


def layout_of(scenario, path: Path | None) -> CellLayout:
    """`cell_layout(scenario, path)`, gathered once per scenario, file and trees."""
    key = (
        yaml_dump_typed(dataclasses.replace(scenario, duration=0.0)),
        str(path),
        *(Path(tree.file).read_text() for tree in scenario.trees.values()),
    )
    if key not in _layouts:
        _layouts[key] = cell_layout(scenario, path)
    return _layouts[key]
