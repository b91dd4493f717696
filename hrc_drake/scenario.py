"""Scenario files: one YAML file per scenario, read into dataclasses with `yaml_load_typed`.

This follows Drake's `examples/hardware_sim`: the schema is plain dataclasses (plus Drake's
own `Transform` and `ModelDirective` schemas), and the builder turns a loaded Scenario into
one Diagram. Every problem in a file is reported as one line naming file, line and field.
"""

import dataclasses
import difflib
import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from pydrake.common.schema import Transform
from pydrake.common.yaml import yaml_load_typed
from pydrake.math import RigidTransform
from pydrake.multibody.parsing import ModelDirective, PackageMap

from hrc_drake.areas import Area
from hrc_drake.human.clip_files import read_clip_file
from hrc_drake.human.skeleton import HEIGHT_RANGE
from hrc_drake.iisy import TOOL_BODY, VARIANTS
from hrc_drake.motion.options import MotionOptions
from hrc_drake.paths import add_model_package, resource_dir
from hrc_drake.safety.config import SafetyConfig
from hrc_drake.workpieces.config import WorkpiecesConfig, problems
from hrc_drake.yaml_check import (
    InputError,
    check_node,
    compose,
    field_path,
    located_error,
    node_at,
)

REQUIRED = {"required": True}
NO_TOOL = "none"
TOOLS = (TOOL_BODY, NO_TOOL)


@dataclass
class RobotConfig:
    """The cobot: which iisy, where its base stands, which tool, which configurations."""

    variant: str = field(default="", metadata=REQUIRED)
    base_pose: Transform = field(default_factory=Transform)
    tool: str = "vacuum_gripper"
    initial_configuration: str = "home"
    configurations_deg: dict[str, list[float]] = field(default_factory=dict)
    motion: MotionOptions = field(default_factory=MotionOptions)


@dataclass
class VisualizationOptions:
    """Meshcat settings; `record` keeps an animation for the standalone replay.html."""

    publish_period: float = 1.0 / 32.0
    record: bool = True
    show_collision: bool = False
    camera_position: list[float] = field(default_factory=lambda: [1.7, -1.4, 1.5])
    camera_target: list[float] = field(default_factory=lambda: [0.0, 0.35, 0.9])


@dataclass
class AgentTree:
    """The behavior tree an agent runs: a BehaviorTree.CPP v4 XML file (relative to the
    scenario file), which of its trees (default: its main tree), and the tick period."""

    file: str = field(default="", metadata=REQUIRED)
    tree_id: str = ""
    period: float = 0.05


AGENTS = ("robot", "human")


@dataclass
class HumanConfig:
    """The person: body height and mass (segments scale with them) and where they start
    (x, y in metres, facing yaw in degrees)."""

    height: float = 1.75
    mass: float = 75.0
    start: list[float] = field(default_factory=lambda: [0.0, -2.0, 90.0])
    clips: list[str] = field(default_factory=list)
    """The scenario's own motion clips: .bvh or .json files (relative to the scenario file),
    which trees play by their file names."""


@dataclass
class Scenario:
    name: str = field(default="", metadata=REQUIRED)
    description: str = ""
    seed: int = 0
    duration: float = 10.0
    time_step: float = 1e-3
    robot: RobotConfig = field(default_factory=RobotConfig, metadata=REQUIRED)
    cell: list[ModelDirective] = field(default_factory=list)
    areas: dict[str, list[list[float]]] = field(default_factory=dict)
    locations: dict[str, Transform] = field(default_factory=dict)
    visualization: VisualizationOptions = field(default_factory=VisualizationOptions)
    human: HumanConfig | None = None
    workpieces: WorkpiecesConfig = field(default_factory=WorkpiecesConfig)
    safety: SafetyConfig = field(default_factory=SafetyConfig)
    trees: dict[str, AgentTree] = field(default_factory=dict)
    parameters: dict[str, str] = field(default_factory=dict)
    """Root blackboard entries of every tree (converted to each port's type when read)."""

    def area(self, name: str) -> Area:
        return Area.from_polygon(self.areas[name])

    def location(self, name: str) -> RigidTransform:
        return self.locations[name].GetDeterministicValue()

    def configuration(self, name: str) -> np.ndarray:
        """A named joint configuration in radians; `home` defaults to the variant's."""
        if name in self.robot.configurations_deg:
            return np.radians(self.robot.configurations_deg[name])
        return np.array(VARIANTS[self.robot.variant].home)

    def with_overrides(self, **changes) -> "Scenario":
        """A copy with some top-level fields replaced (e.g. seed, duration)."""
        given = {k: v for k, v in changes.items() if v is not None}
        return dataclasses.replace(self, **given)


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
    close = difflib.get_close_matches(name_or_path, known, n=1)
    hint = f"did you mean '{close[0]}'? " if close else ""
    raise InputError(
        f"{name_or_path}: no such scenario file or bundled scenario ({hint}bundled: "
        f"{', '.join(known)})"
    )


