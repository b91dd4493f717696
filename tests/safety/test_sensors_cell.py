"""`hrc-drake validate` on a user's packing cell guarded by a light curtain across its
material opening and a laser scanner with speed-switched round fields
(tests/safety/cells/packing_cell.yaml): every mistake of the sensors at once, one line each
with file, line and field; the way through the curtain left to the curtain; the curtain's
beam heights against ISO 13855; the part of a field behind the cell's fences, which the
scanner cannot see, not counted as guarding the way in.

ISO 13855 figures: S = 1.6 m/s × T + C + Z_d of the full-speed field is 3.16 m round the
iisy 11's reach with the tool (1.41 m); the 30 mm curtain's S = 1.6 m/s × T + 0.128 m is
2.06 m, and it stands 2.09 m from the reach."""

import re
import subprocess
import sys
from pathlib import Path

import pytest

from hrc_drake.scenario import load_scenario
from hrc_drake.yaml_check import InputError

CELL = Path(__file__).parent / "cells" / "packing_cell.yaml"
CURTAIN_HEIGHTS = "heights: [0.3, 1.5]"
FIELD_END = "[4.38, -1.81]]"
NOTCH = "[4.38, -1.81], [4.57, -0.85], [3.55, -0.85], [3.55, -0.5], [4.64, -0.5]]"
"""The full-speed field without the strip behind the curtain that is farther than S from
the reach for a person walking round the curtain's posts (2.14 m to the upper post plus
1.1 m, 2.46 m to the lower one plus 0.8 m) but 2.17 m from it straight through."""
CURTAIN = """\
    light_curtains:
      opening: {ends: [[3.5, -1.65], [3.5, 0.6]], heights: [0.3, 1.5], resolution: 0.03,
                response_time: 0.02}
"""
SMALLER = (
    ("[4.74, 0.00]", "[3.00, 0.00]"),
    ("[3.36, 0.00]", "[2.00, 0.00]"),
    ("[2.96, 0.00]", "[1.80, 0.00]"),
)
"""Each speed's field drawn in at the front, less than S from the reach there"""
FENCES = """\
  - add_model: {name: fence_back_left, file: package://hrc_drake_models/cell/fence.sdf}
  - add_weld: {parent: world, child: fence_back_left::body, X_PC: {translation: [-1.3, -1.7, 0]}}
  - add_model: {name: fence_back_right, file: package://hrc_drake_models/cell/fence.sdf}
  - add_weld: {parent: world, child: fence_back_right::body, X_PC: {translation: [1.3, -1.7, 0]}}
safety:
"""


def variant(tmp_path, *changes: tuple[str, str]) -> Path:
    """The packing cell with each (old, new) replaced once."""
    text = CELL.read_text()
    for old, new in changes:
        assert old in text, f"packing_cell.yaml no longer holds {old!r}"
        text = text.replace(old, new, 1)
    path = tmp_path / "cell.yaml"
    path.write_text(text)
    return path


def validate(path: Path) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, "-m", "hrc_drake.cli", "validate", str(path)],
        capture_output=True,
        text=True,
    )


def located(path: Path, stderr: str) -> list[tuple[str, str]]:
    """(field, message) of every line of validate's, each of which names file and line."""
    lines = stderr.splitlines()
    pattern = rf"hrc-drake: error: {re.escape(str(path))}:\d+: (\S+): (.*)"
    found = [re.fullmatch(pattern, line) for line in lines]
    assert all(found), stderr
    return [match.groups() for match in found]


def test_validate_lists_every_sensor_mistake_at_once(tmp_path):
    """A curtain one crawls under and reaches over, and fields too small at every speed: five
    lines from one validate (the user needed five rounds), while a run still refuses the
    cell with the first one, in one line."""
    path = variant(tmp_path, (CURTAIN_HEIGHTS, "heights: [0.7, 0.8]"), *SMALLER)
    result = validate(path)
    assert result.returncode == 2
    fields = [field for field, _ in located(path, result.stderr)]
    curtain = "safety.sensors.light_curtains.opening.heights"
    scanner = "safety.sensors.scanners.front.fields[{}].protective"
    assert fields.count(curtain) == 2
    assert {scanner.format(k) for k in range(3)} <= set(fields)
    with pytest.raises(InputError) as refused:
        load_scenario(path)
    assert "\n" not in str(refused.value) and f"{path}:" in str(refused.value)


@pytest.mark.parametrize(
    ("heights", "says"),
    [
        (
            "[0.7, 1.5]",
            "the lowest beam is 0.7 m above the floor: a person crawls under it "
            "(ISO 13855 puts it at most 0.3 m high)",
        ),
        (
            "[0.3, 0.8]",
            "the highest beam is 0.8 m above the floor: a person steps or reaches over it "
            "(ISO 13855 puts it at least 0.9 m high)",
        ),
    ],
    ids=["crawl under", "reach over"],
)
def test_a_light_curtain_one_gets_past_over_or_under(tmp_path, heights, says):
    path = variant(tmp_path, (CURTAIN_HEIGHTS, f"heights: {heights}"))
    with pytest.raises(InputError) as raised:
        load_scenario(path)
    message = str(raised.value)
    assert re.match(
        rf"{re.escape(str(path))}:\d+: safety.sensors.light_curtains.opening.heights: ", message
    )
    assert says in message


def test_the_way_through_a_light_curtain_is_the_curtains_to_guard(tmp_path):
    """A place behind the curtain, 2.17 m from the reach straight through it, needs no
    scanner field: the curtain at its S guards that way, and round its posts the walk is
    longer than S. Without the curtain the same field is too small there."""
    path = variant(tmp_path, (FIELD_END, NOTCH))
    guarded = located(path, validate(path).stderr)
    assert not [m for _, m in guarded if "is in no protective field" in m], guarded
    unguarded = validate(variant(tmp_path, (FIELD_END, NOTCH), (CURTAIN, "")))
    assert re.search(
        r"a person at \[3\.5\d, -0\.\d\d\], \d\.\d\d m from the reach, is in no "
        r"protective field",
        unguarded.stderr,
    ), unguarded.stderr


def test_a_field_behind_a_fence_does_not_guard(tmp_path):
    """The user's round fields cross the fence behind the robot: there the scanner cannot see,
    and a person walking round the fence's end is within S of the reach, unseen."""
    path = variant(tmp_path, ("safety:\n", FENCES))
    result = validate(path)
    assert result.returncode == 2
    lines = located(path, result.stderr)
    full_speed = [m for f, m in lines if f == "safety.sensors.scanners.front.fields[0].protective"]
    assert full_speed, result.stderr
    for fence in ("fence_back_left", "fence_back_right"):
        assert re.search(
            rf"a person at \[-?\d\.\d\d, -\d\.\d\d\], \d\.\d\d m from the reach, is in the "
            rf"protective field of 'front', where the cell's {fence} hides them from the scanner",
            full_speed[0],
        ), full_speed[0]
