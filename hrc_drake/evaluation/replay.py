"""replay.html: the run as a standalone Meshcat page that shows what happened, and stays small.

The scene is dressed for reading the action (`dress_scene`): the scenario's camera, no grid
or world axes, a key light whose shadows show whether feet and boxes touch a surface, and a
ring around the robot's base in the colour of its safety state (green: full speed, amber:
reduced, red: stopped), as the LED ring of a real cobot.

The animation (`write_replay`) keeps, per frame Meshcat draws, only the keys that change
what is seen: a key is dropped when interpolating its neighbours (linearly for positions,
by slerp for rotations, as three.js does) stays within `POSITION_TOLERANCE` and
`ANGLE_TOLERANCE` of it. Keys travel as float32 arrays (Meshcat's 0x17 extension) rather
than as one map of doubles per key. A static cell object or a parked workpiece slot thus
costs two keys, not 32 a second.

The page also carries the run's timeline as JSON (`<script id="hrc-replay">`): the safety
states, who held which workpiece when, with the Meshcat paths of the holding hands, and with
safety sensors whether they saw the person. A caption shows the replay time, the robot's
safety state and whether the person is seen. The sensors themselves, their fields and
detections are drawn and animated by `hrc_drake.evaluation.replay_sensors`.
"""

import base64
import json
from dataclasses import dataclass
from pathlib import Path

import msgpack
import numpy as np
from pydrake.geometry import Meshcat, Rgba
from pydrake.math import RigidTransform

from hrc_drake.evaluation.recording import (
    FULL_SPEED,
    MESHCAT_ROOT,
    REDUCED,
    STOPPED,
    Recording,
)
from hrc_drake.evaluation.replay_sensors import sensor_tracks
from hrc_drake.workpieces.messages import BOTH_HANDS, LEFT_HAND, RIGHT_HAND

POSITION_TOLERANCE = 0.001
"""m: how far a dropped key may lie from the interpolation of the kept ones."""
ANGLE_TOLERANCE = np.radians(0.2)
"""rad: likewise for rotations (0.2 degrees move a point 0.5 m from the frame by 1.7 mm)."""

CAMERA_FOV = 50.0
"""Degrees, vertical: narrower than Meshcat's 75, so a camera that frames the whole cell
stands back and the person near it is not distorted."""

RING_PATH = "safety_ring"
RING_COLORS = {
    FULL_SPEED: Rgba(0.1, 0.75, 0.25, 1.0),
    REDUCED: Rgba(1.0, 0.5, 0.0, 1.0),
    STOPPED: Rgba(0.9, 0.1, 0.1, 1.0),
}
RING_RADII = (0.125, 0.19)
"""m: the ring lies around the robot's base, where the LBR iisy has its LED ring."""
RING_SEGMENTS = 72

KEY_LIGHT_DIRECTION = (0.35, -0.45, 1.0)
"""Towards the key light: high, behind the usual camera's right shoulder."""
KEY_LIGHT_DISTANCE = 12.0
SHADOW_REACH = 6.0
"""m from the origin that the shadow map covers, each way."""
SHADOW_MAP = 4096

HOLDING_HANDS = {
    LEFT_HAND: ("left_hand",),
    RIGHT_HAND: ("right_hand",),
    BOTH_HANDS: ("left_hand", "right_hand"),
}
"""Workpiece holder -> the person's bodies that hold."""

FLOAT32_EXTENSION = 0x17
LOOP_REPEAT = 2201
DISCRETE = 2300


@dataclass(frozen=True)
class Track:
    """One animated property of one Meshcat path."""

    path: str
    name: str
    kind: str
    times: np.ndarray
    values: np.ndarray | list
    interpolation: int | None = None

    def message(self) -> dict:
        """The track as three.js's KeyframeTrack.parse reads it."""
        values = self.values if isinstance(self.values, list) else _float32(self.values)
        track = {"name": self.name, "type": self.kind, "times": _float32(self.times)}
        track["values"] = values
        if self.interpolation is not None:
            track["interpolation"] = self.interpolation
        return track


def _float32(values) -> msgpack.ExtType:
    return msgpack.ExtType(FLOAT32_EXTENSION, np.asarray(values, dtype="<f4").ravel().tobytes())


# --- the scene -----------------------------------------------------------------------------


