"""The legs in closed form: put a sole where it stands, whatever the pelvis does.

A leg has five joints (hip flexion, abduction and rotation, knee, ankle): enough to put the
sole frame at a point with the foot pointing along a given direction (its roll follows).
`Legs.solve` does that without iterating: the knee angle from the hip-ankle distance, the
hip's rotation from the plane that leg and foot span, the ankle from the foot's pitch in
that plane. It is a few small matrix products, so the person can plant feet while walking
round corners, stepping and blending at every update (a Jacobian IK costs ~50 times more).

Conventions (hrc_drake.human.skeleton): the pelvis is posed by base_x, base_y, base_yaw,
pelvis_height (the hip joints' midpoint above the floor), pelvis_tilt (about y) and
pelvis_list (about x); each hip is half the hip width to the side; flexion turns about -y,
abduction about x (-x on the right) and rotation about -z (+z on the right); the knee turns
about y, the ankle about -y.

Longer than 400 lines: the solve and the legs' forward kinematics are written out in plain
floats (a walking pose calls them dozens of times; small numpy arrays cost 1.7x more,
benchmarks/human_update.py), and they share the conventions above.
"""

from dataclasses import dataclass
from functools import lru_cache
from math import acos, asin, atan2, cos, pi, sin, sqrt
from struct import pack

import numpy as np

from hrc_drake.human.rotations import wrap_angle
from hrc_drake.human.skeleton import SIDES

LEG_JOINTS = ("hip_flexion", "hip_abduction", "hip_rotation", "knee_flexion", "ankle_flexion")
FLOOR_CONTACT = 1e-3
"""m: a sole point this close to the floor stands on it."""
ROLL_TOLERANCE = 0.01
"""Sine of the pitch by which a foot rolling over its toe may still point its toe up (and
one rolling over its heel its toe down): it stands flat, give or take rounding."""
STRAIGHTEST_KNEE = 0.02
"""rad: the knee never quite locks (a straight knee is singular)."""


def rotation_y(a: float) -> np.ndarray:
    return np.array(_rows_y(a))


def _floats(v) -> tuple[float, ...]:
    return tuple(map(float, v))


def _unit(v: np.ndarray) -> np.ndarray:
    return v / sqrt(float(v @ v))


# The closed-form solve and the legs' forward kinematics run a few times per foot at every
# update of a walking person: their 3-vectors and 3 × 3 rotations are plain tuples of floats
# (rows for a matrix), which Python multiplies several times faster than numpy does arrays
# this small (and the same on every machine: no BLAS kernel rounds them its own way).


def _crossed(a, b) -> tuple[float, float, float]:
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def _unit_of(v) -> tuple[float, float, float]:
    x, y, z = v
    length = sqrt(x * x + y * y + z * z)
    return (x / length, y / length, z / length)


def _level_up(forward) -> tuple[float, float, float]:
    """The up axis of a foot along the unit `forward` that does not roll: the world's up
    less its part along the foot."""
    x, y, z = forward
    return _unit_of((-z * x, -z * y, 1.0 - z * z))


def _times(R, v) -> tuple[float, float, float]:
    """R @ v."""
    (a, b, c), (d, e, f), (g, h, i) = R
    x, y, z = v
    return (a * x + b * y + c * z, d * x + e * y + f * z, g * x + h * y + i * z)


def _transposed_times(R, v) -> tuple[float, float, float]:
    """R.T @ v."""
    (a, b, c), (d, e, f), (g, h, i) = R
    x, y, z = v
    return (a * x + d * y + g * z, b * x + e * y + h * z, c * x + f * y + i * z)


def _product(A, B) -> tuple:
    """A @ B, row by row (each row `_transposed_times(B, row)`, written out)."""
    (a, b, c), (d, e, f), (g, h, i) = B
    (x0, y0, z0), (x1, y1, z1), (x2, y2, z2) = A
    return (
        (a * x0 + d * y0 + g * z0, b * x0 + e * y0 + h * z0, c * x0 + f * y0 + i * z0),
        (a * x1 + d * y1 + g * z1, b * x1 + e * y1 + h * z1, c * x1 + f * y1 + i * z1),
        (a * x2 + d * y2 + g * z2, b * x2 + e * y2 + h * z2, c * x2 + f * y2 + i * z2),
    )


