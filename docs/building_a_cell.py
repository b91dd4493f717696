"""Makes what docs/building-a-cell.md shows and reads the guide's snippets back out of it:
the catalogue of the cell models (a picture of each in docs/building-a-cell/, their sizes
and heights written into the guide between its `catalogue` markers), the layout of the
guide's cell with each robot variant, and a screenshot of its replay taken in headless
Chromium (playwright, as tests/evaluation/test_replay_browser.py drives it).

    .venv/bin/python docs/building_a_cell.py [--check] [--skip-layouts] [--skip-replay]

`--check` prints the catalogue without writing anything. tests/docs/test_building_a_cell.py
builds the guide's cell from its snippets (`guide_files`) and checks the catalogue.
"""

import argparse
import re
import shutil
import tempfile
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from pydrake.geometry import Box, Cylinder  # noqa: E402
from pydrake.multibody.parsing import Parser  # noqa: E402
from pydrake.multibody.plant import AddMultibodyPlantSceneGraph  # noqa: E402
from pydrake.systems.framework import DiagramBuilder  # noqa: E402
from shapely.geometry import MultiPoint  # noqa: E402

from hrc_drake.human.navigation import cell_obstacles  # noqa: E402
from hrc_drake.iisy import VARIANTS  # noqa: E402
from hrc_drake.layout import layout_of, write_layout  # noqa: E402
from hrc_drake.layout.cell import furniture  # noqa: E402
from hrc_drake.paths import MODEL_PACKAGE, add_model_package, resource_dir  # noqa: E402
from hrc_drake.scenario import load_scenario  # noqa: E402
from hrc_drake.scene_geometry import anchored_collision_shapes  # noqa: E402

DOCS = Path(__file__).resolve().parent
GUIDE = DOCS / "building-a-cell.md"
PICTURES = DOCS / "building-a-cell"
BEGIN, END = "<!-- catalogue:begin -->", "<!-- catalogue:end -->"
NOT_FURNITURE = ("floor", "box_large", "box_small", "part_medium", "part_small")
"""Models of models/cell/ that are not furniture: the floor lies under all, the boxes and
parts are centred on their frame (objects' shapes, for a fixture at a height)."""
SNIPPET = re.compile(r"^```(yaml|xml) file=(\S+)\n(.*?)^```$", re.MULTILINE | re.DOTALL)
FENCE = re.compile(r"^```(yaml|xml)\b", re.MULTILINE)
REPLAY_TIME = 12.0
"""s into the guide's run where the screenshot is taken."""


def guide_files(text: str) -> dict[str, str]:
    """The guide's files from its snippets: every ```yaml or ```xml block names its file
    (`file=cell.yaml`), and the blocks of one file follow each other in it."""
    blocks = SNIPPET.findall(text)
    if len(blocks) != len(FENCE.findall(text)):
        raise ValueError("a yaml or xml snippet of the guide names no file (file=NAME)")
    files: dict[str, str] = {}
    for _, name, body in blocks:
        files[name] = files.get(name, "") + body
    return files


def write_guide_cell(folder: Path) -> Path:
    """The guide's files written into `folder`; the scenario's path."""
    for name, text in guide_files(GUIDE.read_text()).items():
        (folder / name).write_text(text)
    return folder / "cell.yaml"


def cell_models() -> list[str]:
    return sorted(
        p.stem
        for p in (resource_dir("models") / "cell").glob("*.sdf")
        if p.stem not in NOT_FURNITURE
    )


def model_plant(name: str):
    """One cell model welded at the origin, as a scenario's `add_weld` puts it."""
    builder = DiagramBuilder()
    plant, scene_graph = AddMultibodyPlantSceneGraph(builder, 0.0)
    parser = Parser(plant)
    add_model_package(parser.package_map())
    (instance,) = parser.AddModels(url=f"package://{MODEL_PACKAGE}/cell/{name}.sdf")
    plant.RenameModelInstance(instance, name)
    plant.WeldFrames(plant.world_frame(), plant.GetFrameByName("body", instance))
    plant.Finalize()
    return plant, scene_graph.model_inspector()


def catalogue() -> str:
    """The guide's table of the cell models: footprint, the heights of the faces things go
    on (to the millimetre: an object's centre is put half its height above one) and of their
    highest point."""
    rows = [
        "| model | file | footprint x × y (m) | surfaces (m) | top (m) |",
        "|---|---|---|---|---|",
    ]
    for name in cell_models():
        plant, inspector = model_plant(name)
        (piece,) = furniture(cell_obstacles(plant, inspector))
        x0, y0, x1, y1 = piece.outline.bounds
        surfaces = ", ".join(f"{z:.3f}" for z in _surfaces(plant, inspector, piece.outline.area))
        rows.append(
            f"| {name} ![{name}](building-a-cell/{name}.png) "
            f"| `package://{MODEL_PACKAGE}/cell/{name}.sdf` | {x1 - x0:.2f} × {y1 - y0:.2f} "
            f"| {surfaces} | {piece.top:.3f} |"
        )
    return "\n".join(rows)


