"""The scenario file's schema: plain dataclasses read with Drake's `yaml_load_typed`, as in
Drake's `examples/hardware_sim`, with Drake's own config structs (`Transform`,
`ModelDirective`, `MultibodyPlantConfig`, `SimulatorConfig`) where Drake has one.

Every periodic part has a `period` in seconds in its section; the plant's step is Drake's
own `plant.time_step` (docs/architecture.md, "Rates and seeds"). Each section's schema lives
with the part it configures (`robot.motion`: hrc_drake.motion.options, `safety`:
hrc_drake.safety.config, `workpieces`: hrc_drake.workpieces.config, `trees`:
hrc_drake.agent_trees, `falsify`: hrc_drake.scenario.falsify); this module ties them into
one Scenario.
"""

from dataclasses import dataclass, field

from pydrake.common.schema import Rotation, Transform
from pydrake.math import RigidTransform
from pydrake.multibody.parsing import ModelDirective
from pydrake.multibody.plant import MultibodyPlantConfig
from pydrake.systems.analysis import SimulatorConfig

from hrc_drake.agent_trees import AgentTree, load_agent_tree
from hrc_drake.areas import Area
from hrc_drake.ergonomics.config import ErgonomicsOptions
from hrc_drake.human.protocol import UPDATE_PERIOD
from hrc_drake.human.survey import survey_size
from hrc_drake.iisy import TOOL_BODY
from hrc_drake.motion.options import MotionOptions
from hrc_drake.nodes.agent import Places
from hrc_drake.safety.config import SafetyConfig
from hrc_drake.scenario.falsify import FalsifyConfig
from hrc_drake.station import HOME, StationSpec
from hrc_drake.tree_types import Pose
from hrc_drake.workpieces.config import WorkpiecesConfig
from hrc_drake.yaml_check import REQUIRED


@dataclass
class RobotConfig:
    """The cobot: which iisy, where its base stands, which tool, which configurations."""

    variant: str = field(default="", metadata=REQUIRED)
    base_pose: Transform = field(default_factory=Transform)
    tool: str = TOOL_BODY
    initial_configuration: str = HOME
    configurations_deg: dict[str, list[float]] = field(default_factory=dict)
    motion: MotionOptions = field(default_factory=MotionOptions)


@dataclass
class VisualizationOptions:
    """Meshcat settings; `record` keeps an animation for the standalone replay.html."""

    period: float = 1.0 / 32.0
    """s between frames Meshcat draws and the replay records"""
    record: bool = True
    show_collision: bool = False
    camera_position: list[float] = field(default_factory=list)
    """m, world frame; empty: a camera that frames the whole cell (its furniture, the robot,
    the person's start and places to stand)"""
    camera_target: list[float] = field(default_factory=list)


@dataclass
class HumanConfig:
    """The person: body height and mass (segments scale with them), or a sex and a
    percentile of a published survey (`percentile` given: they set height and mass, see
    hrc_drake.human.anthropometry.survey_size), where they start (x, y in metres, facing
    yaw in degrees) and how often their protocol and pose are updated (above Meshcat's
    frame rate)."""

    height: float = 1.75
    mass: float = 75.0
    sex: str = "male"
    percentile: float | None = None
    start: list[float] = field(default_factory=lambda: [0.0, -2.0, 90.0])
    period: float = UPDATE_PERIOD
    audit_every: int = 2
    """The realism audit samples every this many of the person's poses (every second, 30
    Hz: its worst values lie within 1 mm of every pose's in the bundled scenarios,
    tests/evaluation/test_audit_rate.py)."""
    clips: list[str] = field(default_factory=list)
    """The scenario's own motion clips: .bvh or .json files (relative to the scenario file),
    which trees play by their file names."""

    @property
    def audit_period(self) -> float:
        """s between the realism audit's samples (a cell without a person audits its objects
        at a default person's)."""
        return self.period * self.audit_every

    def size(self) -> tuple[float, float]:
        """Height (m) and mass (kg) of the person."""
        if self.percentile is None:
            return self.height, self.mass
        return survey_size(self.sex, self.percentile)

    def survey_person(self) -> str:
        """Which person of the survey a `percentile` takes, in words ("" without one), for
        `validate` to say: the sex defaults to male, and a user's `percentile: 5` with no
        sex was a 1.64 m man, not the documented 1.52 m 5th-percentile woman (#26)."""
        if self.percentile is None:
            return ""
        height, mass = self.size()
        return (
            f"{_ordinal(self.percentile)}-percentile {self.sex} of ANSUR II, {height:.3f} m and "
            f"{mass:.1f} kg (human.sex: female or male)"
        )


