"""Commands to the simulated person and the status it reports (frozen, port-friendly).

Every command carries a sequence number `seq`. Each issuer's input port (`<issuer>_command`,
hrc_drake.wiring) holds its recent commands; the actor acts once on each new seq. A command
arriving while a Movement or Animation runs is rejected; Cancel stops the running one;
InTheWay may change the running walk; SetCalled is a flag and never conflicts.
"""

from dataclasses import dataclass

from hrc_drake.messages import ResultLog

NULL_QUATERNION = (0.0, 0.0, 0.0, 0.0)
"""Target orientation meaning "end facing the walking direction"."""

STATES = ("SETUP", "IDLE", "MOVEMENT", "ANIMATION")


ONE_HAND = "right"
BOTH_HANDS = "both"


@dataclass(frozen=True)
class Hold:
    """What the hands hold: one hand (the right) or both, and the object's extents (m) along
    the person's forward, sideways and up directions while held. Both hands hold an object
    between their palms (its centre halfway between them); one hand holds it from above (its
    top face at the palm)."""

    hands: str
    size: tuple[float, float, float]


@dataclass(frozen=True)
class Grasp:
    """An object to take: which hands, its centre and heading (rad) in the world, and its
    box extents along its own x, y and z. The person puts their palms on the two faces
    that face their sides (both hands) or on its top face (one hand)."""

    hands: str
    center: tuple[float, float, float]
    yaw: float
    size: tuple[float, float, float]


@dataclass(frozen=True)
class Box:
    """An object standing near what the hands are aimed at, which they keep clear of: its
    centre and heading (rad) in the world, its extents along its own x, y and z, and what
    a refusal calls it when something would go into it."""

    center: tuple[float, float, float]
    yaw: float
    size: tuple[float, float, float]
    name: str = "object"


@dataclass(frozen=True)
class MoveCommand:
    """Walk to `target_position` (x, y[, z ignored]) and turn to `target_quaternion` (w, x, y, z).

    `animation_distance` is the ground covered by one cycle of the walk clip (None: the clip's
    own, which keeps the feet planted); `waypoints` are (x, y) points passed on the way.
    """

    seq: int
    target_position: tuple[float, ...]
    target_quaternion: tuple[float, float, float, float] = NULL_QUATERNION
    animation_name: str = "walk"
    animation_distance: float | None = None
    waypoints: tuple[tuple[float, float], ...] = ()
    hold: Hold | None = None
    """What the hands hold meanwhile (they keep it in the carry posture)."""
    nearby: tuple[Box, ...] = ()
    """Objects near the start and the target: the arms keep out of them as the person turns
    there, and what the hands hold where the walk ends."""
    in_the_way: tuple[Box, ...] = ()
    """Objects standing over the floor (what the robot holds still): a walk that would pass
    through one goes round it."""


@dataclass(frozen=True)
class AnimateCommand:
    """Play a clip in place; `target` (world x, y, z) aims pick/place/reach/hand_over.

    `hold` is what the hands hold when the clip starts: a place or a giving hand-over puts
    its centre at `target`; other clips keep it in the carry posture. `grasp` is what a pick
    or a taking hand-over takes (the hands close on its faces; `target` is then ignored)."""

    seq: int
    animation_name: str
    animation_speed: float = 1.0
    target: tuple[float, float, float] | None = None
    hold: Hold | None = None
    grasp: Grasp | None = None
    nearby: tuple[Box, ...] = ()
    """Objects near the target: the arms keep out of them as out of the cell's furniture."""


@dataclass(frozen=True)
class CancelCommand:
    seq: int


@dataclass(frozen=True)
class InTheWayCommand:
    """What now stands over the floor (the robot stopped holding it): a walk under way whose
    rest would pass through one of `boxes` comes to a stop and goes round them, or, with no
    way round, stays stopped and fails. Never busy: it comes while a walk runs."""

    seq: int
    boxes: tuple[Box, ...]


@dataclass(frozen=True)
class SetCalledCommand:
    seq: int
    called: bool


HumanCommand = MoveCommand | AnimateCommand | CancelCommand | InTheWayCommand | SetCalledCommand


@dataclass(frozen=True)
class HumanStatus:
    """What the person reports after every update.

    `results` keeps the outcomes of the recent commands, so a node can still find its own
    after a later command.
    Poses are (x, y, z, qw, qx, qy, qz) in world; `base_pose` is (x, y, yaw). `event` is the
    clip event that fired during the last update ("" if none); `event_count` counts them all;
    `activity_events` are the events fired since the running action started, so a behavior
    tree ticking slower than the person still sees each one.
    """

    state: str = "SETUP"
    progress: float = 0.0
    base_pose: tuple[float, float, float] = (0.0, 0.0, 0.0)
    base_speed: float = 0.0
    left_hand: tuple[float, ...] = ()
    right_hand: tuple[float, ...] = ()
    head: tuple[float, ...] = ()
    called: bool = False
    event: str = ""
    event_count: int = 0
    activity_events: tuple[str, ...] = ()
    animation: str = ""
    results: ResultLog = ResultLog()
    time: float = 0.0

    def __deepcopy__(self, memo):
        """Immutable: Drake's state copies can share it."""
        return self
