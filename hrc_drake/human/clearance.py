"""The arms clear of the furniture: a motion planned next to a table is checked against the
cell's geometry before it is played, and where an arm would go into it, that arm is moved
out by inverse kinematics; the correction eases in and out around it.

A clip is authored in an empty room: an arm swinging by a walker's side, the free arm of a
person leaning over a table to reach with the other, a forearm turning an object in front of
the belly. Played next to furniture, such an arm may pass through its top. The check samples
the planned poses and measures how deep each of an arm's collision shapes (the capsules of
the upper arm and forearm, the hand's box) goes into the cell's prisms
(hrc_drake.human.furniture), with the separating-axis test on the prisms' faces. An arm
that goes in is pushed out by a little more, the shortest way: up off a table's top, or
back off its edge (a hanging arm is not lifted onto a table); a free arm never down under
it. A hand that is aimed at something or holds it is kept where it is. The corrections are
an `ArmCorrection`: joint offsets at the checked instants, eased in and out.
"""

from bisect import bisect_right
from dataclasses import dataclass
from functools import cached_property, lru_cache

import numpy as np
from pydrake.math import RollPitchYaw

from hrc_drake.human.body import FrameTask, HumanBody
from hrc_drake.human.furniture import Furniture
from hrc_drake.human.grasp import arm_indices
from hrc_drake.human.keyed_clips import minimum_jerk
from hrc_drake.human.skeleton import SIDES

ARM = ("upper_arm", "forearm", "hand")
"""The arm's bodies, from the shoulder out."""
TOLERANCE = -0.01
"""m: an arm this far into the furniture, or less, is left as it is: negative, an arm this
close to it is moved off too (points on the shapes miss how deep two boxes that cross
edge to edge overlap, by up to about a centimetre)."""
HELD_TOLERANCE = 0.0
"""m: the same for the arm of a hand that holds something or is aimed at it: moved only
when it goes in. Its hand is where the grasp puts it, just over what the object stands on
(hrc_drake.human.grasp.GRIP_ABOVE_SUPPORT); pushed off that, the palm leaves the object."""
MARGIN = 0.02
"""m: an arm moved off the furniture ends this far clear of it."""
SAMPLE = 1.0 / 30.0
"""s: the planned poses are checked this often (the built-in clips' frame rate; a hand
rising in front of the body moves some 5 cm in that time)."""
VERIFICATIONS = 3
"""Times the corrected poses are checked again."""
EASE = 0.3
"""s: a correction eases in over this long before the arm would go in, and out after."""
NEAR = 1.2
"""m: furniture further than this from the pelvis cannot be touched by an arm."""
PUSH_STEPS = 8
"""IK steps of one push (it moves a point a few centimetres)."""
PUSHES = 3
"""An arm is pushed out at most this often at one pose (each push may bring another of its
points in)."""
HAND_SHIFT = 0.01
"""m: a correction moves a held hand this far at most, or as far as it must to get the arm
out of what its planned pose puts it in (the IK puts a hand within a centimetre or so of
its target; moved further, a palm leaves the face it holds or goes into the object)."""
SHIFT_SEARCH = 6
"""Halvings of a correction that would move a held hand too far."""
HELD = (3.0, 3.0, 3.0)
"""A hand that holds or is aimed stays where it is: its position outweighs the push."""


@dataclass(frozen=True)
class Points:
    """One arm's collision shapes: per body of the arm, the corners of its shape's hull (in
    the body's frame) and the radius round them."""

    frames: tuple[str, ...]
    points: tuple[np.ndarray, ...]
    radii: tuple[float, ...]

    @cached_property
    def starts(self) -> np.ndarray:
        """Where each shape's corners start among all of them."""
        return np.cumsum([0, *(len(p) for p in self.points[:-1])])

    @cached_property
    def radii_column(self) -> np.ndarray:
        return np.asarray(self.radii)[None, None, :]

    @cached_property
    def stacked(self) -> np.ndarray:
        """All the corners, shape by shape (n × 3; read-only: checks hand out its rows)."""
        stacked = np.vstack(self.points)
        stacked.setflags(write=False)
        return stacked


@lru_cache(maxsize=16)
def arm_points(body: HumanBody, side: str) -> Points:
    """The shapes of the upper arm, forearm and hand as the corners of their hulls: a
    capsule's two axis ends (with its radius), the hand box's eight corners."""
    frames, points, radii = [], [], []
    for part in ARM:
        name = f"{side}_{part}"
        (collision,) = body.skeleton.body(name).collisions
        shape = collision.shape
        R = RollPitchYaw(*shape.rpy).ToRotationMatrix().matrix()
        if shape.kind == "capsule":
            radius, length = shape.size
            local = np.array([[0.0, 0.0, -length / 2], [0.0, 0.0, length / 2]])
        else:  # the hand's box
            radius = 0.0
            half = np.asarray(shape.size) / 2
            local = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)]) * half
        frames.append(name)
        points.append(np.asarray(shape.xyz, dtype=float) + local @ R.T)
        radii.append(radius)
    return Points(tuple(frames), tuple(points), tuple(radii))