ORDINAL_SUFFIXES = {1: "st", 2: "nd", 3: "rd"}


def _ordinal(number: float) -> str:
    """5th, 1st, 22nd, 12.5th."""
    whole = int(number)
    if number != whole or 10 <= whole % 100 <= 20:
        return f"{number:g}th"
    return f"{whole}{ORDINAL_SUFFIXES.get(whole % 10, 'th')}"


@dataclass
class ReportOptions:
    """How often the run's record samples the arm's state and every actor's and tree's
    state (what report.json's robot figures and timeline.png's state rows are made of)."""

    period: float = 0.01


def _plant_config() -> MultibodyPlantConfig:
    """A discrete plant with Drake's SAP contact solver, stepped every millisecond.

    Its output ports are live, not sampled: nothing reads the outputs sampling would hold
    (contact results, accelerations, reaction forces; the state is the same either way),
    and a sampling plant steps as an unrestricted update, after which Drake's simulator asks
    every system for its witness functions, a call into Python for each Python system at
    every plant step (3.5 us per system and step, benchmarks/python_systems.py)."""
    return MultibodyPlantConfig(
        time_step=1e-3, discrete_contact_approximation="sap", use_sampled_output_ports=False
    )


@dataclass
class Scenario:
    name: str = field(default="", metadata=REQUIRED)
    description: str = ""
    seed: int = 0
    duration: float = 10.0
    plant: MultibodyPlantConfig = field(default_factory=_plant_config)
    simulator: SimulatorConfig = field(default_factory=SimulatorConfig)
    robot: RobotConfig = field(default_factory=RobotConfig, metadata=REQUIRED)
    cell: list[ModelDirective] = field(default_factory=list)
    areas: dict[str, list[list[float]]] = field(default_factory=dict)
    locations: dict[str, Transform] = field(default_factory=dict)
    visualization: VisualizationOptions = field(default_factory=VisualizationOptions)
    report: ReportOptions = field(default_factory=ReportOptions)
    ergonomics: ErgonomicsOptions = field(default_factory=ErgonomicsOptions)
    human: HumanConfig | None = None
    workpieces: WorkpiecesConfig = field(default_factory=WorkpiecesConfig)
    safety: SafetyConfig = field(default_factory=SafetyConfig)
    trees: dict[str, AgentTree] = field(default_factory=dict)
    parameters: dict[str, str] = field(default_factory=dict)
    """Root blackboard entries of every tree (converted to each port's type when read)."""
    falsify: FalsifyConfig | None = None
    """The behaviour parameters `hrc-drake falsify` searches (hrc_drake.scenario.falsify)."""

    def area(self, name: str) -> Area:
        return Area.from_polygon(self.areas[name])

    def location(self, name: str) -> RigidTransform:
        return self.locations[name].GetDeterministicValue()

    @property
    def station(self) -> StationSpec:
        """What the station's models are built from (the robot section and the cell)."""
        robot = self.robot
        return StationSpec(
            variant=robot.variant,
            base_pose=robot.base_pose.GetDeterministicValue(),
            tool=robot.tool,
            cell=tuple(self.cell),
            configurations_deg=dict(robot.configurations_deg),
            initial_configuration=robot.initial_configuration,
        )

    def agent_tree(self, agent: str):
        """The agent's tree and its Agent, the root blackboard filled with the places and
        parameters (hrc_drake.agent_trees.load_agent_tree)."""
        return load_agent_tree(self.trees[agent], agent, self.places(), self.parameters)

    def places(self) -> Places:
        """The named locations and areas as trees see them: a location written without a
        rotation has no orientation (the robot keeps its tool down, the person faces where
        they walk)."""
        return Places(
            locations={name: self._location_pose(name) for name in self.locations},
            areas={name: self.area(name) for name in self.areas},
        )

    def _location_pose(self, name: str) -> Pose:
        pose = Pose.from_transform(self.location(name))
        if isinstance(self.locations[name].rotation.value, Rotation.Identity):
            return Pose(pose.position)
        return pose
