"""Everything a scenario's schema cannot say, checked after reading (and after overrides,
so a value from the command line meets the same checks as one from the file): the value
ranges of FIELD_RULES, finite numbers, the robot and its configurations, places, the cell
(parsed by Drake once per robot and cell), the workpieces, the person's clips, the trees
(hrc_drake.agent_trees) and the falsify section. Each problem is field names and a message,
located in the file by hrc_drake.scenario.loading.
"""

import dataclasses
import itertools
import math
import re
from collections.abc import Callable, Iterable, Iterator
from functools import partial
from pathlib import Path

import numpy as np
from pydrake.common.schema import Rotation, Transform
from pydrake.multibody.parsing import ModelDirective, PackageMap
from pydrake.multibody.plant import AddMultibodyPlant, MultibodyPlant, MultibodyPlantConfig
from pydrake.systems.analysis import GetIntegrationSchemes
from pydrake.systems.framework import DiagramBuilder

from hrc_drake.agent_trees import AgentTree, tree_errors
from hrc_drake.areas import Area
from hrc_drake.directives_check import directive_problems
from hrc_drake.human.anthropometry import HEIGHT_RANGE
from hrc_drake.human.clip_files import read_clip_file
from hrc_drake.human.survey import PERCENTILE_RANGE, SEXES
from hrc_drake.iisy import VARIANTS
from hrc_drake.paths import add_model_package
from hrc_drake.safety.config import V_H_RULES
from hrc_drake.safety.sensors_checks import sensor_problems
from hrc_drake.scenario.falsify import search_problems
from hrc_drake.scenario.overrides import field_kind, field_type, overridden
from hrc_drake.scenario.schema import RobotConfig, Scenario
from hrc_drake.station import TOOLS, StationSpec, add_station_models, model_parser
from hrc_drake.wiring import AGENTS, STATION_MODELS
from hrc_drake.workpieces.config import problems
from hrc_drake.workpieces.messages import COUPLINGS
from hrc_drake.yaml_check import InputError, first_line, schema_fields, unknown

Problem = tuple[tuple | None, str]
"""(field names from the scenario's top, message): one thing wrong with a scenario; no
names when the message says where it is itself."""
Rule = Callable[[object], str]
"""A value's problem, or "" when the value is fine."""


def positive(value) -> str:
    return "" if value is None or value > 0 else f"must be positive, got {value}"


def not_negative(value) -> str:
    return "" if value is None or value >= 0 else f"must not be negative, got {value}"


def within(low: float, high: float, unit: str = "", why: str = "") -> Rule:
    def rule(value) -> str:
        if low <= value <= high:
            return ""
        reason = f" ({why})" if why else ""
        return f"must lie within {low}..{high}{unit}, got {value}{reason}"

    return rule


def in_metres(rule: Rule) -> Rule:
    """`rule`, saying so when the value looks like centimetres (a person 175 tall)."""

    def checked(value) -> str:
        problem = rule(value)
        if problem and 100 <= value <= 250:
            return f"{problem} (lengths are in metres: {value / 100:g} for centimetres?)"
        return problem

    return checked


def one_of(known: Iterable[str]) -> Rule:
    return lambda value: "" if value in known else unknown("value", value, known)


