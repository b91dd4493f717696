"""replay.html's parts without a browser: the kept keys restore every sample within the
tolerances, the safety ring and the held spans follow the recording, and every bundled
scenario's camera frames its action."""

from pathlib import Path

import numpy as np
import pytest
from pydrake.common.eigen_geometry import Quaternion

from hrc_drake.evaluation.recording import FULL_SPEED, REDUCED, STOPPED
from hrc_drake.evaluation.replay import (
    ANGLE_TOLERANCE,
    CAMERA_FOV,
    POSITION_TOLERANCE,
    angle_error,
    camera_of,
    held_spans,
    kept_keys,
    position_error,
    ring_tracks,
)
from hrc_drake.scenario import bundled_scenarios, load_scenario
from hrc_drake.scenario.cell_findings import CellScene

TIMES = np.arange(0, 20.0, 1 / 32)


def walk_like_positions() -> np.ndarray:
    """A pelvis-like path: forward at 1.3 m/s with a bounce, standing, a jump to a slot."""
    x = np.where(TIMES < 10, 1.3 * TIMES, 13.0)
    z = 0.9 + np.where(TIMES < 10, 0.02 * np.sin(2 * np.pi * 1.8 * TIMES), 0.0)
    positions = np.stack([x, 0.3 * np.sin(0.2 * TIMES), z], axis=1)
    positions[TIMES >= 15] = [10.0, 0.0, -1000.0]
    return positions


def test_kept_position_keys_restore_every_sample():
    positions = walk_like_positions()
    keys = kept_keys(TIMES, positions, position_error, POSITION_TOLERANCE)
    restored = np.stack([np.interp(TIMES, TIMES[keys], positions[keys, i]) for i in range(3)], 1)
    assert np.abs(restored - positions).max() <= POSITION_TOLERANCE
    assert len(keys) < len(TIMES) / 2


def test_a_still_or_straight_track_keeps_its_two_ends():
    still = np.tile([1.0, 2.0, 3.0], (len(TIMES), 1))
    straight = np.outer(TIMES, [0.5, 0.0, 0.1])
    for track in (still, straight):
        assert kept_keys(TIMES, track, position_error, POSITION_TOLERANCE).tolist() == [
            0,
            len(TIMES) - 1,
        ]


def test_kept_rotation_keys_restore_every_sample_by_slerp():
    yaw = 0.8 * np.sin(0.7 * TIMES) + 0.1 * TIMES
    quaternions = np.stack([np.cos(yaw / 2), 0 * yaw, 0.3 * np.sin(yaw / 2), np.sin(yaw / 2)], 1)
    quaternions /= np.linalg.norm(quaternions, axis=1, keepdims=True)
    keys = kept_keys(TIMES, quaternions, angle_error, ANGLE_TOLERANCE)
    worst = 0.0
    for i, j in zip(keys[:-1], keys[1:], strict=True):
        a, b = Quaternion(quaternions[i]), Quaternion(quaternions[j])
        for k in range(i, j + 1):
            s = (TIMES[k] - TIMES[i]) / (TIMES[j] - TIMES[i])
            between = a.slerp(s, b).wxyz()
            worst = max(worst, 2 * np.arccos(min(1.0, abs(between @ quaternions[k]))))
    assert worst <= ANGLE_TOLERANCE + 1e-9
    assert len(keys) < len(TIMES) / 3


def test_one_ring_shows_the_robots_state_at_a_time():
    states = [FULL_SPEED] * 10 + [REDUCED] * 5 + [STOPPED] * 5 + [FULL_SPEED] * 4
    times = np.arange(len(states)) * 0.5
    tracks = {track.path.rsplit("/", 1)[1]: track for track in ring_tracks(times, states)}
    for k, t in enumerate(times):
        shown = [
            name
            for name, track in tracks.items()
            if track.values[np.searchsorted(track.times, t, side="right") - 1]
        ]
        assert shown == [states[k].replace(" ", "_")]
    assert len(tracks["stopped"].times) == 5  # a key per change and one at the end


def test_held_spans_name_the_holding_hands():
    held = [{}, {"/o/a": "robot"}, {"/o/a": "robot"}, {"/o/a": "right_hand"}, {}, {}]
    spans = held_spans(np.arange(6.0), held, "/drake/visual/human")
    assert [(s["start"], s["end"], s["holder"], s["hands"]) for s in spans] == [
        (1.0, 3.0, "robot", []),
        (3.0, 4.0, "right_hand", ["/drake/visual/human/right_hand"]),
    ]


def project(camera, target, point, aspect: float) -> np.ndarray:
    """Normalised screen coordinates (-1..1) of `point` seen by Meshcat's camera (z up)."""
    forward = (np.asarray(target) - camera) / np.linalg.norm(np.asarray(target) - camera)
    right = np.cross(forward, [0.0, 0.0, 1.0])
    right /= np.linalg.norm(right)
    up = np.cross(right, forward)
    d = np.asarray(point) - camera
    depth = d @ forward
    half = np.tan(np.radians(CAMERA_FOV) / 2)
    return np.array([d @ right / (depth * half * aspect), d @ up / (depth * half)])


def action_points(scenario) -> list:
    """Where things happen: the robot (base to above its reach), every named place (and the
    floor under it), the person standing at their start."""
    x, y, _ = scenario.robot.base_pose.translation
    points = [[x, y, 0.0], [x, y, 1.6]]
    for name in scenario.locations:
        p = scenario.location(name).translation()
        points += [p, [p[0], p[1], 0.0]]
    if scenario.human is not None:
        hx, hy, _ = scenario.human.start
        points += [[hx, hy, 0.0], [hx, hy, scenario.human.height]]
    return points


NEW_CELL = Path(__file__).resolve().parents[1] / "corpus" / "new_cell" / "cell.yaml"
"""A user's first cell, written from the README: it names no camera."""


@pytest.mark.parametrize("name", [*bundled_scenarios(), NEW_CELL])
def test_the_default_camera_frames_the_action(name):
    """Each bundled scenario's camera, and the one that frames a user's cell without a
    camera of its own, show everything that happens."""
    scenario = load_scenario(name)
    camera, target = camera_of(scenario, CellScene(scenario).navigation.obstacles)
    camera = np.asarray(camera)
    for aspect in (16 / 9, 4 / 3):
        screen = np.array([project(camera, target, p, aspect) for p in action_points(scenario)])
        assert np.abs(screen).max() <= 0.9, f"{aspect:.2f}: something is out of view"
        spread = screen.max(axis=0) - screen.min(axis=0)
        assert spread.max() >= 1.0, f"{aspect:.2f}: the action fills {spread / 2} of the view"