@dataclass(frozen=True)
class Prisms:
    """The furniture's prisms by their faces, for the separating-axis test: per piece, the
    outward normal of each face (its outline's edges, then down and up; padded to the same
    count with axes that never separate) and how far the piece reaches along each normal,
    forward and backward."""

    axes: np.ndarray
    """(pieces, faces, 3)"""
    ahead: np.ndarray
    """(pieces, faces): the largest projection of the piece on each axis."""
    behind: np.ndarray
    """(pieces, faces): the smallest."""

    @classmethod
    def of(cls, furniture: Furniture) -> "Prisms":
        faces = [_faces(piece) for piece in furniture.pieces]
        count = max((len(a) for a, _, _ in faces), default=2)
        axes = np.zeros((len(faces), count, 3))
        ahead = np.full((len(faces), count), np.inf)
        behind = np.full((len(faces), count), -np.inf)
        for k, (a, hi, lo) in enumerate(faces):
            axes[k, : len(a)], ahead[k, : len(a)], behind[k, : len(a)] = a, hi, lo
        return cls(axes, ahead, behind)

    def near(self, xy, reach: float) -> "Prisms":
        """The prisms within `reach` of a floor point (the rest cannot be touched)."""
        point = np.array([xy[0], xy[1], 0.0])
        sideways = self.axes[:, :, 2] == 0.0
        distance = np.where(sideways, self.axes @ point - self.ahead, -np.inf).max(axis=1)
        keep = distance <= reach
        return Prisms(self.axes[keep], self.ahead[keep], self.behind[keep])

    def overlap(self, points: np.ndarray, radii: np.ndarray, starts: np.ndarray, not_down=False):
        """How deep the convex shapes (each the hull of its run of `points`, from `starts`,
        grown by its radius) go into the prisms: the deepest shape and prism by the
        separating-axis test on the prisms' faces (at least as deep as they overlap;
        negative: apart by at least that much). Returns the depth, the shape, the direction
        that takes it out (the shortest way, or with `not_down` the shortest but down under
        the prism; a unit vector) and the index of the point that leads the way out."""
        projections, forward, backward, along, depth = self._depths(points, radii, starts)
        k, shape = np.unravel_index(np.argmax(depth), depth.shape)
        choice = along[k, :, shape].copy()
        if not_down:
            choice[self.axes[k, :, 2] < 0.0] = np.inf
        f = int(np.argmin(choice))
        stop = starts[shape + 1] if shape + 1 < len(starts) else len(points)
        run = projections[k, f, starts[shape] : stop]
        if forward[k, f, shape] <= backward[k, f, shape]:
            lead, axis = int(np.argmin(run)), self.axes[k, f]
        else:
            lead, axis = int(np.argmax(run)), -self.axes[k, f]
        return float(depth[k, shape]), int(shape), axis, starts[shape] + lead

    def deepest(self, points: np.ndarray, arm: Points) -> float:
        """`overlap`'s depth alone, of an arm's hull corners at `points`."""
        return float(self._depths(points, arm.radii_column, arm.starts)[-1].max())

    def _depths(self, points, radii, starts):
        """Projections on the axes, reaches past each face forward, backward and the lesser,
        and per prism and shape the least over the faces (the separating-axis depth)."""
        projections = np.einsum("kfj,nj->kfn", self.axes, points)
        low = np.minimum.reduceat(projections, starts, axis=2) - radii
        high = np.maximum.reduceat(projections, starts, axis=2) + radii
        forward = self.ahead[:, :, None] - low
        backward = high - self.behind[:, :, None]
        along = np.minimum(forward, backward)
        return projections, forward, backward, along, along.min(axis=1)


def _faces(piece):
    """A prism's face normals and its extents along them (forward, backward)."""
    coords = np.asarray(piece.outline.exterior.coords)[:-1]
    if not piece.outline.exterior.is_ccw:
        coords = coords[::-1]
    edges = np.roll(coords, -1, axis=0) - coords
    normals = np.column_stack([edges[:, 1], -edges[:, 0]])
    normals /= np.linalg.norm(normals, axis=1)[:, None]
    reach = normals @ coords.T
    axes = np.vstack([np.column_stack([normals, np.zeros(len(normals))]), [[0, 0, -1], [0, 0, 1]]])
    ahead = [*reach.max(axis=1), -piece.low, piece.high]
    behind = [*reach.min(axis=1), -piece.high, piece.low]
    return axes, np.array(ahead), np.array(behind)


