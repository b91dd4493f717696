"""The safety sensors in replay.html: what the monitor saw the person through, drawn into the
scene (`draw_sensors`, when the station is built) and animated from the run's recording
(`sensor_tracks`).

- A scanner is a small yellow cylinder at its place; each of its fields is a ribbon along
  the field's outline on the scan plane, faint while clear and bright while occupied
  (protective red, warning amber), shown only while its set is the active one.
- A light curtain's beams are green lines, red while the person interrupts them.
- Where the sensors see the person: up to `MARKERS` red dots on the scan plane (a light
  curtain's: the middles of the interrupted beams), parked under the floor otherwise.
"""

import numpy as np
from pydrake.geometry import Cylinder, Meshcat, Rgba, Sphere
from pydrake.math import RigidTransform

from hrc_drake.evaluation.recording import MESHCAT_ROOT, Recording
from hrc_drake.safety.sensors import SensorsConfig
from hrc_drake.safety.sensors_reading import PROTECTIVE, WARNING, beams

SENSORS_PATH = f"{MESHCAT_ROOT}/sensors"
MARKERS = 12
MARKER_RADIUS = 0.025
PARKED = np.array([0.0, 0.0, -10.0])
"""Where an unused marker waits, out of sight under the floor."""
RIBBON = 0.03
"""m: the width of a field's outline"""
FIELD_KINDS = ("protective", "warning")
FIELD_COLORS = {
    ("protective", False): Rgba(0.9, 0.1, 0.1, 0.3),
    ("protective", True): Rgba(0.95, 0.1, 0.1, 1.0),
    ("warning", False): Rgba(1.0, 0.6, 0.0, 0.3),
    ("warning", True): Rgba(1.0, 0.6, 0.0, 1.0),
}
BEAM_COLORS = {False: Rgba(0.1, 0.75, 0.25, 1.0), True: Rgba(0.95, 0.1, 0.1, 1.0)}
SCANNER_COLOR = Rgba(0.93, 0.76, 0.12, 1.0)
DISCRETE = 2300
"""three.js's InterpolateDiscrete"""


def field_path(sensor: str, field_set: int, kind: str, occupied: bool) -> str:
    state = "occupied" if occupied else "clear"
    return f"{SENSORS_PATH}/{sensor}/set_{field_set}/{kind}/{state}"


def beams_path(sensor: str, interrupted: bool) -> str:
    return f"{SENSORS_PATH}/{sensor}/{'interrupted' if interrupted else 'clear'}"


def marker_path(k: int) -> str:
    return f"{SENSORS_PATH}/detections/{k}"


def draw_sensors(meshcat: Meshcat, sensors: SensorsConfig) -> None:
    """Every sensor, its fields and beams, and the detection markers (all fields hidden until
    the sensor reports)."""
    for name, scanner in sensors.scanners.items():
        x, y, _ = scanner.pose
        body = f"{SENSORS_PATH}/{name}/body"
        meshcat.SetObject(body, Cylinder(0.06, 0.15), SCANNER_COLOR)
        meshcat.SetTransform(body, RigidTransform([x, y, scanner.height]))
        for k, field_set in enumerate(scanner.fields):
            for kind in FIELD_KINDS:
                corners = getattr(field_set, kind)
                if len(corners) < 3:
                    continue
                vertices, faces = ribbon(np.array(corners, dtype=float), scanner.height)
                for occupied in (False, True):
                    path = field_path(name, k, kind, occupied)
                    meshcat.SetTriangleMesh(path, vertices, faces, FIELD_COLORS[kind, occupied])
                    meshcat.SetProperty(path, "visible", False)
    for name, curtain in sensors.light_curtains.items():
        starts, directions, length = beams(curtain)
        ends = starts + length * directions
        for interrupted in (False, True):
            path = beams_path(name, interrupted)
            color = BEAM_COLORS[interrupted]
            meshcat.SetLineSegments(path, starts.T.copy(), ends.T.copy(), 2.0, color)
            meshcat.SetProperty(path, "visible", not interrupted)
    for k in range(MARKERS):
        meshcat.SetObject(marker_path(k), Sphere(MARKER_RADIUS), BEAM_COLORS[True])
        meshcat.SetTransform(marker_path(k), RigidTransform(PARKED))


