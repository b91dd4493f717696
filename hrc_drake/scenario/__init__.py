"""Scenario files: one YAML file per scenario, read into dataclasses with `yaml_load_typed`.

This follows Drake's `examples/hardware_sim`: the schema is plain dataclasses (plus Drake's
own config structs), and the builder turns a loaded Scenario into one Diagram. Every
problem in a file is reported as one line naming file, line and field.

- `schema`: the Scenario and its sections;
- `loading`: `load_scenario(path, overrides)`, bundled scenarios;
- `overrides`: dotted fields set from the command line, sweeps, searches and notebooks;
- `checks`: what the schema cannot say (FIELD_RULES and the sections' own checks);
- `falsify`: the `falsify:` section, the space `hrc-drake falsify` searches.
"""

from hrc_drake.scenario.checks import FIELD_RULES, MAX_SEED
from hrc_drake.scenario.loading import bundled_scenarios, load_scenario, resolve_scenario_path
from hrc_drake.scenario.overrides import Overrides, overridden
from hrc_drake.scenario.schema import HumanConfig, RobotConfig, Scenario, VisualizationOptions

__all__ = [
    "FIELD_RULES",
    "MAX_SEED",
    "HumanConfig",
    "Overrides",
    "RobotConfig",
    "Scenario",
    "VisualizationOptions",
    "bundled_scenarios",
    "load_scenario",
    "overridden",
    "resolve_scenario_path",
]