MAX_SEED = 2**63 - 1
FIELD_RULES: dict[str, Rule] = {
    "seed": within(0, MAX_SEED),
    "duration": positive,
    "plant.time_step": within(1e-5, 0.01, " s", "the controller and the monitor run at 100 Hz"),
    "robot.motion.period": positive,
    "robot.motion.ik_attempts": positive,
    "robot.motion.search_nodes": positive,
    "robot.motion.clearance": not_negative,
    "robot.motion.linear_tolerance": positive,
    "robot.motion.tool_speed_limit": positive,
    "robot.motion.settle_tolerance": positive,
    "robot.motion.settle_timeout": positive,
    "robot.motion.gripper_timeout": positive,
    "robot.motion.person_radius": positive,
    "visualization.period": positive,
    "report.period": positive,
    "human.period": positive,
    "human.audit_every": positive,
    "simulator.max_step_size": positive,
    "simulator.accuracy": positive,
    "simulator.target_realtime_rate": not_negative,
    "simulator.integration_scheme": one_of(GetIntegrationSchemes()),
    "human.height": in_metres(within(*HEIGHT_RANGE, " m")),
    "human.mass": positive,
    "human.sex": one_of(SEXES),
    "human.percentile": within(*PERCENTILE_RANGE),
    "ergonomics.period": positive,
    "ergonomics.work_hours": within(0, 24, " h"),
    "ergonomics.coupling": one_of(COUPLINGS),
    "trees.*.period": positive,
    "safety.period": positive,
    "safety.v_h_rule": one_of(V_H_RULES),
    "safety.v_h": not_negative,
    "safety.v_h_near": not_negative,
    "safety.near_distance": not_negative,
    "safety.sensing_time": not_negative,
    "safety.robot_speed": positive,
    "safety.intrusion_distance": not_negative,
    "safety.sensor_uncertainty": not_negative,
    "safety.robot_uncertainty": not_negative,
    "safety.hysteresis": not_negative,
    "safety.min_scale": within(0, 1),
    "safety.moving_speed": positive,
    "safety.contact_area_cm2": positive,
    "safety.clamping_gap": not_negative,
    "falsify.batch": positive,
    "falsify.startup_trials": not_negative,
    "falsify.worst": not_negative,
    "falsify.parameters.*.step": positive,
}
"""The valid range of every field that has one, by dotted path (`*`: every key of a
mapping). A new field with a range gets its line here; YAML and `--set` both meet it."""


def scenario_problems(
    scenario: Scenario, directory: Path, sensors: bool = True
) -> Iterator[Problem]:
    """Everything the schema cannot say, first problem first: finite numbers, the field
    rules above, then the sections' own checks. Tree files are made absolute on the way.
    `sensors=False` leaves the safety sensors out (validate lists all of theirs at once,
    hrc_drake.scenario.findings)."""
    yield from _value_problems(scenario, ())
    for pattern, rule in FIELD_RULES.items():
        for names, value in _values_at(scenario, pattern.split(".")):
            if value is not None and (problem := rule(value)):
                yield names, problem
    yield from _plant_problems(scenario.plant)
    yield from _prefixed("robot", _robot_problems(scenario.robot))
    yield from _place_problems(scenario)
    cell = directive_problems(scenario.cell, _package_map(), RESERVED, directory)
    yield from _prefixed("cell", cell)
    yield from _station_problems(scenario)
    yield from _prefixed("workpieces", problems(scenario.workpieces))
    if sensors:
        yield from safety_sensor_problems(scenario)
    if scenario.human is not None and len(scenario.human.start) != 3:
        yield ("human", "start"), "needs [x, y, yaw_deg]"
    if scenario.human is not None:
        yield from _prefixed("human", _clip_problems(scenario.human.clips, directory))
    yield from _prefixed("trees", _resolve_tree_files(directory, scenario.trees))
    yield from tree_problems(scenario)
    if scenario.falsify is not None:
        yield from _falsify_problems(scenario, directory)


def safety_sensor_problems(scenario: Scenario) -> Iterator[Problem]:
    """The problems of `safety.sensors` in the scenario's cell, with the robot's command
    period."""
    latency = scenario.robot.motion.period
    yield from _prefixed("safety", sensor_problems(scenario.safety, scenario.station, latency))


def _falsify_problems(scenario: Scenario, directory: Path) -> Iterator[Problem]:
    """The search space's own mistakes, then every range end and choice checked like the
    bound field's value in the file (with the first problem it causes; the safety sensors'
    only where the parameter binds a field their checks read: the scenario's own are
    checked once, and they take seconds)."""
    kind_of = partial(field_kind, Scenario)
    found = list(_prefixed("falsify", search_problems(scenario.falsify, kind_of)))
    yield from found
    if found:
        return
    plain = dataclasses.replace(scenario, falsify=None)
    for name, parameter in scenario.falsify.parameters.items():
        kind = field_type(Scenario, parameter.bind)
        for names, sample in parameter.ends():
            where = ("falsify", "parameters", name)
            value = parameter.value(sample, kind)
            try:
                changed = overridden(plain, ((parameter.bind, value),))
            except InputError as error:  # the bound field is not in the scenario
                yield (*where, "bind"), str(error).removeprefix("--set ")
                break
            sensors = parameter.bind.split(".")[0] in _SENSOR_INPUTS
            checked = scenario_problems(changed, directory, sensors)
            for _, message in itertools.islice(checked, 1):
                yield (*where, *names), f"{parameter.bind}={value}: {message}"


