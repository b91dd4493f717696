"""What the person refuses: a motion aimed at something (a pick, a put-down, a reach) that
still goes into the furniture once the head and arms have been kept out of it as far as
they can (hrc_drake.human.head_room, hrc_drake.human.clearance), a pick whose hands, so kept
out, would close on the air beside what they take, a pick or a put-down whose
held object goes into it on its planned way or would be in it where it is put, or a carry
that would end with the held object in it (or else stops short of its place) or start by
turning it into it however far the person steps back (hrc_drake.human.planning).

Where the corrections cannot find a way, the person played it through the shelf: a stoop
to a carton on a shelf's bottom board put the head 8 cm into the board above, and the run
reported only a realism excess. Refused, the tree's node fails with what would have gone
where (the run's summary says so), and `hrc-drake validate` finds it before a run
(hrc_drake.scenario.tree_findings plans the picks it can know of)."""

from functools import partial

import numpy as np

from hrc_drake.human.activity import Activity
from hrc_drake.human.aiming import Unreachable
from hrc_drake.human.arm_shapes import HEAD, Prisms, corners_in_world, parts_shapes
from hrc_drake.human.clearance import NEAR, SAMPLE, instants
from hrc_drake.human.furniture import Furniture
from hrc_drake.human.grasp import box_corners, held_corners
from hrc_drake.human.messages import Hold
from hrc_drake.human.performer import Performer
from hrc_drake.human.segments import ClipSegment
from hrc_drake.human.skeleton import SIDES

DEPTH_LIMIT = 0.02
"""m: deeper than this, the motion is refused: twice the realism audit's limit for the body
in the cell's geometry or an object (docs/realism.md), since the prisms' separating-axis
test, which knows only their faces' directions, overstates how deep a round shape goes in
beside an edge (a forearm passing a shelf board's edge: 1.4 cm by it, clear in SceneGraph).
A held box is refused at the same depth, not at the audit's 1 cm for it: its corners,
measured at the planned pose against the prisms, are not what the audit measures in the
played run with SceneGraph's shapes (coexistence seed 2's inspect pick: 1.2 cm into the
finished part 15 as planned, 0.0 cm in the run's audit)."""
ARRIVING = 0.6
"""s: the last step of a walk, in which what the hands carry swings furthest ahead (a kit
carried up to another on a table: 2.3 cm in it 0.35 s before the walk ended, clear where
it ended)."""
GRASP_REACH = 0.05
"""m: how far from what they take the hands may close on it (the point between two palms,
or one palm), as the objects' world takes it (hrc_drake.workpieces.config, hand_tolerance)."""
PARTS = (HEAD, *SIDES)
HELD_RADII, HELD_SHAPE = np.zeros(1), np.arange(8)[None]
"""A held box as one shape of `Prisms.shape_depths`: its 8 corners, no radius."""


def refuse_going_in(performer: Performer, activity: Activity, start: float) -> None:
    """Raises Unreachable, saying what would go where, when `activity`, played from `start`
    with its corrections, puts the head, an arm or what the hands hold into what it keeps
    out of (`going_in`)."""
    problem = going_in(performer, activity, start)
    if problem:
        raise Unreachable(problem)


def going_in(performer: Performer, activity: Activity, start: float) -> str:
    """What the hands hold to put down puts deeper than DEPTH_LIMIT into what it keeps out
    of, or else what of the head and arms `activity`, played from `start`, does so, or else
    what the hands take does, and where, or else how far the arms so kept out leave the
    hands from what they take (`_kept_off_the_grasp`) ("" when none). What is put down
    first: one in the furniture where the put-down begins says what to change (where the
    person stands with it), whatever the head and arms then do on their way (a tote carried
    into a shelf's board, its put-down planned with the hands held above the board, also
    put the head 2.2 cm into the shelf); what is taken last, as the hands reach it before
    they take it (stooping to a carton on a shelf's bottom board, the head went into the
    board above before the carton went into it)."""
    furniture = activity.furniture_of(performer)
    if not furniture.pieces:
        return ""
    end = activity.end if np.isfinite(activity.end) else start
    times = instants(start, end)
    return (
        _held_going_in(performer, activity, times, PUTTING_DOWN)
        or _body_going_in(performer, activity, times)
        or _held_going_in(performer, activity, times, TAKING_UP)
        or _kept_off_the_grasp(performer, activity)
    )