def _rows_x(a: float) -> tuple:
    c, s = cos(a), sin(a)
    return ((1.0, 0.0, 0.0), (0.0, c, -s), (0.0, s, c))


def _rows_y(a: float) -> tuple:
    c, s = cos(a), sin(a)
    return ((c, 0.0, s), (0.0, 1.0, 0.0), (-s, 0.0, c))


def _rows_z(a: float) -> tuple:
    c, s = cos(a), sin(a)
    return ((c, -s, 0.0), (s, c, 0.0), (0.0, 0.0, 1.0))


@dataclass(frozen=True)
class SolePose:
    """Where a sole frame is: its origin and the foot's forward and up axes (world)."""

    position: np.ndarray
    forward: np.ndarray
    up: np.ndarray

    def point(self, along: float) -> np.ndarray:
        """The sole's point `along` metres ahead of its origin (heel < 0 < toe)."""
        return self.position + along * self.forward


class Legs:
    """Forward and closed-form inverse kinematics of both legs of one body."""

    def __init__(self, body):
        sizes = body.sizes
        self.thigh, self.shank = sizes["thigh"], sizes["shank"]
        self.hip = {
            side: np.array([0.0, sign * sizes["hip_half_width"], 0.0])
            for side, sign in zip(SIDES, (1, -1), strict=True)
        }
        self.sole_offset = np.array(
            [sizes["foot"] / 2 - sizes["heel_back"], 0.0, -sizes["ankle_height"]]
        )
        self._hips = {side: tuple(map(float, hip)) for side, hip in self.hip.items()}
        """`hip` as tuples, for `solve`."""
        self._sole_offset = tuple(self.sole_offset.tolist())
        self.half_foot = sizes["foot"] / 2
        (foot,) = body.skeleton.body("left_foot").collisions
        self.half_foot_width = foot.shape.size[1] / 2
        index = body.index
        self.root = tuple(index(n) for n in ("base_x", "base_y", "base_yaw", "pelvis_height"))
        self.pelvis_angles = (index("pelvis_tilt"), index("pelvis_list"))
        self._pelvis_columns = np.array([*self.root, *self.pelvis_angles])
        """`root` and `pelvis_angles`, for reading them off q in one go."""
        self.joints = {side: tuple(index(f"{side}_{j}") for j in LEG_JOINTS) for side in SIDES}
        self.lower = {side: body.lower[list(self.joints[side])] for side in SIDES}
        self.upper = {side: body.upper[list(self.joints[side])] for side in SIDES}
        self._columns = {side: np.array(self.joints[side]) for side in SIDES}
        """`joints` as index arrays, for `solve`."""
        self._limits = {
            side: tuple(zip(self.lower[side].tolist(), self.upper[side].tolist(), strict=True))
            for side in SIDES
        }
        """Per side, each leg joint's (lower, upper) limit as floats, for `solve`."""
        self._rotation = (b"", (), np.empty((3, 3)))
        """The last pelvis rotation worked out: (its angles' bytes, rows, array)."""

    def pelvis(self, q) -> tuple[np.ndarray, np.ndarray]:
        """World rotation and position of the pelvis frame (the hip joints' midpoint)."""
        _, p = self._pelvis_rows(q)
        return self._rotation[2], np.array(p)  # the rotation just worked out, as an array

    def _pelvis_rows(self, q) -> tuple[tuple, tuple[float, float, float]]:
        """`pelvis` as tuples: the rotation's rows, the position."""
        x, y, yaw, height, tilt, tilt_list = np.asarray(q)[self._pelvis_columns].tolist()
        return self._pelvis_rotation(yaw, tilt, tilt_list)[0], (x, y, height)

    def _pelvis_rotation(self, yaw: float, tilt: float, tilt_list: float) -> tuple:
        """The pelvis rotation's rows and array, the last one remembered: placing a walking
        person's feet asks for it some eight times, for the same pelvis (keyed by the
        angles' bytes, so that a -0.0 is never taken for a 0.0)."""
        key = pack("3d", yaw, tilt, tilt_list)
        if key != self._rotation[0]:
            rows = _product(_product(_rows_z(yaw), _rows_y(tilt)), _rows_x(tilt_list))
            array = np.array(rows)
            array.flags.writeable = False  # shared by every caller until the pelvis turns
            self._rotation = (key, rows, array)
        return self._rotation[1:]

    def sole(self, q, side: str) -> SolePose:
        """Where the `side` sole is at the joint positions q."""
        return SolePose(*map(np.array, self._sole_rows(q, side)))

    def _sole_rows(self, q, side: str) -> tuple[tuple, tuple, tuple]:
        """`sole` as tuples: position, forward, up (a walking pose asks twice)."""
        R_p, p = self._pelvis_rows(q)
        flexion, abduction, rotation, knee, ankle = (float(q[i]) for i in self.joints[side])
        sign = 1.0 if side == "left" else -1.0
        hip = _product(_rows_y(-flexion), _rows_x(sign * abduction))
        R_thigh = _product(R_p, _product(hip, _rows_z(-sign * rotation)))
        R_shank = _product(R_thigh, _rows_y(knee))
        R_foot = _product(R_shank, _rows_y(-ankle))
        offsets = (
            _times(R_p, self._hips[side]),
            _times(R_thigh, (0.0, 0.0, -self.thigh)),
            _times(R_shank, (0.0, 0.0, -self.shank)),
            _times(R_foot, self._sole_offset),
        )
        position = tuple(x + a + b + c + d for x, a, b, c, d in zip(p, *offsets, strict=True))
        forward, _, up = zip(*R_foot, strict=True)
        return position, forward, up

    def under_the_floor(self, q, side: str) -> float:
        """How far the `side` foot's sole reaches under the floor (0: it does not). The leg
        gives the foot its roll (there is no ankle to roll it back): a foot swung round a
        turn lands rolled, and the edge of a pitched and rolled sole dips below its heel."""
        position, forward, up = self._sole_rows(q, side)
        across = _crossed(up, forward)
        drop = self.half_foot * abs(forward[2]) + self.half_foot_width * abs(across[2])
        return max(drop - position[2], 0.0)

    def within_reach(self, q, side: str, position, forward, knee: float) -> np.ndarray:
        """`position` for the `side` sole, or where it would be had the leg moved it only as
        far from the hip as the knee bent `knee` allows (straight back towards the hip)."""
        p, hip, ankle = self._hip_and_ankle(q, side, position, forward)
        hip = [h + a for h, a in zip(hip, p, strict=True)]
        leg = [a - h for a, h in zip(ankle, hip, strict=True)]
        longest = sqrt(self._longest_squared(knee))
        length = sqrt(leg[0] * leg[0] + leg[1] * leg[1] + leg[2] * leg[2])
        if length <= longest:
            return np.asarray(position)
        offset = [t - a for t, a in zip(_floats(position), ankle, strict=True)]
        scale = longest / length
        return np.array([h + v * scale + o for h, v, o in zip(hip, leg, offset, strict=True)])

    def highest_pelvis(self, q, side: str, position, forward, knee: float) -> float:
        """The highest the pelvis may stand (pelvis_height, the rest of q kept) for the
        `side` leg to reach its sole's place with the knee bent at least `knee`."""
        (x, y, _), hip, ankle = self._hip_and_ankle(q, side, position, forward)
        across_squared = (x + hip[0] - ankle[0]) ** 2 + (y + hip[1] - ankle[1]) ** 2
        return ankle[2] - hip[2] + sqrt(max(self._longest_squared(knee) - across_squared, 0.0))

    def _hip_and_ankle(self, q, side: str, position, forward) -> tuple[tuple, tuple, list]:
        """The pelvis's position, the `side` hip's offset from it (world axes) and the
        ankle (world) of a sole at `position` pointing along `forward`."""
        R_p, p = self._pelvis_rows(q)
        f = _floats(forward)
        up = _level_up(f)
        along, down = self._sole_offset[0], self._sole_offset[2]
        ankle = [t - along * v - down * u for t, v, u in zip(_floats(position), f, up, strict=True)]
        return p, _times(R_p, self._hips[side]), ankle

    def _longest_squared(self, knee: float) -> float:
        """The squared hip-ankle distance of a leg with the knee bent `knee`."""
        L1, L2 = self.thigh, self.shank
        return L1 * L1 + L2 * L2 + 2 * L1 * L2 * cos(knee)

    def planted(self, q, stance) -> np.ndarray:
        """q with both soles put back where the pose `stance` has them: the pelvis moved by
        a correction (a trunk tipped back, an eased squat), the feet stay where they stand."""
        for side in SIDES:
            sole = self.sole(stance, side)
            q = self.solve(q, side, sole.position, sole.forward)
        return q

    def solve(self, q, side: str, position, forward, passes: int = 3) -> np.ndarray:
        """q with the `side` leg's joints set so its sole frame is at `position` (world)
        with the foot pointing along `forward` (a unit vector; its roll is what the leg
        gives). A target out of reach leaves the leg straight towards it.

        Each pass aims the ankle with the foot's up axis the previous pass gave; only the
        last pass's hip angles are read off."""
        q = np.array(q, dtype=float)
        R_p, p = self._pelvis_rows(q)
        forward = _unit_of(_floats(forward))
        up = _level_up(forward)
        hip = [a + b for a, b in zip(p, _times(R_p, self._hips[side]), strict=True)]
        f = _transposed_times(R_p, forward)
        ahead, down = self._sole_offset[0], self._sole_offset[2]
        # the target less the sole's offset along the foot; each pass takes off the rest, along
        # the foot's up axis as the pass before left it
        aimed = [t - ahead * v for t, v in zip(_floats(position), forward, strict=True)]
        for k in range(passes):
            ankle = [a - down * u - h for a, u, h in zip(aimed, up, hip, strict=True)]
            R_hip, knee, pitch = self._leg(_transposed_times(R_p, ankle), f)
            if k + 1 < passes:
                up = _times(R_p, _times(R_hip, (sin(pitch), 0.0, cos(pitch))))
        joints = (*self._hip_angles(side, R_hip), knee, knee - pitch)
        q[self._columns[side]] = [
            min(max(joint, lower), upper)
            for joint, (lower, upper) in zip(joints, self._limits[side], strict=True)
        ]
        return q

    def place_foot(self, q, side: str, position, forward) -> np.ndarray:
        """`solve`, and where that bends the ankle past its dorsiflexion limit, or a foot on
        its toe is out of reach of the straight leg, the foot rolls further over its heel or
        toe (which stays where the target has it): a heel rises earlier rather than the
        foot sliding."""
        solved = self.solve(q, side, position, forward)
        ankle, knee = self.joints[side][4], self.joints[side][3]
        overbent = solved[ankle] >= self.upper[side][4]
        short = solved[knee] <= STRAIGHTEST_KNEE and forward[2] <= 0
        if not (overbent or short):
            return solved
        along = -self.half_foot if forward[2] > 0 else self.half_foot
        point = np.asarray(position) + along * np.asarray(forward)
        if point[2] > FLOOR_CONTACT:
            return solved
        heading = np.array([forward[0], forward[1], 0.0])
        angle = self.upper[side][4]
        if short:
            angle = self.ankle_for_knee(solved, side, point, along, STRAIGHTEST_KNEE)
            if angle is None:
                return solved
        return self.solve_rolling(solved, side, point, along, heading, angle, forward[2])

    def ankle_for_knee(self, q, side: str, point, along: float, knee: float) -> float | None:
        """The ankle angle with which the `side` leg, its knee at `knee`, puts the sole's
        point `along` metres from its origin at `point` (None: no ankle angle does); of
        two, the one nearer q's."""
        R_p, p = self.pelvis(q)
        d = R_p.T @ (np.asarray(point, dtype=float) - p) - self.hip[side]
        ankle_at = np.array([0.0, 0.0, -self.thigh]) + rotation_y(knee) @ [0.0, 0.0, -self.shank]
        c = self.sole_offset + [along, 0.0, 0.0]
        wanted = (float(d @ d) - float(ankle_at @ ankle_at) - float(c @ c)) / 2
        a_x, a_z, c_x, c_z = ankle_at[0], ankle_at[2], c[0], c[2]
        amplitude = sqrt((a_x * c_x + a_z * c_z) ** 2 + (a_x * c_z - a_z * c_x) ** 2)
        if abs(wanted) > amplitude:
            return None
        beta = atan2(a_x * c_z - a_z * c_x, a_x * c_x + a_z * c_z)
        spread = acos(wanted / amplitude)
        current = float(q[self.joints[side][4]])
        return min(
            (wrap_angle(knee - beta - spread), wrap_angle(knee - beta + spread)),
            key=lambda a: abs(a - current),
        )

    def solve_rolling(self, q, side, point, along: float, heading, ankle: float, pitch: float):
        """q with the `side` leg's joints set so that the sole's point `along` metres from
        its origin (the heel < 0, the toe > 0) is at `point` (world), the foot heading along
        the horizontal `heading`, and the ankle at `ankle`: the foot pitches round that point
        as far as the leg needs (a heel rising off the floor while the toe stays put, or the
        toe lowering onto it while the heel does). Of the two knee angles that reach, the
        one that pitches the foot that way, nearer `pitch` (a sine)."""
        q = np.array(q, dtype=float)
        R_p, p = self.pelvis(q)
        L1 = self.thigh
        c = self.sole_offset + [along, 0.0, 0.0]
        w = np.array([0.0, 0.0, -self.shank]) + rotation_y(-ankle) @ c
        d = R_p.T @ (np.asarray(point, dtype=float) - p) - self.hip[side]
        rho = sqrt(w[0] ** 2 + w[2] ** 2)
        reach = (float(d @ d) - L1 * L1 - rho * rho) / (2 * L1)
        bend = asin(min(max(reach / rho, -1.0), 1.0))
        h = R_p.T @ _unit(np.asarray(heading, dtype=float))
        up = R_p.T @ np.array([0.0, 0.0, 1.0])
        best = None
        for knee in (atan2(w[2], w[0]) + bend, atan2(w[2], w[0]) + pi - bend):
            knee = min(max(wrap_angle(knee), STRAIGHTEST_KNEE), self.upper[side][3])
            u = np.array([0.0, 0.0, -L1]) + rotation_y(knee) @ w
            forward = h
            for _ in range(4):
                R_hip = np.array(self._hip_frame(d, u, forward))
                rise = float(R_hip @ rotation_y(knee - ankle)[:, 0] @ up)
                forward = sqrt(max(1.0 - rise * rise, 0.0)) * h + rise * up
            wrong_way = rise * along > ROLL_TOLERANCE * abs(along)  # the heel up or the toe
            score = (wrong_way, abs(rise - pitch))
            if best is None or score < best[0]:
                best = (score, [*self._hip_angles(side, R_hip), knee, ankle])
        q[list(self.joints[side])] = np.clip(best[1], self.lower[side], self.upper[side])
        return q

    @staticmethod
    def _hip_frame(d, u, forward) -> tuple:
        """The hip's rotation (rows) taking the thigh-frame vector u (in its x-z plane) onto
        d, with the leg's plane holding `forward` (all in the pelvis frame)."""
        u_hat, d_hat = _unit_of(u), _unit_of(d)
        n = _unit_of(_crossed(forward, d_hat))
        m = _crossed(n, d_hat)
        ux, _, uz = u_hat
        # (d_hat | n | m) @ (u_hat; (0, 1, 0); (uz, 0, -ux)), row by row
        (d0, d1, d2), (n0, n1, n2), (m0, m1, m2) = d_hat, n, m
        return (
            (d0 * ux + m0 * uz, n0, d0 * uz - m0 * ux),
            (d1 * ux + m1 * uz, n1, d1 * uz - m1 * ux),
            (d2 * ux + m2 * uz, n2, d2 * uz - m2 * ux),
        )

    @staticmethod
    def _hip_angles(side: str, R_hip) -> tuple[float, float, float]:
        """Hip flexion, abduction and rotation of a hip rotation matrix (rows)."""
        sign = 1.0 if side == "left" else -1.0
        a = atan2(R_hip[0][2], R_hip[2][2])
        b = asin(min(max(-R_hip[1][2], -1.0), 1.0))
        c = atan2(R_hip[1][0], R_hip[1][1])
        return -a, sign * b, -sign * c

    def _leg(self, d, f):
        """The hip's rotation (rows), the knee angle and the foot's pitch (in the leg's
        plane) putting the ankle at d from the hip with the foot along f (both in the
        pelvis frame)."""
        L1, L2 = self.thigh, self.shank
        reach = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2])
        c = (reach * reach - L1 * L1 - L2 * L2) / (2 * L1 * L2)
        knee = max(acos(min(max(c, -1.0), 1.0)), STRAIGHTEST_KNEE)
        u = (-L2 * sin(knee), 0.0, -L1 - L2 * cos(knee))
        R_hip = self._hip_frame(d, u, f)
        g = _transposed_times(R_hip, f)
        return R_hip, knee, atan2(-g[2], g[0])


@lru_cache(maxsize=4)
def legs_of(body) -> Legs:
    """The legs of `body`, worked out once per body."""
    return Legs(body)