_SENSOR_INPUTS = {"safety", "robot", "cell"}
"""The sections the safety sensors' checks read (`safety_sensor_problems`): a search that
binds a field of one may make the sensors fail where the scenario's own do not."""


def _prefixed(name: str, found: Iterable[Problem]) -> Iterator[Problem]:
    return ((None if names is None else (name, *names), message) for names, message in found)


def _values_at(obj, pattern: list[str], names: tuple = ()) -> Iterator[tuple[tuple, object]]:
    if not pattern:
        yield names, obj
        return
    head, rest = pattern[0], pattern[1:]
    if obj is None:
        return
    if head == "*":
        for key, value in obj.items():
            yield from _values_at(value, rest, (*names, key))
    else:
        yield from _values_at(getattr(obj, head), rest, (*names, head))


def _value_problems(value, names: tuple) -> Iterator[Problem]:
    """Every number in the scenario is finite (inf or nan would only fail deep in a run)
    and every pose fixed (Drake's random distributions are schema, not yet supported)."""
    if isinstance(value, float | np.floating):
        if not math.isfinite(value):
            yield names, f"must be a finite number, got {value}"
    elif isinstance(value, list | tuple | np.ndarray):
        for i, item in enumerate(value):
            yield from _value_problems(item, (*names, i))
    elif isinstance(value, dict):
        for key, item in value.items():
            yield from _value_problems(item, (*names, key))
    elif isinstance(value, Transform) and not value.IsDeterministic():
        yield names, "must be a fixed pose (random distributions are not supported here)"
    elif (fields := schema_fields(type(value))) is not None:
        for name in fields:
            yield from _value_problems(getattr(value, name), (*names, name))
    elif isinstance(value, Rotation):
        yield from _value_problems(value.value, names)


def _robot_problems(robot: RobotConfig) -> Iterator[Problem]:
    if robot.variant not in VARIANTS:
        yield ("variant",), unknown("robot variant", robot.variant, VARIANTS)
        return
    if robot.tool not in TOOLS:
        yield ("tool",), unknown("tool", robot.tool, TOOLS)
    joints = len(VARIANTS[robot.variant].joint_names)
    for name, q in robot.configurations_deg.items():
        if len(q) != joints:
            yield ("configurations_deg", name), f"needs {joints} joint angles, got {len(q)}"
    known = {"home", *robot.configurations_deg}
    if robot.initial_configuration not in known:
        yield (
            ("initial_configuration",),
            unknown("configuration", robot.initial_configuration, known),
        )


def _plant_problems(config: MultibodyPlantConfig) -> Iterator[Problem]:
    """What Drake refuses of the plant's settings (an unknown contact model, say), found by
    making a plant with them: Drake knows its own names best."""
    try:
        AddMultibodyPlant(config, DiagramBuilder())
    except Exception as e:  # Drake names the setting it refuses
        message = first_line(e)
        named = re.match(r"Unknown (\w+):", message)
        yield ("plant", named.group(1)) if named else ("plant",), message


def _place_problems(scenario: Scenario) -> Iterator[Problem]:
    """Areas are simple floor polygons; the names of locations, areas and parameters
    share the trees' root blackboard, so no name may be used twice."""
    for name, points in scenario.areas.items():
        short = next((i for i, point in enumerate(points) if len(point) != 2), None)
        if short is not None:
            yield ("areas", name, short), "a point needs exactly [x, y] (areas lie on the floor)"
            continue
        try:
            Area.from_polygon(points)
        except ValueError as e:
            yield ("areas", name), f"not a valid polygon: {e}"
    seen: dict[str, str] = {}
    for section in ("locations", "areas", "parameters"):
        for name in getattr(scenario, section):
            if name in seen:
                yield (section, name), f"'{name}' is already a name in {seen[name]}"
            seen.setdefault(name, section)