def _body_going_in(performer: Performer, activity: Activity, times) -> str:
    """What of the head and arms goes deeper than DEPTH_LIMIT into the furniture, and where
    ("" when nothing)."""
    furniture = activity.furniture_of(performer)
    prisms, start = Prisms.of(furniture), times[0]
    poses = np.array([activity.pose(performer, float(t)) for t in times])
    body = performer.body
    radii, shapes, starts = parts_shapes(body, PARTS)
    corners = corners_in_world(body, poses, PARTS)
    depths = prisms.deepest_near(poses[:, :2], NEAR, corners, radii, shapes)
    k, shape = np.unravel_index(np.argmax(depths), depths.shape)
    if depths[k, shape] <= DEPTH_LIMIT:
        return ""
    part = PARTS[np.searchsorted(starts, shape, side="right") - 1]
    into = prisms.shape_depths(corners[k], radii, shapes)[:, shape]
    where = furniture.pieces[int(np.argmax(into))].name
    return (
        f"{_named(part)} would go {100 * depths[k, shape]:.1f} cm into '{where}' "
        f"{times[k] - start:.1f} s in, however the arms and head are moved: no way to do it "
        "from where the person stands"
    )


def _kept_off_the_grasp(performer: Performer, activity: Activity) -> str:
    """How far the head and arms kept out of the furniture leave the hands from what they
    take as they close on it, where that is further than the objects' world lets them take
    it from (GRASP_REACH; "" when not). A box on a rack's 1.6 m board: the forearms lifted
    over the board's edge put the palms 7.7 cm over the box, `validate` said nothing and
    the run's pick failed, 0.09 m from the point between the palms."""
    grasped = _grasp_of(performer, activity)
    if grasped is None:
        return ""
    t, sides = grasped
    box, _ = activity.reached_for
    q = activity.pose(performer, t)
    hands = [performer.body.frame_pose(f"{side}_hand_grasp", q).translation() for side in sides]
    off = _outside(box, np.mean(hands, axis=0))
    if off <= GRASP_REACH:
        return ""
    return (
        f"the arms kept out of the cell would leave the {_palms(sides)} {100 * off:.0f} cm "
        "from what they take as they close on it: no way to take it from where the person stands"
    )


def _grasp_of(performer: Performer, activity: Activity):
    """When `activity` takes what it reaches for, and with which hands (None: it takes
    nothing)."""
    if activity.reached_for is None:
        return None
    for segment in activity.segments:
        if isinstance(segment, ClipSegment) and segment.aim is not None:
            events = performer.clips[segment.clip].events
            if "grasp" in events:
                return segment.start + events["grasp"] / segment.speed, segment.aim.hands
    return None


def _outside(box, point) -> float:
    """How far `point` is outside `box` (0 inside)."""
    c, s = np.cos(box.yaw), np.sin(box.yaw)
    d = np.asarray(point) - np.asarray(box.center)
    local = np.array([c * d[0] + s * d[1], -s * d[0] + c * d[1], d[2]])
    return float(np.linalg.norm(np.maximum(np.abs(local) - np.asarray(box.size) / 2, 0.0)))


def _palms(sides) -> str:
    return "point between the palms" if len(sides) == 2 else f"{sides[0]} palm"


PUTTING_DOWN, TAKING_UP = "put it down", "take it"
"""What the hands do with what they hold (`_held_going_in`)."""


def _held_going_in(performer: Performer, activity: Activity, times, doing) -> str:
    """What an object the hands hold goes into deeper than DEPTH_LIMIT, and where ("" when
    nothing), as they put it down (`doing` PUTTING_DOWN: on the way from the carry posture;
    a blend from the pose before leaves the object where the hands were; a tote carried up
    to a shelf whose board is at its height is in the board before the put-down begins, a
    cell of our own: 4.5 cm) or take it (TAKING_UP: from the grasp into the carry posture;
    a tote taken off a shelf's 1.1 m board, carried at the waist just below the board's top,
    stayed 6 cm inside the shelf, a cell of our own)."""
    held = activity.putting_down if doing == PUTTING_DOWN else activity.taking_up
    carries = [held(performer, float(t)) for t in times]
    furniture = activity.furniture_of(performer)
    depth, where, t = _deepest_held(performer, activity, furniture, times, carries)
    if depth <= DEPTH_LIMIT:
        return ""
    return (
        f"what the hands hold would go {100 * depth:.1f} cm into '{where}' "
        f"{t - times[0]:.1f} s in: no way to {doing} from where the person stands"
    )


def _deepest_held(performer: Performer, activity: Activity, furniture, times, carries):
    """How deep, into which piece of `furniture` and when (the first time so deep), the
    object held at `times` as `carries` (None: nothing) goes deepest: (0.0, "", first
    time) when nowhere."""
    body, prisms = performer.body, Prisms.of(furniture)
    worst = (0.0, "", times[0])
    for t, carry in zip(times, carries, strict=True):
        if carry is None:
            continue
        q = activity.planned_pose(performer, float(t))
        near = np.flatnonzero(prisms.near_mask(q[:2], NEAR + max(carry.size)))
        if not near.size:
            continue
        corners = held_corners(body, carry, q)[None]
        into = prisms.subset(near).shape_depths(corners, HELD_RADII, HELD_SHAPE)[0, :, 0]
        if into.max() > worst[0]:
            worst = (float(into.max()), furniture.pieces[near[np.argmax(into)]].name, t)
    return worst


