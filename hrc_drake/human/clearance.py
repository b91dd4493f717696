"""The arms clear of the furniture: a motion planned next to a table is checked against the
cell's geometry before it is played, and where an arm would go into it, that arm is moved
out by inverse kinematics; the correction eases in and out around it.

A clip is authored in an empty room: an arm swinging by a walker's side, the free arm of a
person leaning over a table to reach with the other, a forearm turning an object in front of
the belly. Played next to furniture, such an arm may pass through its top. The check samples
the planned poses and measures how deep each of an arm's collision shapes (the capsules of
the upper arm and forearm, the hand's box) goes into the cell's prisms
(hrc_drake.human.furniture), with the separating-axis test on the prisms' faces
(hrc_drake.human.arm_shapes). An arm
that goes in is pushed out by a little more, the shortest way: up off a table's top, or
back off its edge (a hanging arm is not lifted onto a table); a free arm never down under
it. A hand that is aimed at something or holds it is kept where it is. The corrections are
an `ArmCorrection`: joint offsets at the checked instants, eased in and out.
"""

from bisect import bisect_right
from dataclasses import dataclass

import numpy as np

from hrc_drake.human.arm_shapes import (
    ArmCheck,
    Prisms,
    check_arm,
    corners_in_world,
    parts_shapes,
)
from hrc_drake.human.body import FrameTask, HumanBody
from hrc_drake.human.grasp import arm_indices
from hrc_drake.human.keyed_clips import minimum_jerk
from hrc_drake.human.skeleton import SIDES

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


def push_out(body: HumanBody, q: np.ndarray, side: str, check: ArmCheck, keep_hand: bool):
    """q with the `side` arm moved so that its deepest point is MARGIN clear of what it went
    into the way `check` says (with `keep_hand` the hand's grasp frame kept where it is, but
    for rising when the way out is up: a palm on a box's side may slide up off the board
    under it, never sideways into the box or down into what the box is lowered onto; freed
    along a forearm's way down off a board above, the hands holding a tote rose 2.3 cm and
    it went 5 cm into the board, freed along the way back, they drew it 7 cm out of its
    place)."""
    target = check.at + (check.depth + MARGIN) * check.out
    tasks = [FrameTask(check.frame, target, point=tuple(check.point))]
    if keep_hand:
        X = body.frame_pose(f"{side}_hand_grasp", q)
        rising = int(np.argmax(np.abs(check.out))) == 2 and check.out[2] > 0
        weights = (*HELD[:2], 0.0) if rising else HELD
        tasks.append(
            FrameTask(f"{side}_hand_grasp", X.translation(), X.rotation(), weights, (1.0,) * 3)
        )
    return body.solve(
        q, tasks, arm_indices(body, (side,)), iterations=PUSH_STEPS, posture_weight=1e-3
    )


def clear_of(body: HumanBody, near: Prisms, q: np.ndarray, holding=()) -> np.ndarray | None:
    """q with both arms out of the prisms near it (None: they are clear as they are)."""
    moved = q
    for _ in range(PUSHES):
        pushed = moved
        for side in SIDES:
            held = side in holding
            check = (
                _held_check(body, near, moved, side)
                if held
                else check_arm(body, near, moved, side, not_down=True)
            )
            if check.depth > _tolerance(side, holding):
                before, moved = moved, push_out(body, moved, side, check, held)
                if len(holding) == len(SIDES):
                    moved = _following(body, before, moved, side)
        if moved is pushed:
            break
    return None if moved is q else moved


def _following(body: HumanBody, before: np.ndarray, moved: np.ndarray, side: str) -> np.ndarray:
    """`moved` with the other hand moved as the `side` hand was from `before`: two hands
    that hold one object between their palms move it together (the object's heading is the
    line between them: one moving alone turns it, into the other palm)."""
    (other,) = (s for s in SIDES if s != side)
    shift = (
        body.frame_pose(f"{side}_hand_grasp", moved).translation()
        - body.frame_pose(f"{side}_hand_grasp", before).translation()
    )
    X = body.frame_pose(f"{other}_hand_grasp", moved)
    task = FrameTask(f"{other}_hand_grasp", X.translation() + shift, X.rotation(), HELD, (1.0,) * 3)
    return body.solve(moved, [task], arm_indices(body, (other,)), iterations=PUSH_STEPS)


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


