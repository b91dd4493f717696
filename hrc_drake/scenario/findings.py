"""Everything `hrc-drake validate` can know about a loaded scenario before anything is
simulated, beyond what loading it refuses (hrc_drake.scenario.checks): magnitudes that
cannot be meant (hrc_drake.scenario.magnitudes), objects that start inside the cell or each
other and places the person cannot stand (hrc_drake.scenario.cell_findings), every mistake
of the safety sensors (hrc_drake.safety.sensors_checks, which validate loads the scenario
without), and what the
trees will do with the values known before a run: robot targets out of reach, animations
the person lacks, places to stand, places and reaches too far from where the person
stands, configurations, object types and areas that do not exist
(hrc_drake.scenario.tree_findings).

Each Finding (hrc_drake.scenario.located) names the file, the line and the field (or the
tree's node and port), says what was probably meant where it can, and carries the point in
the cell it concerns, if any, so a view of the cell can mark it.
"""

from collections.abc import Iterable
from pathlib import Path

from hrc_drake.scenario.cell_findings import CellScene, cell_findings
from hrc_drake.scenario.checks import safety_sensor_problems
from hrc_drake.scenario.located import Finding, Locator
from hrc_drake.scenario.magnitudes import magnitude_findings
from hrc_drake.scenario.schema import Scenario
from hrc_drake.scenario.tree_findings import tree_findings

__all__ = ["Finding", "findings"]


def findings(scenario: Scenario, path: Path) -> list[Finding]:
    """Every finding of a scenario that loaded (`load_scenario(path)`), in the order of
    the checks: magnitudes, the cell, the safety sensors, then the trees (the robot's reach
    last: it takes the longest)."""
    at = Locator(path)
    found = list(magnitude_findings(scenario, at))
    implausible = {f.where for f in found}
    scene = CellScene(scenario, skip_types=_types_named(implausible))
    found += cell_findings(scenario, scene, at, skip_locations=_named(implausible, "locations"))
    found += [at.field(names, message) for names, message in safety_sensor_problems(scenario)]
    configurations = _named(implausible, "robot.configurations_deg")
    placed = all(f.where != "robot.base_pose" for f in found)
    found += tree_findings(scenario, scene, at, configurations, robot_placed=placed)
    return found


def _types_named(fields: Iterable[str]) -> set[str]:
    """The object types that `workpieces.types.<name>...` fields name."""
    return _named(fields, "workpieces.types")


def _named(fields: Iterable[str], section: str) -> set[str]:
    """The names that `<section>.<name>...` fields name (what a finding already covers)."""
    depth = section.count(".") + 1
    return {f.split(".")[depth] for f in fields if f.startswith(f"{section}.")}