def placed_going_in(furniture: Furniture, hold: Hold, center, heading: float) -> str:
    """What an object held as `hold` and put down with its centre at `center`, facing the
    person's `heading`, would be in deeper than DEPTH_LIMIT, and how deep ("" when
    nothing): a tote put onto a stack that reaches the board above went 2.7 cm into the
    board (a cell of our own: a fourth tote onto three)."""
    return _box_going_in(furniture, box_corners(center, heading, hold.size), "where it is put")


def put_on_nothing(furniture: Furniture, hold: Hold, center) -> str:
    """Where an object held as `hold`, put down onto a top with its centre at `center`, has
    nothing but the floor under its middle ("" when something is under it): the top it is
    off, by how far and where on that top it goes. Let go there, the objects' world rested
    a tray 15 cm past a table's edge on the table its footprint touched, in the air against
    the person's belly, 2.5 cm in it (a user's cell: #26); fallen 0.9 m to the floor, it
    would be no put-down either."""
    size = np.asarray(hold.size, dtype=float)
    bottom = np.asarray(center, dtype=float) - (0.0, 0.0, size[2] / 2)
    if furniture.support(bottom) is not None:
        return ""
    nearest = furniture.nearest_top(bottom, np.hypot(*size[:2]) / 2)
    if nearest is None:
        return f"where it is put, {100 * bottom[2]:.0f} cm up, has nothing under it"
    piece, off, onto = nearest
    x, y, z = onto + (0.0, 0.0, size[2] / 2)
    return (
        f"where it is put is {100 * off:.1f} cm off the top of '{piece.name}', nothing but "
        f"the floor under it: put it on the top, at about ({x:.2f}, {y:.2f}, {z:.2f})"
    )


def arrived_going_in(performer: Performer, activity: Activity, carry, furniture):
    """How deep the object the hands carry (`carry`) would be in the furniture in the last
    ARRIVING seconds of `activity`, a walk, and what it would be in deeper than DEPTH_LIMIT
    ("" when nothing): a carton carried up to a column of cartons stood 2.4 cm in its top one
    while its put-down was refused (a cell of our own)."""
    times = np.arange(activity.end, activity.end - ARRIVING, -SAMPLE)
    pose = partial(activity.planned_pose, performer)
    depth, where = _held_depth(performer, carry, pose, times, furniture)
    return depth, _deeper_than_allowed(depth, where, "where the walk ends")


def swept_depth(performer: Performer, turn, furniture: Furniture) -> tuple[float, str]:
    """How deep the object the hands carry through `turn` (a turn on the spot with a carry)
    goes into the furniture at its deepest (<= 0: it keeps out), and into what: turned on
    the spot, its far corners sweep round further ahead than the hands hold them."""
    times = np.arange(turn.start, turn.end(performer) + SAMPLE / 2, SAMPLE)
    pose = partial(turn.pose, performer)
    return _held_depth(performer, turn.carry, pose, times, furniture)


def _held_depth(performer: Performer, carry, pose, times, furniture: Furniture):
    """How deep the object held as `carry` goes into the furniture at its deepest over
    `times`, the person posed by `pose(t)`, and into what (0, "": there is no furniture)."""
    if not furniture.pieces:
        return 0.0, ""
    corners = np.array([held_corners(performer.body, carry, pose(t)) for t in times])
    return _boxes_depth(furniture, corners)


def _box_going_in(furniture: Furniture, corners: np.ndarray, where_then: str) -> str:
    """What a box with `corners` is in deeper than DEPTH_LIMIT ("" when nothing)."""
    return _deeper_than_allowed(*_boxes_depth(furniture, corners[None]), where_then)


def _boxes_depth(furniture: Furniture, corners: np.ndarray) -> tuple[float, str]:
    """How deep the deepest of boxes with `corners` (boxes, 8, 3) is in the furniture, and
    in which piece (0, "": there is no furniture)."""
    if not furniture.pieces:
        return 0.0, ""
    into = Prisms.of(furniture).shape_depths(corners, HELD_RADII, HELD_SHAPE)[..., 0].max(axis=0)
    return float(into.max()), furniture.pieces[int(np.argmax(into))].name


def _deeper_than_allowed(depth: float, where: str, where_then: str) -> str:
    if depth <= DEPTH_LIMIT:
        return ""
    return f"what the hands hold would be {100 * depth:.1f} cm into '{where}' {where_then}"


def _named(part: str) -> str:
    return "the head" if part == HEAD else f"the {part} arm"
