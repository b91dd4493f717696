"""A new user's first cell (new_cell/: written from the README alone) validates cleanly; with
the mistakes such a user makes, validate names every one at once, each on its own line with
the file, the line and the field or node, where a run showed them one at a time or never."""

from pathlib import Path

NEW_CELL = Path(__file__).resolve().parent / "new_cell"
MISTAKES = {
    "cell.yaml": {
        # the person starts inside the work table (a run shows 0.36 m of them in it)
        "start: [0.0, 2.45, 90.0]": "start: [0.0, 3.0, 90.0]",
        # millimetres and grams: a crate 600 m long of 2 t
        "  objects:": "    crate: {shape: box, size: [600, 400, 300], mass: 2000}\n  objects:",
        # the tray's part put into the side table's top instead of onto it
        "translation: [0.0, 0.5, 0.77]}}": "translation: [0.0, 0.5, 0.74]}}",
        # radians where degrees are asked for
        "deg: [0, 0, -90]": "deg: [0, 0, -1.5708]",
        # the belt's height guessed (the conveyor model's belt is at 0.85 m)
        "start: [0.44, 0.0, 0.85]": "start: [0.44, 0.0, 0.9]",
        "end: [2.4, 0.0, 0.85]": "end: [2.4, 0.0, 0.9]",
        # a ready pose copied from another cell: here it puts the tool into the belt
        "ready: [0, -30, 120, 0, 0, 0]": "ready: [0, -45, 90, 0, 45, 0]",
        # a conveyor end beyond the arm's reach (tool down)
        "belt_place: {translation: [0.5,": "belt_place: {translation: [0.75,",
    },
    "human.xml": {'animation_name="inspect"': 'animation_name="assemble"'},
}
EXPECTED = [
    (
        "cell.yaml",
        "start: [0.44",
        "workpieces.conveyors.belt: its line at (0.44, 0.00, 0.90) lies 0.05 m above belt "
        "(objects on it would move in the air)",
    ),
    (
        "cell.yaml",
        "ready:",
        "robot.configurations_deg.ready: the link_6 and vacuum_gripper would touch belt there",
    ),
    ("cell.yaml", "crate:", "workpieces.types.crate.size: [600, 400, 300] m is larger than a"),
    ("cell.yaml", "crate:", "workpieces.types.crate.mass: 2000 kg is more than a person may"),
    ("cell.yaml", "-1.5708", "locations.tray_front.rotation.deg[2]: -1.5708 looks like radians"),
    (
        "cell.yaml",
        "0.74]}}",
        "workpieces.objects[0].pose: the part at (0.00, 0.50, 0.74) starts 0.030 m inside "
        "side_table (to rest on it, raise its centre 0.030 m to z = 0.770)",
    ),
    (
        "cell.yaml",
        "start:",
        "human.start: (0.00, 3.00) lies within the floor outline of bench: the nearest place "
        "with room to stand and turn is [0.00, 2.47]",
    ),
    (
        "robot.xml",
        'RobotMove target="{over}"',
        "port 'target': the value OffsetPose (robot.xml:24) made from location 'belt_place' at "
        "(0.75, 0.00, 0.99): out of reach with the tool pointing down: 0.75 m from its base axis",
    ),
    (
        "robot.xml",
        'RobotMoveLinear target="{to}"',
        "port 'target': location 'belt_place' at (0.75, 0.00, 0.90): out of reach",
    ),
    (
        "robot.xml",
        'RobotMoveLinear target="{over}"',
        "port 'target': the value OffsetPose (robot.xml:24) made from location 'belt_place' at "
        "(0.75, 0.00, 0.99): out of reach",
    ),
    (
        "human.xml",
        'animation_name="assemble"',
        "port 'animation_name': no animation named 'assemble'",
    ),
]


def copy_of_the_cell(directory: Path, mistakes: dict) -> Path:
    for name in ("cell.yaml", "robot.xml", "human.xml"):
        text = (NEW_CELL / name).read_text()
        for old, new in mistakes.get(name, {}).items():
            assert old in text, (name, old)
            text = text.replace(old, new)
        (directory / name).write_text(text)
    return directory / "cell.yaml"


def line_of(path: Path, text: str) -> int:
    return next(i for i, line in enumerate(path.read_text().splitlines(), 1) if text in line)


def test_the_new_users_cell_validates_cleanly(tmp_path, hrc_drake):
    status, out, err = hrc_drake("validate", copy_of_the_cell(tmp_path, {}))
    assert (status, err) == (0, "")
    assert "ok (my_cell; trees robot: robot.xml, human: human.xml)" in out


def test_every_mistake_in_the_new_users_cell_is_one_located_line(tmp_path, hrc_drake):
    status, _, err = hrc_drake("validate", copy_of_the_cell(tmp_path, MISTAKES))
    assert status == 2
    lines = err.splitlines()
    assert all(line.startswith("hrc-drake: error: ") for line in lines)
    assert len(lines) == len(EXPECTED), err
    for name, at, says in EXPECTED:
        place = f"{tmp_path / name}:{line_of(tmp_path / name, at)}: "
        assert sum(place in line and says in line for line in lines) == 1, (place, says, err)