RESERVED = (*STATION_MODELS, "WorldModelInstance", "DefaultModelInstance")
"""Model instance names the station gives itself; the cell cannot use them."""


def _station_problems(scenario: Scenario) -> Iterator[Problem]:
    """Builds the robot and cell models once (no simulation), so whatever else Drake
    refuses (e.g. a weld to a frame the model lacks) is one line at load time, at the
    directive it refuses. Parsing takes half a second, so each robot and cell is tried
    once per process."""
    key = repr((scenario.robot.variant, scenario.robot.tool, scenario.cell))
    if key not in _STATION_PROBLEMS:
        _STATION_PROBLEMS[key] = _station_problem(scenario.station)
    if _STATION_PROBLEMS[key] is not None:
        yield _STATION_PROBLEMS[key]


def _station_problem(station: StationSpec) -> Problem | None:
    """What Drake refuses of the station's models, at the first directive of the cell that
    makes it refuse: Drake's message names only links and joints ('world', 'body'), which
    every weld of a cell shares, so the directive is found by building ever longer parts
    of the cell (only when the whole is refused)."""
    message = _refusal(station)
    if not message:
        return None
    cell = station.cell
    low, high = 0, len(cell)  # the robot with cell[:low] loads, with cell[:high] not
    if _refusal(dataclasses.replace(station, cell=())):
        return ("robot",), message
    while high - low > 1:
        middle = (low + high) // 2
        if _refusal(dataclasses.replace(station, cell=cell[:middle])):
            high = middle
        else:
            low = middle
    return ("cell", high - 1), _explained(message, cell[high - 1])


def _refusal(station: StationSpec) -> str:
    """Drake's first line on building `station`'s models ("" when they load)."""
    plant = MultibodyPlant(0.0)
    try:
        add_station_models(plant, model_parser(plant), station)
    except Exception as e:  # Drake's parser: its first line says what is wrong
        return first_line(e).split(" (valid names")[0]
    return ""


STATIC_WELD = "sdformat_model_static_world_welds_to_"
"""The joint Drake's SDFormat parser makes for a model marked `<static>`: a second weld of
the same model to the world is refused with a message about joints a user never wrote."""


def _explained(message: str, directive: ModelDirective) -> str:
    """Drake's `message` about `directive`, in the user's terms where it has known ones."""
    weld = directive.add_weld
    if weld is not None and STATIC_WELD in message:
        model = weld.child.split("::")[0]
        return (
            f"model '{model}' is static in its file (<static>true</static>), which welds it "
            "to the world already: remove this add_weld or the <static> tag"
        )
    return message


_STATION_PROBLEMS: dict[str, Problem | None] = {}
"""Robot and cell (as text) -> what Drake refuses of them, where (None when they load)."""


def _package_map() -> PackageMap:
    package_map = PackageMap()
    add_model_package(package_map)
    return package_map


def _clip_problems(clips: list[str], directory: Path) -> Iterator[Problem]:
    """The scenario's own clips, named relative to the scenario file: each must read as a
    clip; they are kept as absolute paths, like the tree files."""
    for i, clip in enumerate(clips):
        file = (directory / clip).resolve()
        clips[i] = str(file)
        try:
            read_clip_file(file)
        except InputError as error:
            yield ("clips", i), str(error)


def _resolve_tree_files(directory: Path, trees: dict[str, AgentTree]) -> Iterator[Problem]:
    """Tree files are named relative to the scenario file; keep them as absolute paths so
    the loaded scenario works from any directory (and in sweep workers)."""
    for agent, tree in trees.items():
        if agent not in AGENTS:
            yield (agent,), unknown("agent", agent, AGENTS)
            continue
        file = (directory / tree.file).resolve()
        if not file.is_file():
            yield (agent, "file"), f"tree file '{tree.file}' not found (looked at {file})"
        tree.file = str(file)


def tree_problems(scenario: Scenario) -> Iterator[Problem]:
    """The trees' own errors (they name the tree file, line, node and port: the field
    names are empty) and scenario parameters the trees cannot read."""
    for error in tree_errors(scenario.trees, scenario.places(), scenario.parameters):
        yield error if isinstance(error, tuple) else (None, str(error))