@dataclass(frozen=True)
class ArmCheck:
    """One arm's points in the world at a pose, and how deep they go into the furniture."""

    depth: float
    frame: str
    point: np.ndarray
    """The deepest point, in its frame."""
    at: np.ndarray
    """The deepest point, in the world."""
    out: np.ndarray
    """Which way it gets out (a unit vector)."""


@lru_cache(maxsize=16)
def arm_frames(body: HumanBody, sides: tuple[str, ...]) -> tuple:
    """The plant frames of the `sides` arms' bodies, side by side (as `arm_points` has them)."""
    return tuple(body.plant.GetFrameByName(f) for s in sides for f in arm_points(body, s).frames)


def arms_in_world(body: HumanBody, q: np.ndarray, sides: tuple[str, ...]) -> dict:
    """The `sides` arms' hull corners in the world at q (n × 3), by one forward kinematics."""
    poses = body.world_poses(arm_frames(body, sides), body.plant_positions(q))
    world = {}
    for k, side in enumerate(sides):
        arm, points = poses[k * len(ARM) : (k + 1) * len(ARM)], arm_points(body, side).points
        world[side] = np.hstack([X @ local.T for X, local in zip(arm, points, strict=True)]).T
    return world


def check_arm(
    body: HumanBody, prisms: Prisms, q: np.ndarray, side: str, not_down: bool = False
) -> ArmCheck:
    """How deep the `side` arm goes into the prisms at q (its deepest shape), where, and how
    it gets out (as `Prisms.overlap`)."""
    arm = arm_points(body, side)
    world = arms_in_world(body, q, (side,))[side]
    depth, shape, out, k = prisms.overlap(world, arm.radii_column, arm.starts, not_down)
    return ArmCheck(depth, arm.frames[shape], arm.stacked[k], world[k], out)


def push_out(body: HumanBody, q: np.ndarray, side: str, check: ArmCheck, keep_hand: bool):
    """q with the `side` arm moved so that its deepest point is MARGIN clear of what it went
    into the way `check` says (with `keep_hand` the hand's grasp frame kept where it is but
    along that way, the world axis nearest it: a palm on a box's side may slide up off the
    board under it, never sideways into the box)."""
    target = check.at + (check.depth + MARGIN) * check.out
    tasks = [FrameTask(check.frame, target, point=tuple(check.point))]
    if keep_hand:
        X = body.frame_pose(f"{side}_hand_grasp", q)
        along = np.abs(check.out) == np.abs(check.out).max()
        weights = tuple(np.where(along, 0.0, HELD))
        tasks.append(
            FrameTask(f"{side}_hand_grasp", X.translation(), X.rotation(), weights, (1.0,) * 3)
        )
    return body.solve(
        q, tasks, arm_indices(body, (side,)), iterations=PUSH_STEPS, posture_weight=1e-3
    )


def clear_of(body: HumanBody, near: Prisms, q: np.ndarray, holding=()) -> np.ndarray | None:
    """q with both arms out of the prisms near it (None: they are clear as they are)."""
    moved = q
    for side in SIDES:
        for _ in range(PUSHES):
            held = side in holding
            check = check_arm(body, near, moved, side, not_down=not held)
            if check.depth <= _tolerance(side, holding):
                break
            moved = push_out(body, moved, side, check, held)
    return None if moved is q else moved


@dataclass(frozen=True, eq=False)
class ArmCorrection:
    """Joint offsets that keep the arms out of the furniture: at each key time an offset,
    minimum jerk from key to key, none before the first and after the last."""

    times: tuple[float, ...]
    offsets: tuple[np.ndarray, ...]

    def offset(self, t: float) -> np.ndarray | None:
        times = self.times
        if t < times[0] or t >= times[-1]:
            return None
        k = bisect_right(times, t) - 1
        s = minimum_jerk((t - times[k]) / (times[k + 1] - times[k]))
        return self.offsets[k] + s * (self.offsets[k + 1] - self.offsets[k])

    def over(self, q: np.ndarray, t: float) -> np.ndarray:
        offset = self.offset(t)
        return q if offset is None else q + offset


