"""The safety monitor's numerics as compiled kernels over plain arrays (numba).

A measurement works on a few dozen small arrays: as numpy calls it cost ~70 calls of 3-5 us
each, not arithmetic; `kinematics` does all of it past the pose lookups in one call.

Every kernel is `@njit(cache=True)`: numba compiles them at their first call (~8 s CPU for
all, once) and with `cache=True` writes the machine code to `__pycache__`, so a later
process (a sweep worker, a test worker, the next run) loads it instead (~0.2 s, besides
~0.25 s importing numba). No `fastmath`: IEEE arithmetic in the order written here."""

import math

import numpy as np
from numba import njit

EPS = 1e-12


@njit(cache=True)
def kinematics(
    poses,
    times,
    previous,
    person_rates,
    reference_ends,
    reference_gaps,
    time,
    person_time,
    robot_frames,
    human_frames,
    parts,
    part_frames,
    ends_F,
    robot,
    radii,
    refresh_distance,
):
    """A measurement's numerics past the pose lookups, in one call (plain arrays: a tuple
    argument would cost numba's slow typing path at every call).

    `poses`: the frames' world poses (frames × 3 × 4, NaN for inactive ones); `times` to
    `reference_gaps`: the last reading's memory (see `_remembered`); `robot_frames`,
    `human_frames`: the active robot frames, the person's; `parts`: the active parts (the
    person's first), `part_frames` their frames, `ends_F` their segment ends in them;
    `robot`: the active robot parts' columns among all gaps; `radii`: the radii sums
    (person's parts × active robot parts).

    Returns the frames' pose rates, the active parts' world segment ends (parts × 3 × 2),
    the distances' lower bounds, the reading's memory, and the robot's speed (its fastest
    segment end).
    """
    dt, person_dt = time - times[0], person_time - times[1]
    rates = _pose_rates(poses, previous, person_rates, robot_frames, human_frames, dt, person_dt)
    ends = _transformed_ends(poses, part_frames, ends_F)
    bounds, all_ends, all_gaps = _capsule_bounds(
        ends, reference_ends, reference_gaps, parts, robot, radii, refresh_distance
    )
    n = radii.shape[0]
    robot_speed = _fastest_end(rates, part_frames[n:], ends_F[n:])
    memory = _remembered(time, person_time, poses, rates, human_frames, all_ends, all_gaps)
    return rates, ends, bounds, memory, robot_speed


@njit(cache=True)
def _remembered(time, person_time, poses, rates, human_frames, ends, gaps):
    """The memory vector: the times, the poses, the person's frames' rates, the parts' ends
    and the gaps (what `kinematics` recalls next time)."""
    pieces = (poses.ravel(), rates[human_frames].ravel(), ends.ravel(), gaps.ravel())
    memory = np.empty(2 + sum([piece.size for piece in pieces]))
    memory[0], memory[1] = time, person_time
    start = 2
    for piece in pieces:
        memory[start : start + piece.size] = piece
        start += piece.size
    return memory


@njit(cache=True)
def segment_distances(a_start, a_dir, b_start, b_dir):
    """Distances between every segment a (n, 3) and every segment b (m, 3): an (n, m) array.

    Segment a_i is p_i + s u_i and b_j is q_j + t w_j, s and t in [0, 1]: Ericson,
    Real-Time Collision Detection, 5.1.9; a point segment (|u| or |w| ~ 0) keeps its start.
    """
    n, m = a_start.shape[0], b_start.shape[0]
    distances = np.empty((n, m))
    r = np.empty(3)
    for i in range(n):
        u = a_dir[i]
        a = _dot(u, u)
        for j in range(m):
            w = b_dir[j]
            for k in range(3):
                r[k] = a_start[i, k] - b_start[j, k]
            e, b = _dot(w, w), _dot(u, w)
            c, f = _dot(u, r), _dot(w, r)
            denom = a * e - b * b
            s = _unit_clamp((b * f - c * e) / denom) if denom > EPS else 0.0
            t = _unit_clamp((b * s + f) / e) if e > EPS else 0.0
            s = _unit_clamp((b * t - c) / a) if a > EPS else 0.0
            squared = 0.0
            for k in range(3):
                gap = r[k] + s * u[k] - t * w[k]
                squared += gap * gap
            distances[i, j] = math.sqrt(squared)
    return distances


@njit(cache=True)
def _transformed_ends(poses, part_frames, ends_F):
    """Each part's frame pose (frames × 3 × 4, or its rate) applied to the part's segment
    ends in that frame (parts × 4 × 2, homogeneous columns): world ends (or their
    velocities), parts × 3 × 2."""
    ends = np.empty((part_frames.shape[0], 3, 2))
    for k in range(part_frames.shape[0]):
        X = poses[part_frames[k]]
        for row in range(3):
            for end in range(2):
                ends[k, row, end] = (
                    X[row, 0] * ends_F[k, 0, end]
                    + X[row, 1] * ends_F[k, 1, end]
                    + X[row, 2] * ends_F[k, 2, end]
                    + X[row, 3] * ends_F[k, 3, end]
                )
    return ends