def _surfaces(plant, inspector, footprint: float) -> list[float]:
    """The tops of a model's boxes that cover at least half its footprint: a table's top, a
    pallet's deck, each of a shelf's boards (a user put totes on boards guessed from the
    shelf's lowest), not a rail or a post."""
    tops = {
        round(X_WG.translation()[2] + shape.height() / 2, 3)
        for _, shape, X_WG in anchored_collision_shapes(plant, inspector)
        if isinstance(shape, Box) and shape.width() * shape.depth() >= footprint / 2
    }
    return sorted(tops)


def draw_model(name: str, path: Path) -> None:
    """Its collision shapes from above and from the front (x to the right)."""
    plant, inspector = model_plant(name)
    figure, (top, front) = plt.subplots(1, 2, figsize=(5.0, 2.4))
    for _, shape, X_WG in anchored_collision_shapes(plant, inspector):
        points = np.array([X_WG @ p for p in _surface_points(shape)])
        for ax, (i, j) in ((top, (0, 1)), (front, (0, 2))):
            hull = MultiPoint(points[:, [i, j]].tolist()).convex_hull
            ax.fill(*hull.exterior.xy, facecolor="#d9c7a3", edgecolor="#5b4a2f", lw=0.6, alpha=0.7)
    for ax, title, label in ((top, "from above", "y (m)"), (front, "from the front", "z (m)")):
        ax.set_aspect("equal")
        ax.set_title(f"{name}: {title}", fontsize=8)
        ax.set_xlabel("x (m)", fontsize=7)
        ax.set_ylabel(label, fontsize=7)
        ax.tick_params(labelsize=6)
        ax.grid(True, lw=0.3)
    figure.tight_layout()
    figure.savefig(path, dpi=80, metadata={"Software": None})
    plt.close(figure)


def _surface_points(shape) -> list[np.ndarray]:
    """Corners of a box, points round both ends of a cylinder (in its frame)."""
    if isinstance(shape, Box):
        half = np.array([shape.width(), shape.depth(), shape.height()]) / 2
        return [half * np.array([x, y, z]) for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)]
    if isinstance(shape, Cylinder):
        r, h = shape.radius(), shape.length() / 2
        angles = np.linspace(0, 2 * np.pi, 24, endpoint=False)
        return [np.array([r * np.cos(a), r * np.sin(a), z]) for a in angles for z in (-h, h)]
    raise ValueError(f"no picture of a {type(shape).__name__}")


def write_catalogue(check: bool) -> None:
    table = catalogue()
    if check:
        print(table)
        return
    text = GUIDE.read_text()
    before, rest = text.split(BEGIN)
    _, after = rest.split(END)
    GUIDE.write_text(f"{before}{BEGIN}\n{table}\n{END}{after}")
    for name in cell_models():
        draw_model(name, PICTURES / f"{name}.png")


def write_variant_layouts(folder: Path) -> None:
    """The guide's cell seen with each variant on its pedestal: what it reaches there."""
    path = write_guide_cell(folder)
    for variant in VARIANTS:
        scenario = load_scenario(path, [("robot.variant", variant)])
        write_layout(layout_of(scenario, path), PICTURES / f"layout-{variant}.png")
        print(PICTURES / f"layout-{variant}.png")


def write_replay_screenshot(folder: Path) -> None:
    """The guide's run for a few seconds, its replay.html opened in headless Chromium and
    its canvas saved: what the guide's last step shows."""
    from playwright.sync_api import sync_playwright

    from hrc_drake.runner import run

    path = write_guide_cell(folder)
    run(load_scenario(path), duration=REPLAY_TIME + 1.0, out_dir=folder / "run")
    with sync_playwright() as playwright:
        browser = playwright.chromium.launch(
            executable_path=shutil.which("chromium"), args=["--no-sandbox", "--disable-gpu"]
        )
        page = browser.new_page(viewport={"width": 1000, "height": 600})
        page.goto((folder / "run" / "replay.html").as_uri())
        page.wait_for_function("() => window.viewer && viewer.animator.actions.length > 0")
        page.evaluate(f"() => {{ viewer.animator.pause(); viewer.animator.seek({REPLAY_TIME}); }}")
        page.wait_for_timeout(1000)
        page.screenshot(path=PICTURES / "replay.png")
        browser.close()
    print(PICTURES / "replay.png")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--check", action="store_true", help="print the catalogue only")
    parser.add_argument("--skip-layouts", action="store_true")
    parser.add_argument("--skip-replay", action="store_true")
    args = parser.parse_args()
    write_catalogue(args.check)
    if args.check:
        return
    with tempfile.TemporaryDirectory() as folder:
        if not args.skip_layouts:
            write_variant_layouts(Path(folder))
        if not args.skip_replay:
            write_replay_screenshot(Path(folder))


if __name__ == "__main__":
    main()