def ribbon(corners: np.ndarray, height: float) -> tuple[np.ndarray, np.ndarray]:
    """A flat band RIBBON wide along the closed outline `corners` (n × 2) at `height`:
    vertices (3 × 4n) and triangles (3 × 2n), as Meshcat's SetTriangleMesh takes them."""
    starts, ends = corners, np.roll(corners, -1, axis=0)
    along = ends - starts
    side = np.column_stack([-along[:, 1], along[:, 0]])
    side *= RIBBON / 2 / np.linalg.norm(side, axis=1, keepdims=True)
    quads = np.stack([starts - side, starts + side, ends + side, ends - side], axis=1)
    flat = quads.reshape(-1, 2)
    vertices = np.column_stack([flat, np.full(len(flat), height + 0.002)]).T
    first = 4 * np.arange(len(corners))
    faces = np.concatenate(
        [np.stack([first, first + 1, first + 2]), np.stack([first, first + 2, first + 3])], axis=1
    )
    return np.asfortranarray(vertices), np.asfortranarray(faces, dtype=np.int32)


def occupied(kind: str, field_state: int) -> bool:
    """A warning field holds its protective one: it is occupied with it."""
    return field_state == PROTECTIVE if kind == "protective" else field_state >= WARNING


def sensor_tracks(recording: Recording) -> list[tuple]:
    """The fields', beams' and markers' tracks, each as the fields of the replay's Track
    (path, property, type, key times, values, interpolation)."""
    times = np.array(recording.times)
    samples = recording.sensors
    tracks = []
    for name in [s.name for s in samples[0]] if samples else []:
        mine = [next(s for s in sample if s.name == name) for sample in samples]
        for k in sorted({s.field_set for s in mine} - {-1}):
            for kind in FIELD_KINDS:
                for state in (False, True):
                    path = field_path(name, k, kind, state)
                    shown = [
                        s.field_set == k and occupied(kind, s.field_state) == state for s in mine
                    ]
                    tracks.append(_visible(path, times, shown))
        if all(s.field_set == -1 for s in mine):
            for interrupted in (False, True):
                shown = [s.seen == interrupted for s in mine]
                tracks.append(_visible(beams_path(name, interrupted), times, shown))
    return tracks + _marker_tracks(times, recording.detections)


def _visible(path: str, times: np.ndarray, shown: list[bool]) -> tuple:
    """A visibility track keyed only where it changes."""
    keys = [0] + [k for k in range(1, len(shown)) if shown[k] != shown[k - 1]]
    key_times = np.append(times[keys], times[-1])
    values = [shown[k] for k in keys] + [shown[-1]]
    return path, ".visible", "boolean", key_times, values, DISCRETE


def _marker_tracks(times: np.ndarray, detections: list[np.ndarray]) -> list[tuple]:
    """Each marker on one of the detections (spread over them), or parked; it jumps from
    one sample's to the next."""
    if not detections:
        return []
    positions = np.tile(PARKED, (MARKERS, len(times), 1))
    for j, points in enumerate(detections):
        chosen = points[np.linspace(0, len(points) - 1, min(len(points), MARKERS)).astype(int)]
        positions[: len(chosen), j] = chosen
    tracks = []
    for k in range(MARKERS):
        changes = np.flatnonzero(np.any(np.diff(positions[k], axis=0) != 0.0, axis=1)) + 1
        keys = np.unique(np.concatenate([[0, len(times) - 1], changes]))
        path = marker_path(k)
        tracks.append((path, ".position", "vector3", times[keys], positions[k][keys], DISCRETE))
    return tracks