@njit(cache=True)
def _fastest_end(rates, part_frames, ends_F):
    """Speed of the fastest end of the parts' segments, from their frames' pose rates."""
    velocities = _transformed_ends(rates, part_frames, ends_F)
    fastest = 0.0
    for k in range(velocities.shape[0]):
        for end in range(2):
            fastest = max(fastest, _dot(velocities[k, :, end], velocities[k, :, end]))
    return math.sqrt(fastest)


@njit(cache=True)
def _pose_rates(poses, previous, person_rates, robot_frames, human_frames, dt, person_dt):
    """Rates of change (frames × 3 × 4) of the robot's frames over `dt` (zero for a frame
    not measured before: NaN in `previous`; all zero unless dt > 0), and of the person's
    over `person_dt` (their `person_rates`, one per human frame, unless person_dt > 0)."""
    rates = np.zeros_like(poses)
    if dt > 0.0:
        for f in robot_frames:
            for row in range(3):
                for col in range(4):
                    before = previous[f, row, col]
                    if not math.isnan(before):
                        rates[f, row, col] = (poses[f, row, col] - before) / dt
    for h in range(human_frames.shape[0]):
        f = human_frames[h]
        if person_dt > 0.0:
            rates[f] = (poses[f] - previous[f]) / person_dt
        else:
            rates[f] = person_rates[h]
    return rates


@njit(cache=True)
def _capsule_bounds(ends, reference_ends, reference_gaps, parts, robot, radii, refresh_distance):
    """Lower bounds (human × active robot parts) of the distances, from the gaps between
    the bounding segments (`ends`: the active `parts`' world ends, the person's first), and
    the gaps' reference (all parts' ends, gaps of all pairs, NaN where not computed): the
    reference's gaps less how far each part moved, while no active part moved farther than
    `refresh_distance` (or was not measured then); else fresh gaps, the new reference."""
    n, columns = radii.shape
    moved = np.empty(len(parts))
    for p in range(len(parts)):
        moved[p] = max(
            _distance(ends[p, :, 0], reference_ends[parts[p], :, 0]),
            _distance(ends[p, :, 1], reference_ends[parts[p], :, 1]),
        )
    # NaN for a part not measured then (both its ends are NaN): then False
    if np.all(moved <= refresh_distance):
        bounds = np.empty((n, columns))
        for i in range(n):
            for j in range(columns):
                gap = reference_gaps[i, robot[j]] - moved[i] - moved[n + j]
                bounds[i, j] = gap - radii[i, j]
        return bounds, reference_ends.copy(), reference_gaps.copy()
    starts, spans = ends[:, :, 0], ends[:, :, 1] - ends[:, :, 0]
    gaps = segment_distances(starts[:n], spans[:n], starts[n:], spans[n:])
    all_ends = np.full(reference_ends.shape, np.nan)
    all_gaps = np.full(reference_gaps.shape, np.nan)
    for p in range(len(parts)):
        all_ends[parts[p]] = ends[p]
    for j in range(columns):
        all_gaps[:, robot[j]] = gaps[:, j]
    return gaps - radii, all_ends, all_gaps


@njit(cache=True)
def witness_motion(X_FG, part_frame, poses, rates, human, robot, p_GH, p_GR, normal):
    """Of the witness points `p_GH` of geometry `human` and `p_GR` of geometry `robot`
    (fixed in them; `X_FG`: every geometry's pose in its frame `part_frame`; `poses`,
    `rates`: the frames' world poses and their rates), the robot's speed along `normal`,
    the person's against it, and the person's point in the world."""
    p_FH, p_FR = _applied(X_FG[human], p_GH), _applied(X_FG[robot], p_GR)
    robot_approach = _dot(_applied(rates[part_frame[robot]], p_FR), normal)
    human_approach = -_dot(_applied(rates[part_frame[human]], p_FH), normal)
    return robot_approach, human_approach, _applied(poses[part_frame[human]], p_FH)


@njit(cache=True)
def _applied(X, p):
    """X[:, :3] p + X[:, 3] (a 3 × 4 pose, or its rate, applied to a point)."""
    out = np.empty(3)
    for row in range(3):
        out[row] = X[row, 0] * p[0] + X[row, 1] * p[1] + X[row, 2] * p[2] + X[row, 3]
    return out


@njit(cache=True)
def _dot(u, v):
    return u[0] * v[0] + u[1] * v[1] + u[2] * v[2]


@njit(cache=True)
def _distance(p, q):
    """|p - q|; NaN where either is."""
    return math.sqrt((p[0] - q[0]) ** 2 + (p[1] - q[1]) ** 2 + (p[2] - q[2]) ** 2)


@njit(cache=True)
def _unit_clamp(x):
    return min(max(x, 0.0), 1.0)
