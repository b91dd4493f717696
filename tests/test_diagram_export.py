"""A scenario's diagram.svg is the same bytes whoever draws it: another process, or this one
after building other systems (Drake numbers systems by a process-wide counter and lists
connections in the order of their ports' memory addresses)."""

import subprocess
import sys

from hrc_drake.builder import build_diagram
from hrc_drake.diagram_export import write_diagram
from hrc_drake.scenario import load_scenario

SCENARIO = "coexistence"


def test_diagram_svg_is_the_same_bytes_in_every_process(tmp_path):
    drawn = []
    for k in range(2):  # the second build's systems have other ids
        drawn.append(write_diagram(build_diagram(load_scenario(SCENARIO)), tmp_path / f"{k}.svg"))
    other = tmp_path / "other.svg"
    subprocess.run(
        [sys.executable, "-m", "hrc_drake.cli", "diagram", SCENARIO, "-o", str(other)],
        check=True,
        capture_output=True,
    )
    first = drawn[0].read_bytes()
    assert "<svg" in first.decode()
    assert drawn[1].read_bytes() == first
    assert other.read_bytes() == first
