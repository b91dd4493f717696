"""How a station is wired, in one place: who acts, who may command whom, and the names of
the ports, command issuers, systems and model instances that connect them.

Agents are the behavior trees (one per agent); actors are the systems that carry out
commands (the robot's motion, the person, the workpieces); the safety monitor reports but
takes no commands. Commands flow down from an agent's tree to the actors it may command,
status flows up from every actor and the monitor to every tree (docs/architecture.md).

An actor that several issuers command has one command input per issuer,
`<issuer>_command`, and keeps the issuers apart; a tree has one command output per actor
it may command, `<actor>_command`, and one status input per source, `<source>_status`.
"""

ROBOT = "robot"
HUMAN = "human"
WORKPIECES = "workpieces"
SAFETY = "safety"

AGENTS = (ROBOT, HUMAN)
"""The agents that run behavior trees, in the order their command numbers interleave."""
STATUS_SOURCES = (ROBOT, HUMAN, WORKPIECES, SAFETY)
"""Whose status every tree reads: the actors, which carry out commands (RobotMotion,
HumanActor, Workpieces), and the safety monitor, which takes none."""

COMMANDED_BY = {ROBOT: (ROBOT, HUMAN, WORKPIECES), HUMAN: (HUMAN, WORKPIECES)}
"""The actors each agent's tree may command: the robot's tree its robot, the objects, and
the person (to call them); the person's tree the person and the objects."""

GRIPPER_ISSUER = "robot_gripper"
"""RobotMotion's vacuum gripper, which commands the workpieces on its own behalf."""


def may_command(agent: str, actor: str) -> bool:
    return actor in COMMANDED_BY[agent]


def tree_issuer(agent: str) -> str:
    """How the actors name the commands of `agent`'s tree."""
    return f"{agent}_tree"


def issuers_of(actor: str) -> tuple[str, ...]:
    """Everything that commands `actor`, one command input each: the trees that may,
    and for the workpieces the robot's gripper."""
    trees = tuple(tree_issuer(agent) for agent in AGENTS if may_command(agent, actor))
    return (*trees, GRIPPER_ISSUER) if actor == WORKPIECES else trees


def command_input(issuer: str) -> str:
    """An actor's input for the commands of `issuer`."""
    return f"{issuer}_command"


def command_output(actor: str) -> str:
    """A tree's output of its commands to `actor`."""
    return f"{actor}_command"


def status_port(source: str) -> str:
    """The status output of `source`, and every tree's input of it."""
    return f"{source}_status"


def first_seq(agent: str) -> int:
    """The number of `agent`'s first command. Agents number their commands in disjoint
    steps of SEQ_STEP (robot 1, 3, 5...; person 2, 4, 6...), so an actor that both trees
    command never sees one number twice, and the gripper's commands, which carry the number
    of the robot's Grip or Release, never meet the person's."""
    return AGENTS.index(agent) + 1


SEQ_STEP = len(AGENTS)


# System names in the station diagram.
DYNAMIC_PLANT = "plant"
SCENE_GRAPH = "scene_graph"
STATION_MIRROR = "station_mirror"
STATION_MIRROR_GEOMETRY = "station_mirror_geometry"
ROBOT_CONTROLLER = "robot_controller"
ROBOT_MOTION = "robot_motion"
ROBOT_DESIRED_CLOCK = "robot_desired_clock"
ROBOT_DESIRED_MOTION = "robot_desired_motion"
ROBOT_DESIRED_DIFFERENCES = "robot_desired_differences"
ROBOT_DESIRED_SPLIT = "robot_desired_split"
TOOL_POSE = "tool_pose"
HUMAN_ACTOR = "human_actor"
HUMAN_GEOMETRY = "human_geometry"
HUMAN_HANDS = "human_hands"
WORKPIECES_SYSTEM = "workpieces"
SAFETY_MONITOR = "safety"
SAFETY_SENSORS = "safety_sensors"
REALISM_AUDIT = "realism_audit"
VISUALIZER = "meshcat_visualizer"
RECORDER = "replay_recorder"
STATE_CHANGES = "state_changes"
ROBOT_STATE_LOG = "robot_state_log"
SAFETY_SIGNALS_LOG = "safety_signals_log"
POSTURE_LOG = "posture_log"
HELD_OBJECTS = "held_objects"


def tree_system(agent: str) -> str:
    """The name of `agent`'s BehaviorTreeSystem (and the stem of its log files)."""
    return f"bt_{agent}"


# Model instance names the station gives itself (a scenario's cell may not use them).
ROBOT_MODEL = "iisy"
TOOL_MODEL = "tool"
HUMAN_MODEL = "human"
STATION_MODELS = (ROBOT_MODEL, TOOL_MODEL)

VISUAL_PREFIX = "visual"
"""Meshcat's path prefix of the illustration geometry (`/drake/visual/...`)."""