def load_scenario(name_or_path: str | Path) -> Scenario:
    """Reads and checks a scenario; raises InputError with file, line and field."""
    path = resolve_scenario_path(str(name_or_path))
    text = path.read_text()
    root = compose(path, text)
    if root is None:
        raise InputError(f"{path}: the file is empty")
    check_node(path, root, Scenario)
    try:
        scenario = yaml_load_typed(schema=Scenario, data=text)
    except Exception as e:  # Drake's reader; our check above catches the common cases first.
        raise InputError(f"{path}: {e}") from None
    _check_meaning(path, root, scenario)
    return scenario


def _check_meaning(path: Path, root, scenario: Scenario) -> None:
    """Checks what the schema cannot: known names, sane numbers, files that exist."""

    def fail(field_names: tuple, message: str):
        raise located_error(path, node_at(root, field_names), field_path(field_names), message)

    if not scenario.duration > 0 or not math.isfinite(scenario.duration):
        fail(("duration",), f"must be a positive number of seconds, got {scenario.duration}")
    if not scenario.time_step > 0:
        fail(("time_step",), f"must be positive, got {scenario.time_step}")
    _check_robot(scenario.robot, lambda names, msg: fail(("robot", *names), msg))
    for name, points in scenario.areas.items():
        try:
            Area.from_polygon(points)
        except ValueError as e:
            fail(("areas", name), f"not a valid polygon: {e}")
    _check_model_files(scenario.cell, lambda names, msg: fail(("cell", *names), msg))
    for names, message in problems(scenario.workpieces):
        fail(("workpieces", *names), message)
    if scenario.human is not None:
        _check_human(scenario.human, path.parent, lambda names, msg: fail(("human", *names), msg))
    _resolve_tree_files(
        path.parent, scenario.trees, lambda names, msg: fail(("trees", *names), msg)
    )


def _resolve_tree_files(directory: Path, trees: dict[str, AgentTree], fail) -> None:
    """Tree files are named relative to the scenario file; keep them as absolute paths so
    the loaded scenario works from any directory (and in sweep workers)."""
    for agent, tree in trees.items():
        if agent not in AGENTS:
            fail((agent,), _unknown("agent", agent, AGENTS))
        file = (directory / tree.file).resolve()
        if not file.is_file():
            fail((agent, "file"), f"tree file '{tree.file}' not found (looked at {file})")
        tree.file = str(file)
        if not tree.period > 0:
            fail((agent, "period"), f"must be positive, got {tree.period}")


def _check_robot(robot: RobotConfig, fail) -> None:
    if robot.variant not in VARIANTS:
        fail(("variant",), _unknown("robot variant", robot.variant, VARIANTS))
    if robot.tool not in TOOLS:
        fail(("tool",), _unknown("tool", robot.tool, TOOLS))
    joints = len(VARIANTS[robot.variant].joint_names)
    for name, q in robot.configurations_deg.items():
        if len(q) != joints:
            fail(("configurations_deg", name), f"needs {joints} joint angles, got {len(q)}")
    positive = ("update_period", "ik_attempts", "search_nodes", "tool_speed_limit", "person_radius")
    for name in positive:
        if not getattr(robot.motion, name) > 0:
            fail(("motion", name), f"must be positive, got {getattr(robot.motion, name)}")
    known = {"home", *robot.configurations_deg}
    if robot.initial_configuration not in known:
        fail(
            ("initial_configuration",),
            _unknown("configuration", robot.initial_configuration, known),
        )


def _check_human(human: HumanConfig, directory: Path, fail) -> None:
    low, high = HEIGHT_RANGE
    if not low <= human.height <= high:
        fail(("height",), f"must lie within {low}..{high} m, got {human.height}")
    if not human.mass > 0:
        fail(("mass",), f"must be positive, got {human.mass}")
    if len(human.start) != 3:
        fail(("start",), "needs [x, y, yaw_deg]")
    for i, clip in enumerate(human.clips):
        file = (directory / clip).resolve()
        try:
            read_clip_file(file)
        except InputError as error:
            fail(("clips", i), str(error))
        human.clips[i] = str(file)


def _check_model_files(directives: list[ModelDirective], fail) -> None:
    package_map = PackageMap()
    add_model_package(package_map)
    for i, directive in enumerate(directives):
        if directive.add_model is None:
            continue
        url = directive.add_model.file
        try:
            exists = Path(package_map.ResolveUrl(url)).is_file()
        except Exception:
            exists = False
        if not exists:
            fail((i, "add_model", "file"), f"model file '{url}' not found")


def _unknown(what: str, name: str, known) -> str:
    close = difflib.get_close_matches(name, list(known), n=1)
    hint = f" (did you mean '{close[0]}'?)" if close else ""
    return f"unknown {what} '{name}'{hint}; known: {', '.join(sorted(known))}"
