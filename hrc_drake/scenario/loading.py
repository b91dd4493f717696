"""Reading a scenario: a file or a bundled scenario's name, checked as YAML against the
schema (file, line and field for every problem), read with `yaml_load_typed`, overridden
(hrc_drake.scenario.overrides) and then checked as a whole (hrc_drake.scenario.checks)."""

from dataclasses import dataclass
from pathlib import Path

from pydrake.common.yaml import yaml_load_typed

from hrc_drake.paths import resource_dir
from hrc_drake.scenario.checks import scenario_problems
from hrc_drake.scenario.overrides import Overrides, overridden
from hrc_drake.scenario.schema import Scenario
from hrc_drake.yaml_check import (
    InputError,
    check_node,
    compose,
    did_you_mean,
    field_path,
    first_line,
    located_error,
    node_at,
    read_text,
)


def bundled_scenarios() -> list[str]:
    return sorted(p.stem for p in resource_dir("scenarios").glob("*.yaml"))


def resolve_scenario_path(name_or_path: str) -> Path:
    """A path to a scenario file, or the name of a bundled one."""
    path = Path(name_or_path)
    if path.is_file():
        return path
    bundled = resource_dir("scenarios") / f"{name_or_path}.yaml"
    if bundled.is_file():
        return bundled
    known = bundled_scenarios()
    raise InputError(
        f"{name_or_path}: no such scenario file or bundled scenario"
        f"{did_you_mean(name_or_path, known)}; bundled: {', '.join(known)}"
    )


def load_scenario(
    name_or_path: str | Path,
    overrides: Overrides = (),
    options: dict[str, str] | None = None,
    sensors: bool = True,
) -> Scenario:
    """Reads and checks a scenario; raises InputError with file, line and field.

    `overrides` ((dotted field, value), ...) are layered over the file before the checks,
    so a value from the command line is checked exactly like one from the file; `options`
    names how the user gave a field (e.g. {"seed": "--seed -1"}), default `--set
    field=value`. `sensors=False` loads a scenario whose safety sensors cannot work, so
    that validate lists all their findings (hrc_drake.scenario.findings) instead of the
    first.
    """
    path = resolve_scenario_path(str(name_or_path))
    text = read_text(path, "scenario file")
    root = compose(path, text)
    if root is None:
        raise InputError(f"{path}: the file is empty")
    check_node(path, root, Scenario)
    try:
        scenario = yaml_load_typed(schema=Scenario, data=text)
    except Exception as e:  # Drake's reader; check_node catches the common cases first.
        raise located_error(path, root, "<document>", first_line(e)) from None
    scenario = overridden(scenario, overrides)
    given = {name: f"--set {name}={value}" for name, value in overrides} | (options or {})
    where = _Where(path, root, given)
    for names, message in scenario_problems(scenario, path.parent, sensors):
        raise where.error(names, message)
    return scenario


@dataclass
class _Where:
    """Where a field was given: the file's line, or the command-line option that set it."""

    path: Path
    root: object
    options: dict[str, str]

    def error(self, names: tuple | None, message: str) -> InputError:
        if names is None:  # the message names its own place (e.g. a tree file's line)
            return InputError(message)
        dotted = field_path(names)
        for name, option in self.options.items():
            if dotted == name or dotted.startswith(f"{name}."):
                return InputError(f"{option}: {message}")
        return located_error(self.path, node_at(self.root, names), dotted, message)
