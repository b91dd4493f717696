"""Rotations about joint axes: a chain of axis rotations composed into one rotation matrix,
and a rotation split back into the angles of three orthonormal axes (both solutions), as
joint angles need for any axis order, not only roll-pitch-yaw; and angles wrapped into
[-π, π) for headings compared or turned the short way round."""

from math import pi

import numpy as np

AXES = {"X": np.array([1.0, 0, 0]), "Y": np.array([0, 1.0, 0]), "Z": np.array([0, 0, 1.0])}


def wrap_angle(angle: float) -> float:
    """`angle` in [-π, π): the same direction, the short way round from 0."""
    return (angle + pi) % (2 * pi) - pi


def axis_rotation(axis: np.ndarray, angle: float) -> np.ndarray:
    """Rodrigues: rotation by `angle` about the unit vector `axis`."""
    k = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
    return np.eye(3) + np.sin(angle) * k + (1 - np.cos(angle)) * k @ k


def compose(axes, angles) -> np.ndarray:
    """R_a1(θ1) R_a2(θ2) ...: the rotation of a chain of joints about `axes` by `angles`."""
    rotation = np.eye(3)
    for axis, angle in zip(axes, angles, strict=True):
        rotation = rotation @ axis_rotation(np.asarray(axis, dtype=float), angle)
    return rotation


def decompose(rotation: np.ndarray, axes) -> list[np.ndarray]:
    """Both solutions (θ1, θ2, θ3) of R = R_a(θ1) R_b(θ2) R_c(θ3), a, b, c orthonormal."""
    a, b, c = (np.asarray(v, dtype=float) for v in axes)
    eps = float(a @ np.cross(b, c))
    theta2 = np.arcsin(np.clip(eps * a @ rotation @ c, -1.0, 1.0))
    theta1 = np.arctan2(-eps * b @ rotation @ c, c @ rotation @ c)
    theta3 = np.arctan2(-eps * a @ rotation @ b, a @ rotation @ a)
    first = np.array([theta1, theta2, theta3])
    other = np.array([theta1 + np.pi, np.pi - theta2, theta3 + np.pi])
    return [first, (other + np.pi) % (2 * np.pi) - np.pi]


def minimal_rotation(source: np.ndarray, target: np.ndarray) -> np.ndarray:
    """The smallest rotation turning direction `source` into direction `target`."""
    a, b = source / np.linalg.norm(source), target / np.linalg.norm(target)
    v, c = np.cross(a, b), float(a @ b)
    if c < -0.999999:
        return axis_rotation(
            np.cross(a, [1.0, 0, 0]) / np.linalg.norm(np.cross(a, [1.0, 0, 0])), np.pi
        )
    k = np.array([[0, -v[2], v[1]], [v[2], 0, -v[0]], [-v[1], v[0], 0]])
    return np.eye(3) + k + k @ k / (1 + c)


def padded_axes(axes: list[np.ndarray]) -> list[np.ndarray]:
    """Complete one or two orthogonal joint axes to three (the extra angles should be zero)."""
    axes = list(axes)
    for candidate in (AXES["X"], AXES["Y"], AXES["Z"]):
        if len(axes) == 3:
            break
        if all(abs(candidate @ axis) < 0.5 for axis in axes):
            axes.append(candidate)
    return axes
