"""Feet that stay where they stand: the planned pose's legs corrected so that a sole on the
floor does not slide.

Clips plant their feet, but joining them does not: a fade from a stride into standing, a
turn whose heading eases differently from its authored steps, a walk round a corner all
move the planned feet along the floor. Each update, every sole point (heel, toe) that the
plan puts on the floor keeps the place where it touched down, and the leg is solved by IK
to keep it there (animators call this foot locking). A foot whose planned place has moved
further than `STEP_AFTER` from where it stands steps there: it lifts and moves in
`STEP_TIME`. A foot that leaves the floor lets its correction fade out in `RELEASE_FADE`.
"""

from dataclasses import dataclass, field, replace
from math import pi, sin

import numpy as np

from hrc_drake.human.authoring import leg_indices, minimum_jerk
from hrc_drake.human.body import FrameTask, HumanBody
from hrc_drake.human.skeleton import SIDES

CONTACT_HEIGHT = 0.001
"""m: a planned sole point this close to the floor stands on it."""
STEP_AFTER = 0.03
"""m: a standing foot this far from its planned place steps there."""
STEP_TIME = 0.45
STEP_LIFT = 0.04
RELEASE_FADE = 0.25
SETTLED = 1e-4
"""m: anchors this close to the plan need no correction."""
KNEE_SEED = 0.15
"""rad: the IK starts a straight knee this bent (a straight knee is singular: it would stay
straight however far the foot has to rise)."""
POINTS = {"heel": -1.0, "toe": 1.0}
"""Sole points, as a multiple of half the foot's length along the sole frame's x."""


@dataclass(frozen=True)
class Foot:
    """One foot's footing: its anchored sole points, or the step it takes, and the leg
    correction it had when it let go (fading out)."""

    anchors: dict[str, tuple[float, float]] = field(default_factory=dict)
    step_start: float | None = None
    step_from: dict[str, tuple[float, float, float]] = field(default_factory=dict)
    """Where each sole point was when the step began."""
    correction: np.ndarray | None = None
    released: float = 0.0


@dataclass(frozen=True)
class Footing:
    """Both feet, and the pelvis height correction that let them reach the floor (fading
    out from when it was last needed)."""

    feet: tuple[Foot, Foot] = (Foot(), Foot())
    pelvis: float = 0.0
    pelvis_set: float = 0.0


NO_FOOTING = Footing()
REACH_ERROR = 0.003
"""m: feet further than this from their targets with the pelvis where the plan has it let
the pelvis lower (or rise) too: the plan asks the legs for more than they can reach."""


def _sole_points(body: HumanBody, q: np.ndarray) -> dict[str, dict[str, np.ndarray]]:
    points = body.sole_points(q)
    return {side: {p: points[f"{side}_{p}"] for p in POINTS} for side in SIDES}


def _faded(correction, since: float, t: float):
    return (1.0 - minimum_jerk((t - since) / RELEASE_FADE)) * correction


def planted(
    body: HumanBody, footing: Footing, q: np.ndarray, previous: np.ndarray | None, t: float
) -> tuple[np.ndarray, Footing]:
    """The planned pose `q` with its legs corrected, and the footing after this update.

    `previous` is the pose at the last update (None at the first). Whether a sole point
    stands on the floor is judged on the pose as shown (the corrections so far), where it
    should go on the plan."""
    height = body.index("pelvis_height")
    shown = q.copy()
    shown[height] += _faded(footing.pelvis, footing.pelvis_set, t)
    for side, foot in zip(SIDES, footing.feet, strict=True):
        legs = leg_indices(body, side)
        if previous is not None and (foot.anchors or foot.step_start is not None):
            shown[legs] = previous[legs]
        elif foot.correction is not None:
            shown[legs] += _faded(foot.correction, foot.released, t)
    planned, standing = _sole_points(body, q), _sole_points(body, shown)
    feet, targets = [], {}
    stepping = [foot.step_start is not None for foot in footing.feet]
    for k, (side, foot) in enumerate(zip(SIDES, footing.feet, strict=True)):
        foot, targets[side] = _footing(foot, standing[side], planned[side], t, stepping[1 - k])
        stepping[k] = foot.step_start is not None
        feet.append(foot)
    for side, foot in zip(SIDES, feet, strict=True):
        if not targets[side]:  # the plan's legs, with what is left of a correction
            legs = leg_indices(body, side)
            shown[legs] = q[legs]
            if foot.correction is not None:
                shown[legs] += _faded(foot.correction, foot.released, t)
    aimed = [side for side in SIDES if targets[side]]
    if not aimed:
        return shown, replace(footing, feet=(feet[0], feet[1]))
    solved, pelvis_moved = _solve_legs(body, shown, targets, aimed)
    for k, side in enumerate(SIDES):
        if side in aimed:
            legs = leg_indices(body, side)
            feet[k] = _holding(feet[k], solved[legs] - q[legs], t)
    footing = Footing((feet[0], feet[1]), footing.pelvis, footing.pelvis_set)
    if pelvis_moved:
        footing = replace(footing, pelvis=float(solved[height] - q[height]), pelvis_set=t)
    return solved, footing