def arm_correction(body, furniture, pose, start, end, held, early=None):
    """The correction that keeps the arms out of the furniture while `pose(t)` is played from
    `start` to `end` (None: they keep clear as they are); it is nothing at `start` (it eases
    in after it) unless the arms are in the furniture there. `held(t)`: the sides whose
    hands must stay where they are (aimed or holding something). `early` (furniture, time):
    what the arms keep out of before that time instead (with what the hands take).

    The poses are checked every SAMPLE in turn; a correction found at one check is tried
    first at the next (it usually still holds), so that it changes smoothly and the arm is
    moved by IK only where it would go in further. Then the corrected poses are checked
    twice as often near the corrections, and corrected again where they need it, until they
    need no more (at most VERIFICATIONS times)."""
    late = Prisms.of(furniture)
    first = (Prisms.of(early[0]), early[1]) if early is not None else (late, start)
    if len(first[0].axes) == 0 and len(late.axes) == 0:
        return None

    def near_at(t, q) -> Prisms:
        return (first[0] if t < first[1] else late).near(q[:2], NEAR)

    moved, offset = {}, None
    for t in np.arange(start, end + SAMPLE / 2, SAMPLE):
        q, holding = pose(float(t)), held(float(t))
        near = near_at(t, q)
        if len(near.axes) == 0 or _clear(body, near, q, holding):
            offset = None
            continue
        tried = q if offset is None else _keeping_held_hands(body, near, q, q + offset, holding)
        if tried is q or not _clear(body, near, tried, holding):
            cleared = clear_of(body, near, tried, holding)
            tried = cleared if cleared is not None else tried
        offset = tried - q
        moved[float(t)] = offset
    if not moved:
        return None
    for _ in range(VERIFICATIONS):
        correction, added = _correction(moved, start), False
        for t in _near(sorted(moved), start, end):
            q, holding = pose(t), held(t)
            near = near_at(t, q)
            eased = correction.over(q, t)
            corrected = _keeping_held_hands(body, near, q, eased, holding)
            if corrected is not eased or not _clear(body, near, corrected, holding):
                cleared = clear_of(body, near, corrected, holding)
                moved[t], added = (cleared if cleared is not None else corrected) - q, True
        if not added:
            return correction
    return _correction(moved, start)


def _keeping_held_hands(body, near, q, corrected, holding):
    """`corrected` with the arms of held hands it would move off their places further than
    they must go to get out of what q puts them in (at least HAND_SHIFT) brought back
    towards q until it moves them that far: a correction found while a hand was free must
    not carry it away from what it then takes or holds."""
    kept = corrected
    for side in holding:
        allowed = max(HAND_SHIFT, check_arm(body, near, q, side).depth + MARGIN)
        kept = _arm_pulled_back(body, q, kept, side, allowed)
    return kept


def _arm_pulled_back(body, q, corrected, side: str, allowed: float):
    """`corrected` with the `side` arm's offset from q scaled down (by bisection) until its
    hand is at most `allowed` from where q has it."""
    arm, frame = arm_indices(body, (side,)), f"{side}_hand_grasp"
    place = body.frame_pose(frame, q).translation()

    def scaled(scale):
        pose = corrected.copy()
        pose[arm] = q[arm] + scale * (corrected[arm] - q[arm])
        return pose

    def within(pose) -> bool:
        return np.linalg.norm(body.frame_pose(frame, pose).translation() - place) <= allowed

    if within(corrected):
        return corrected
    low, high = 0.0, 1.0
    for _ in range(SHIFT_SEARCH):
        middle = (low + high) / 2
        low, high = (middle, high) if within(scaled(middle)) else (low, middle)
    return scaled(low)


def _near(times: list, start: float, end: float) -> list:
    """The instants every half SAMPLE within EASE of a corrected one (where the eased
    correction may fall short, or move an arm into what it was clear of)."""
    instants = np.arange(start, end + SAMPLE / 4, SAMPLE / 2)
    corrected = np.array(times)
    near = np.min(np.abs(instants[:, None] - corrected[None, :]), axis=1) <= EASE
    return [float(t) for t in instants[near]]


def _correction(moved: dict, start: float) -> ArmCorrection:
    keys = _eased(sorted(moved.items()), start)
    return ArmCorrection(tuple(t for t, _ in keys), tuple(o for _, o in keys))


def _clear(body, prisms: Prisms, q, holding) -> bool:
    arms = arms_in_world(body, q, SIDES)
    return all(
        prisms.deepest(arms[s], arm_points(body, s)) <= _tolerance(s, holding) for s in SIDES
    )


def _tolerance(side: str, holding) -> float:
    return HELD_TOLERANCE if side in holding else TOLERANCE


def _eased(corrected, start: float):
    """Keys for (time, offset) corrections at checked times: zero EASE before each run of
    them (not before `start`) and EASE after (runs closer than that are joined)."""
    zero = np.zeros_like(corrected[0][1])
    first = corrected[0][0]
    keys = [(max(first - EASE, start), zero)] if first > start else []
    for (t, offset), following in zip(corrected, [*corrected[1:], None], strict=True):
        keys.append((t, offset))
        if following is None or following[0] - t > 2 * EASE:
            keys.append((t + EASE, zero))
            if following is not None:
                keys.append((following[0] - EASE, zero))
    return keys