CAMERA_DIRECTION = (0.45, -0.75, 0.7)
"""From the middle of the cell towards the camera that frames it: in front, to the right
and above, as the bundled scenarios' cameras look."""
FLOOR_PLACE = 0.05
"""m: a location this close to the floor is a place to stand (framed with the cell)."""
SMALLEST_CELL = 2.5
"""m: a framed cell is at least this wide (one table and a robot)."""


def framing_camera(points_xy) -> tuple[list[float], list[float]]:
    """A camera position and target that show every one of `points_xy` (the cell's
    furniture corners, the robot, the places to stand): a user's own cell is seen whole
    before they choose a camera of their own."""
    points = np.asarray(points_xy, dtype=float)
    low, high = points.min(axis=0), points.max(axis=0)
    size = max(float(np.linalg.norm(high - low)), SMALLEST_CELL)
    target = np.array([*(low + high) / 2, 0.5])
    distance = 0.55 * size / np.tan(np.radians(CAMERA_FOV) / 2)
    direction = np.array(CAMERA_DIRECTION) / np.linalg.norm(CAMERA_DIRECTION)
    return (target + distance * direction).round(2).tolist(), target.round(2).tolist()


def camera_of(scenario, obstacles) -> tuple[list[float], list[float]]:
    """The scenario's camera (position, target), or one framing the cell: the furniture's
    outlines (`obstacles`, hrc_drake.human.navigation), the robot, the person's start and
    the places on the floor."""
    options = scenario.visualization
    if options.camera_position and options.camera_target:
        return options.camera_position, options.camera_target
    points = [xy for obstacle in obstacles for xy in obstacle.outline.exterior.coords]
    points.append(scenario.robot.base_pose.GetDeterministicValue().translation()[:2])
    if scenario.human is not None:
        points.append(scenario.human.start[:2])
    for name in scenario.locations:
        position = scenario.location(name).translation()
        if abs(position[2]) < FLOOR_PLACE:
            points.append(position[:2])
    return framing_camera(points)


def dress_scene(meshcat: Meshcat, camera_position, camera_target, robot_base: RigidTransform):
    """Camera, lights and shadows, no helpers, and the safety ring (full speed at first)."""
    meshcat.SetCamera(Meshcat.PerspectiveCamera(fov=CAMERA_FOV, near=0.05, far=100.0))
    meshcat.SetCameraPose(camera_position, camera_target)
    meshcat.SetProperty("/Grid", "visible", False)  # the cell has its own floor
    meshcat.SetProperty("/Axes", "visible", False)
    _key_light(meshcat)
    _safety_ring(meshcat, robot_base)


def _key_light(meshcat: Meshcat) -> None:
    """Meshcat's directional light, moved overhead, casts soft shadows over the cell."""
    light = "/Lights/FillLight/<object>"
    direction = np.array(KEY_LIGHT_DIRECTION) / np.linalg.norm(KEY_LIGHT_DIRECTION)
    meshcat.SetProperty(light, "position", list(KEY_LIGHT_DISTANCE * direction))
    meshcat.SetProperty(light, "intensity", 2.2)
    for side, value in (("left", -1), ("right", 1), ("bottom", -1), ("top", 1)):
        meshcat.SetProperty(light, f"shadow.camera.{side}", value * SHADOW_REACH)
    meshcat.SetProperty(light, "shadow.camera.far", 2 * KEY_LIGHT_DISTANCE)
    meshcat.SetProperty(light, "shadow.mapSize.width", SHADOW_MAP)
    meshcat.SetProperty(light, "shadow.mapSize.height", SHADOW_MAP)
    meshcat.SetProperty(light, "shadow.bias", -0.0005)
    meshcat.SetProperty(light, "castShadow", True)
    meshcat.SetProperty("/Lights/AmbientLight/<object>", "intensity", 1.2)


def _safety_ring(meshcat: Meshcat, robot_base: RigidTransform) -> None:
    """One flat ring per state on the floor around the pedestal; only one is shown."""
    inner, outer = RING_RADII
    angles = np.linspace(0.0, 2 * np.pi, RING_SEGMENTS, endpoint=False)
    circle = np.stack([np.cos(angles), np.sin(angles), np.zeros_like(angles)])
    vertices = np.asfortranarray(np.hstack([inner * circle, outer * circle]))
    k = np.arange(RING_SEGMENTS)
    n = (k + 1) % RING_SEGMENTS
    faces = np.hstack(
        [np.stack([k, RING_SEGMENTS + k, RING_SEGMENTS + n]), np.stack([k, RING_SEGMENTS + n, n])]
    )
    x, y, z = robot_base.translation()
    for state, color in RING_COLORS.items():
        path = _ring_state_path(state)
        meshcat.SetTriangleMesh(path, vertices, np.asfortranarray(faces, dtype=np.int32), color)
        meshcat.SetTransform(path, RigidTransform([x, y, z + 0.002]))
        meshcat.SetProperty(path, "visible", state == FULL_SPEED)