def instants(start: float, end: float, step: float = SAMPLE) -> np.ndarray:
    """start, start + step, ... to `end` (within half a step), each start + k step: those of
    half the step fall exactly on these, wherever `start` is. (np.arange steps by
    (start + step) - start, not step: from t = 0.5 its half-step instants missed these by
    1e-16, a correction checked again there was keyed beside the first one, not over it,
    and a put-down onto a flow rack's 1.4 m board that `validate`, planning it at t = 0,
    found 1.2 cm in, the run refused at 3.2 cm in, depending on the time it came.)"""
    return start + step * np.arange(int(np.floor((end - start) / step + 0.5)) + 1)


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
    need no more (at most VERIFICATIONS times). The poses of each pass are checked all at
    once (`_Keep.clear`) and only those that go in are taken in turn."""
    keep = _Keep.of(furniture, start, early)
    if keep is None:
        return None
    times = [float(t) for t in instants(start, end)]
    poses, holdings = [pose(t) for t in times], [held(t) for t in times]
    moved, offset = {}, None
    for t, q, holding, clear in zip(
        times, poses, holdings, keep.clear(body, times, poses, holdings), strict=True
    ):
        if clear:
            offset = None
            continue
        near = keep.near(t, q)
        tried = q if offset is None else _keeping_held_hands(body, near, q, q + offset, holding)
        if tried is q or not keep.clear(body, [t], [q], [holding], [tried])[0]:
            cleared = clear_of(body, near, tried, holding)
            tried = cleared if cleared is not None else tried
        offset = tried - q
        moved[t] = offset
    if not moved:
        return None
    for _ in range(VERIFICATIONS):
        correction = _correction(moved, start)
        times = _near(sorted(moved), start, end)
        poses, holdings = [pose(t) for t in times], [held(t) for t in times]
        eased = [correction.over(q, t) for t, q in zip(times, poses, strict=True)]
        kept = [
            _keeping_held_hands(body, keep.near(t, q), q, e, h) if h else e
            for t, q, e, h in zip(times, poses, eased, holdings, strict=True)
        ]
        clear = keep.clear(body, times, poses, holdings, kept)
        added = False
        for t, q, e, k, holding, ok in zip(times, poses, eased, kept, holdings, clear, strict=True):
            if k is not e or not ok:
                cleared = clear_of(body, keep.near(t, q), k, holding)
                moved[t], added = (cleared if cleared is not None else k) - q, True
        if not added:
            return correction
    return _correction(moved, start)


@dataclass(frozen=True)
class _Keep:
    """What the arms keep out of: the `early` prisms before `until`, the `late` ones after."""

    early: Prisms
    until: float
    late: Prisms

    @classmethod
    def of(cls, furniture, start: float, early) -> "_Keep | None":
        """For `arm_correction`'s arguments (None: there is nothing to keep out of)."""
        late = Prisms.of(furniture)
        keep = (
            cls(Prisms.of(early[0]), early[1], late)
            if early is not None
            else cls(late, start, late)
        )
        return None if len(keep.early.axes) == 0 and len(keep.late.axes) == 0 else keep

    def at(self, t: float) -> Prisms:
        return self.early if t < self.until else self.late

    def near(self, t: float, q: np.ndarray) -> Prisms:
        """The prisms at t within NEAR of the pelvis of q."""
        return self.at(t).near(q[:2], NEAR)

    def clear(self, body, times, poses, holdings, arms=None) -> np.ndarray:
        """Whether the arms are out of the prisms near each pose (within TOLERANCE of them,
        or HELD_TOLERANCE for a hand that holds), with the arms of `arms` (poses with the
        same pelvis; default `poses`): one forward kinematics per pose, the depths of all
        at once."""
        corners = corners_in_world(body, poses if arms is None else arms, SIDES)
        radii, shapes, sides = parts_shapes(body, SIDES)
        tolerances = np.array([[_tolerance(s, holding) for s in SIDES] for holding in holdings])
        clear = np.ones(len(times), dtype=bool)
        early = np.array(times) < self.until
        for prisms, chosen in ((self.early, early), (self.late, ~early)):
            xy = np.array(poses)[chosen, :2]
            deepest = prisms.deepest_near(xy, NEAR, corners[chosen], radii, shapes)
            per_side = np.maximum.reduceat(deepest, sides, axis=1)
            clear[chosen] = (per_side <= tolerances[chosen]).all(axis=1)
        return clear


def _keeping_held_hands(body, near, q, corrected, holding):
    """`corrected` with the arms of held hands it would move off their places further than
    they must go to get out of what q puts them in (at least HAND_SHIFT) brought back
    towards q until it moves them that far: a correction found while a hand was free must
    not carry it away from what it then takes or holds."""
    allowed = {
        side: max(HAND_SHIFT, _held_check(body, near, q, side).depth + MARGIN) for side in holding
    }
    return _arms_pulled_back(body, q, corrected, allowed)


def _held_check(body: HumanBody, near: Prisms, q: np.ndarray, side: str) -> ArmCheck:
    """How the arm of a holding or aimed hand at q gets out of the prisms: along its palm's
    face, never across it (off the face, the palm leaves what it holds)."""
    palm = body.frame_pose(f"{side}_hand_grasp", q).rotation().matrix()[:, 1]
    return check_arm(body, near, q, side, not_along=palm)


def _arms_pulled_back(body, q, corrected, allowed: dict):
    """`corrected` with the offsets from q of the arms of `allowed`'s sides scaled down, by
    one factor (by bisection), until each hand is at most its `allowed` distance from where
    q has it (one factor: two hands that hold one object stay where they are on it)."""
    arms = arm_indices(body, tuple(allowed))
    places = {side: body.frame_pose(f"{side}_hand_grasp", q).translation() for side in allowed}

    def scaled(scale):
        pose = corrected.copy()
        pose[arms] = q[arms] + scale * (corrected[arms] - q[arms])
        return pose

    def within(pose) -> bool:
        return all(
            np.linalg.norm(body.frame_pose(f"{side}_hand_grasp", pose).translation() - place)
            <= allowed[side]
            for side, place in places.items()
        )

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
    every = instants(start, end, SAMPLE / 2)
    corrected = np.array(times)
    near = np.min(np.abs(every[:, None] - corrected[None, :]), axis=1) <= EASE
    return [float(t) for t in every[near]]


def _correction(moved: dict, start: float) -> ArmCorrection:
    keys = _eased(sorted(moved.items()), start)
    return ArmCorrection(tuple(t for t, _ in keys), tuple(o for _, o in keys))


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
