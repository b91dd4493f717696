"""Clips: range of motion, floor contact, loops, and walk realism on the real kinematics."""

import numpy as np
import pytest

from hrc_drake.human.body import human_body
from hrc_drake.human.clip import clip_from_json, clip_to_json, load_clips

REQUIRED = {
    "idle",
    "walk",
    "turn_left",
    "turn_right",
    "pick_floor",
    "pick_table",
    "place_floor",
    "place_table",
    "inspect",
    "reach",
    "hand_over",
    "carry",
    "wave",
    "look_around",
}
SAMPLE_RATE = 120.0


def _samples(clip, cycles=1):
    times = np.arange(0.0, cycles * clip.duration, 1.0 / SAMPLE_RATE)
    return times, np.array([clip.sample(t) for t in times])


def _sole_tracks(body, poses) -> dict[str, np.ndarray]:
    tracks = {}
    for q in poses:
        for name, point in body.sole_points(q).items():
            tracks.setdefault(name, []).append(point)
    return {name: np.array(points) for name, points in tracks.items()}


def test_all_required_clips_exist_with_metadata():
    clips = load_clips()
    assert set(clips) >= REQUIRED
    for clip in clips.values():
        assert clip.duration > 0.5 and clip.description
        assert all(0.0 <= t <= clip.duration for t in clip.events.values())
    assert clips["pick_floor"].events["grasp"] < clips["pick_floor"].duration
    assert clips["place_table"].events["release"] > 0
    assert clips["walk"].loop and clips["idle"].loop and not clips["reach"].loop


@pytest.mark.parametrize("name", sorted(REQUIRED))
def test_clip_inside_range_of_motion_and_on_the_floor(name):
    body = human_body()
    clip = load_clips()[name]
    _, poses = _samples(clip)
    tolerance = np.radians(0.01)
    assert np.all(poses >= body.lower - tolerance) and np.all(poses <= body.upper + tolerance)
    lowest = np.array([min(p[2] for p in body.sole_points(q).values()) for q in poses])
    assert lowest.min() >= -0.01, "a sole goes through the floor"
    assert lowest.max() <= 0.02, "the body floats"


@pytest.mark.parametrize("name", ["idle", "walk", "carry", "turn_left"])
def test_loops_join_without_a_jump(name):
    clip = load_clips()[name]
    before, after = clip.sample(clip.duration - 1e-6), clip.sample(clip.duration + 1e-6)
    assert np.max(np.abs(after - before)) < 1e-4


def test_file_format_round_trips():
    clip = load_clips()["wave"]
    again = clip_from_json(clip_to_json(clip))
    assert np.max(np.abs(again.frames - clip.frames)) < 1e-6
    assert again.events == clip.events


def _contact_slips(track: np.ndarray, threshold=0.005) -> list[float]:
    """Largest horizontal travel of a sole point during each spell on the floor."""
    slips, start = [], None
    for k, on_floor in enumerate(np.append(track[:, 2] < threshold, False)):
        if on_floor and start is None:
            start = k
        elif not on_floor and start is not None:
            spell = track[start:k, :2]
            slips.append(float(np.max(np.linalg.norm(spell - spell[0], axis=1))))
            start = None
    return slips


def test_walk_speed_cadence_and_planted_stance_foot():
    body = human_body()
    walk = load_clips()["walk"]
    speed = walk.animation_distance / walk.duration
    cadence = 2 * 60.0 / walk.duration
    assert 1.2 <= speed <= 1.4
    assert 100 <= cadence <= 120
    _, poses = _samples(walk, cycles=3)
    slips = [s for track in _sole_tracks(body, poses).values() for s in _contact_slips(track)]
    assert max(slips) < 0.02


PUBLISHED_GAIT = {
    "hip_flexion": [(0, 25), (50, -10), (60, 0), (85, 30)],
    "knee_flexion": [(0, 0), (12, 17.5), (60, 40), (72, 65)],
}
"""Key points from docs/human-body.md (% of the cycle from heel strike, degrees)."""


@pytest.mark.parametrize("joint", sorted(PUBLISHED_GAIT))
def test_walk_sagittal_angles_follow_published_key_points(joint):
    walk = load_clips()["walk"]
    index = walk.joint_names.index(f"left_{joint}")
    for percent, published in PUBLISHED_GAIT[joint]:
        angle = np.degrees(walk.sample(percent / 100 * walk.duration)[index])
        assert abs(angle - published) < 10, f"{joint} at {percent}%: {angle:.1f} deg"


def test_walk_heel_strikes_when_the_event_fires():
    body = human_body()
    walk = load_clips()["walk"]
    for side in ("left", "right"):
        q = walk.sample(walk.events[f"{side}_heel_strike"])
        points = body.sole_points(q)
        assert points[f"{side}_heel"][2] < 0.005
        assert points[f"{side}_toe"][2] > points[f"{side}_heel"][2]


def test_idle_keeps_both_feet_in_place():
    body = human_body()
    _, poses = _samples(load_clips()["idle"])
    for track in _sole_tracks(body, poses).values():
        assert np.max(np.linalg.norm(track[:, :2] - track[0, :2], axis=1)) < 0.01