def _ring_state_path(state: str) -> str:
    return f"{MESHCAT_ROOT}/{RING_PATH}/{state.replace(' ', '_')}"


# --- the animation -----------------------------------------------------------------------


def kept_keys(times: np.ndarray, values: np.ndarray, error, tolerance: float) -> np.ndarray:
    """Indices of the keys to keep (Ramer-Douglas-Peucker over time): every dropped sample
    lies within `tolerance` of the interpolation between the kept keys around it.
    `error(times, values, i, j)` is the deviation of samples i+1..j-1 from that."""
    keep = {0, len(times) - 1}
    spans = [(0, len(times) - 1)]
    while spans:
        i, j = spans.pop()
        if j - i < 2:
            continue
        deviation = error(times, values, i, j)
        k = int(np.argmax(deviation))
        if deviation[k] > tolerance:
            keep.add(i + 1 + k)
            spans += [(i, i + 1 + k), (i + 1 + k, j)]
    return np.array(sorted(keep))


def _between(times, i, j) -> np.ndarray:
    return ((times[i + 1 : j] - times[i]) / (times[j] - times[i]))[:, None]


def position_error(times, positions, i, j) -> np.ndarray:
    s = _between(times, i, j)
    interpolated = (1 - s) * positions[i] + s * positions[j]
    return np.linalg.norm(positions[i + 1 : j] - interpolated, axis=1)


def angle_error(times, quaternions, i, j) -> np.ndarray:
    """Angle between each sample and the slerp of the two keys (signs made continuous)."""
    s = _between(times, i, j)
    a, b = quaternions[i], quaternions[j]
    cos = float(np.clip(a @ b, -1.0, 1.0))
    theta = np.arccos(cos)
    if theta < 1e-9:
        interpolated = np.broadcast_to(a, (len(s), 4))
    else:
        interpolated = (np.sin((1 - s) * theta) * a + np.sin(s * theta) * b) / np.sin(theta)
    dots = np.abs(np.sum(interpolated * quaternions[i + 1 : j], axis=1))
    return 2 * np.arccos(np.clip(dots, -1.0, 1.0))


def _continuous(quaternions: np.ndarray) -> np.ndarray:
    """q and -q are one rotation: flip signs so neighbours are on the same side."""
    flips = np.concatenate([[1.0], np.sign(np.sum(quaternions[1:] * quaternions[:-1], axis=1))])
    flips[flips == 0] = 1.0
    return quaternions * np.cumprod(flips)[:, None]


def pose_tracks(path: str, times: np.ndarray, poses: np.ndarray) -> list[Track]:
    """Position and rotation tracks of one frame (three.js quaternions are x, y, z, w)."""
    positions = poses[:, :3]
    quaternions = _continuous(poses[:, 3:])
    p = kept_keys(times, positions, position_error, POSITION_TOLERANCE)
    q = kept_keys(times, quaternions, angle_error, ANGLE_TOLERANCE)
    return [
        Track(path, ".position", "vector3", times[p], positions[p]),
        Track(path, ".quaternion", "quaternion", times[q], quaternions[q][:, [1, 2, 3, 0]]),
    ]


def state_changes(times, states: list[str]) -> list[tuple[float, str]]:
    changes = []
    for t, state in zip(times, states, strict=True):
        if not changes or changes[-1][1] != state:
            changes.append((float(t), state))
    return changes


def ring_tracks(times: np.ndarray, states: list[str]) -> list[Track]:
    """Each state's ring is visible exactly while the robot is in that state."""
    changes = state_changes(times, states)
    key_times = np.array([t for t, _ in changes] + [float(times[-1])])
    shown = [s for _, s in changes]
    return [
        Track(
            _ring_state_path(state),
            ".visible",
            "boolean",
            key_times,
            [s == state for s in shown] + [shown[-1] == state],
            DISCRETE,
        )
        for state in RING_COLORS
    ]