def _footing(foot: Foot, standing: dict, planned: dict, t: float, other_steps: bool):
    """The foot's next footing and its sole points' targets ({} when the plan is right):
    `standing` are its sole points as shown, `planned` where the plan puts them."""
    if foot.step_start is not None:
        s = (t - foot.step_start) / STEP_TIME
        if s < 1.0:
            return foot, _step_targets(foot, planned, s)
        foot = Foot(correction=foot.correction, released=foot.released)
    on_floor = {  # an anchored point stays until the plan lifts it; a free one lands as shown
        p: xyz
        for p, xyz in standing.items()
        if (planned[p] if p in foot.anchors else xyz)[2] <= CONTACT_HEIGHT
    }
    anchors = {
        p: foot.anchors.get(p, (float(xyz[0]), float(xyz[1]))) for p, xyz in on_floor.items()
    }
    away = max((np.hypot(*(planned[p][:2] - a)) for p, a in anchors.items()), default=0.0)
    if away > STEP_AFTER and not other_steps:
        start = {p: tuple(map(float, xyz)) for p, xyz in standing.items()}
        foot = Foot(step_start=t, step_from=start, correction=foot.correction, released=t)
        return foot, _step_targets(foot, planned, 0.0)
    foot = Foot(
        anchors, correction=foot.correction if not anchors else None, released=foot.released
    )
    if away <= SETTLED:
        return foot, {}
    return foot, {p: np.array([*a, 0.0]) for p, a in anchors.items()}


def _step_targets(foot: Foot, planned: dict, s: float) -> dict:
    """Sole points on the way from where the foot stood to its planned place, lifted."""
    w = minimum_jerk(s)
    lift = STEP_LIFT * sin(pi * s) ** 2  # eases off the floor: a straight knee bends slowly
    targets = {}
    for p, xyz in planned.items():
        start = np.array(foot.step_from[p])
        end = np.array([*xyz[:2], max(xyz[2], 0.0)])
        targets[p] = start + w * (end - start) + [0.0, 0.0, lift]
    return targets


def _holding(foot: Foot, correction: np.ndarray, t: float) -> Foot:
    """The foot keeps its latest correction, to fade out from when it lets go."""
    return Foot(foot.anchors, foot.step_start, foot.step_from, correction, t)


def _solve_legs(body: HumanBody, q, targets: dict, sides) -> tuple[np.ndarray, bool]:
    """Legs of `sides` solved for their sole points' targets; the pelvis height joins in
    only when the legs alone cannot reach. Returns the pose and whether the pelvis moved."""
    half = body.sizes["foot"] / 2
    tasks = [
        FrameTask(f"{side}_sole", target, point=(POINTS[p] * half, 0.0, 0.0))
        for side in sides
        for p, target in targets[side].items()
    ]
    start = q.copy()
    for side in sides:
        knee = body.index(f"{side}_knee_flexion")
        start[knee] = max(start[knee], KNEE_SEED)
    legs = np.concatenate([leg_indices(body, side) for side in sides])
    solved = body.solve(start, tasks, legs, iterations=10, posture_weight=1e-4, tolerance=1e-4)
    if body.task_error(solved, tasks) <= REACH_ERROR:
        return solved, False
    free = np.append(legs, body.index("pelvis_height"))
    return body.solve(solved, tasks, free, iterations=10, posture_weight=1e-4), True