def held_spans(times, held: list[dict[str, str]], human_path: str) -> list[dict]:
    """Who held which workpiece from when to when, with the holding hands' Meshcat paths."""
    spans, holding = [], {}
    for t, now in zip(times, held, strict=True):
        now = set(now.items())
        for key in [key for key in holding if key not in now]:
            spans.append({**holding.pop(key), "end": float(t)})
        for object_path, holder in now - holding.keys():
            hands = [f"{human_path}/{body}" for body in HOLDING_HANDS.get(holder, ())]
            holding[(object_path, holder)] = {
                "start": float(t),
                "object": object_path,
                "holder": holder,
                "hands": hands,
            }
    spans += [{**span, "end": float(times[-1])} for span in holding.values()]
    return sorted(spans, key=lambda span: span["start"])


def animation_message(recording: Recording) -> bytes:
    times = np.array(recording.times)
    tracks = [
        track
        for path in recording.poses
        for track in pose_tracks(path, times, recording.pose_array(path))
    ]
    if recording.safety:
        tracks += ring_tracks(times, recording.safety)
    tracks += [Track(*spec) for spec in sensor_tracks(recording)]
    by_path: dict[str, list[Track]] = {}
    for track in tracks:
        by_path.setdefault(track.path, []).append(track)
    animations = [
        {
            "path": path,
            "clip": {"fps": 1.0, "name": "default", "tracks": [t.message() for t in path_tracks]},
        }
        for path, path_tracks in by_path.items()
    ]
    options = {"play": True, "loopMode": LOOP_REPEAT, "repetitions": 1, "clampWhenFinished": True}
    command = {"type": "set_animation", "animations": animations, "options": options}
    return msgpack.packb(command, use_bin_type=True)


def timeline(recording: Recording, human_path: str) -> dict:
    """The run's states over time for the page (and tests): safety states, held objects
    and, with safety sensors, whether they saw the person (`seen`, else absent)."""
    times = np.array(recording.times)
    found = {
        "duration": float(times[-1]) if times.size else 0.0,
        "safety": state_changes(times, recording.safety) if recording.safety else [],
        "held": held_spans(times, recording.held, human_path) if recording.held else [],
    }
    if recording.sensors:
        seen = [any(s.seen for s in sample) for sample in recording.sensors]
        found["seen"] = state_changes(times, seen)
    return found


CAPTION_SCRIPT = """
(function () {
  const run = JSON.parse(document.getElementById("hrc-replay").textContent);
  const caption = document.createElement("div");
  caption.id = "hrc-caption";
  caption.style.cssText = "position:fixed;left:12px;bottom:12px;padding:4px 10px;" +
    "font:14px sans-serif;background:rgba(255,255,255,0.8);border-radius:4px";
  document.body.appendChild(caption);
  const at = (changes, t) => {
    let state = "";
    for (const [start, s] of changes) { if (start <= t + 1e-6) state = s; }
    return state;
  };
  const update = () => {
    const actions = viewer.animator.actions;
    const t = actions.length ? Math.max(...actions.map((a) => a.time)) : 0;
    const state = at(run.safety, t);
    let text = t.toFixed(1) + " s" + (state ? " \u00b7 robot: " + state : "");
    if (run.seen) text += at(run.seen, t) ? " \u00b7 person seen" : " \u00b7 person not seen";
    caption.textContent = text;
    requestAnimationFrame(update);
  };
  requestAnimationFrame(update);
})();
"""


def write_replay(path: Path, meshcat: Meshcat, recording: Recording, human_path: str) -> Path:
    """Meshcat's standalone page with the compact animation, the timeline and the caption."""
    html = meshcat.StaticHtml()
    command = base64.b64encode(animation_message(recording)).decode("ascii")
    data = json.dumps(timeline(recording, human_path), separators=(",", ":"))
    extra = (
        f'<script id="hrc-replay" type="application/json">{data}</script>\n'
        f'<script>\nfetch("data:application/octet-binary;base64,{command}")\n'
        "  .then(res => res.arrayBuffer())\n"
        "  .then(buffer => viewer.handle_command_bytearray(new Uint8Array(buffer)));\n"
        f"{CAPTION_SCRIPT}</script>\n"
    )
    end = html.rindex("</body>")
    Path(path).write_text(html[:end] + extra + html[end:])
    return Path(path)
