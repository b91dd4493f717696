"""The safety sensors in replay.html as a user sees them, in headless Chromium: the guarded
cell's person walks in and stands left of the table (seen by the scanner, the robot slows
and stops), or walks round the robot to the corner behind the shelf of cartons (not seen
there). Sought to the stop, the caption says the person is seen, the active field set's
occupied fields are shown and the detection markers sit on the person's lower legs in the
page's three.js scene; sought into the blind spot, the caption says not seen, the markers
are parked out of sight and the fields show clear.
"""

import json

import numpy as np
import pytest

from hrc_drake.runner import run
from hrc_drake.safety.log import read_safety_log
from hrc_drake.scenario import load_scenario
from tests.browser import chromium_page
from tests.evaluation.test_replay_browser import loaded, seek

DURATION = 11.0
STILL_UPDATES = 30
"""monitor updates (0.3 s) the person stands in one place before the markers are checked"""
HIDDEN = 1.0
"""s the person is out of the scanner's view at least, behind the shelf (brief gaps on the
way, behind the robot's pedestal, are not the blind spot)"""
STAND_STILL = 0.015
"""m the body's centre moves at most meanwhile"""
ON_LEG = 0.06
"""m: a marker lies this close to the box round a lower leg's visual mesh: it is on the
collision capsule, which the mesh follows within a centimetre, up to the scanner's
measurement error (0.05 m)"""

VISIBLE_JS = """
() => {
  const found = [];
  const walk = (node, path) => {
    if (!node.object.visible) return;
    if ("<object>" in node.children) found.push(path);
    for (const [name, child] of Object.entries(node.children)) walk(child, path + "/" + name);
  };
  walk(viewer.scene_tree.find(["drake", "sensors"]), "");
  return found;
}
"""
"""The sensors' drawn objects that are shown, by path below /drake/sensors."""

MARKERS_JS = """
() => {
  viewer.scene.updateMatrixWorld(true);
  const root = viewer.scene_tree.find(["drake", "sensors", "detections"]);
  const legs = [];
  for (const side of ["left", "right"]) {
    viewer.scene_tree.find(["drake", "visual", "human", side + "_shank"]).object.traverse((o) => {
      if (o.isMesh) { o.geometry.computeBoundingBox(); legs.push(o); }
    });
  }
  const boxDistance = (mesh, worldPoint) => {
    const p = worldPoint.clone().applyMatrix4(mesh.matrixWorld.clone().invert());
    const low = mesh.geometry.boundingBox.min, high = mesh.geometry.boundingBox.max;
    const out = [Math.max(low.x - p.x, p.x - high.x), Math.max(low.y - p.y, p.y - high.y),
                 Math.max(low.z - p.z, p.z - high.z)];
    return Math.hypot(...out.map((v) => Math.max(v, 0))) + Math.min(Math.max(...out), 0);
  };
  return Object.values(root.children).map((marker) => {
    const p = marker.object.position.clone().applyMatrix4(marker.object.parent.matrixWorld);
    const gaps = legs.map((leg) => Math.abs(boxDistance(leg, p)));
    return [marker.object.position.z, Math.min(...gaps)];
  });
}
"""
"""Per detection marker: its height in the cell, and how far it is from the surface of the
box round the nearest of the person's lower legs (both in the page's scene)."""


def visiting(area: str, tmp_path_factory):
    scenario = load_scenario("guarded_cell", [("parameters.visit_area", area)])
    return run(scenario, duration=DURATION, out_dir=tmp_path_factory.mktemp(area))


@pytest.fixture(scope="module")
def report(tmp_path_factory):
    """The person stands left of the table, in the scanner's view."""
    return visiting("left_side", tmp_path_factory)


@pytest.fixture(scope="module")
def hidden(tmp_path_factory):
    """The person goes behind the shelf."""
    return visiting("right_side", tmp_path_factory)


@pytest.fixture(scope="module")
def browser():
    """One browser for both runs (two playwright drivers at once are refused)."""
    with chromium_page() as page:
        yield page


@pytest.fixture
def page(browser, report):
    return loaded(browser, report.files["replay"])


@pytest.fixture
def hidden_page(browser, hidden):
    return loaded(browser, hidden.files["replay"])


def standing_seen(report) -> float:
    """A moment the robot is stopped for the person, who has stood in one place (their
    body's centre within STAND_STILL) for a while, seen all along: the detections, a
    response time old, are where the legs are."""
    log = read_safety_log(report.files["safety_log"])
    centre = np.stack([log["person_x"], log["person_y"]], axis=1)
    moved = np.linalg.norm(centre[STILL_UPDATES:] - centre[:-STILL_UPDATES], axis=1)
    watched = (log["seen"] > 0) & (log["scale"] == 0.0)
    held = np.convolve(watched, np.ones(STILL_UPDATES + 1), "valid") == STILL_UPDATES + 1
    return float(log["time"][STILL_UPDATES:][(moved < STAND_STILL) & held][0])


def timeline(page) -> dict:
    return json.loads(page.locator("#hrc-replay").text_content())


def caption(page) -> str:
    page.wait_for_timeout(200)
    return page.locator("#hrc-caption").text_content()


def test_seen_and_stopped_the_fields_and_markers_show_the_person(page, report):
    seek(page, standing_seen(report))
    assert caption(page).endswith("robot: stopped · person seen")
    shown = page.evaluate(VISIBLE_JS)
    assert "/front/set_1/protective/occupied" in shown, shown
    assert "/front/set_1/protective/clear" not in shown
    assert not [path for path in shown if "/set_0/" in path], "the fast set is not active"
    markers = np.array(page.evaluate(MARKERS_JS))
    on_person = markers[markers[:, 0] > 0.0]
    assert len(on_person) >= 2, "no detection markers shown"
    np.testing.assert_allclose(on_person[:, 0], 0.3, atol=1e-3)  # the scan plane
    assert on_person[:, 1].max() <= ON_LEG


def test_behind_the_shelf_the_person_is_not_seen(hidden_page):
    page = hidden_page
    changes = [(t, bool(flag)) for t, flag in timeline(page)["seen"]]
    ends = [t for t, _ in changes[1:]] + [DURATION]
    hidden = [
        t
        for (t, flag), end in zip(changes, ends, strict=True)
        if not flag and t > 1.0 and end - t >= HIDDEN
    ]
    assert hidden, "the person was never out of view for long"
    seek(page, hidden[0] + HIDDEN / 2)
    assert caption(page).endswith("person not seen")
    markers = np.array(page.evaluate(MARKERS_JS))
    assert np.all(markers[:, 0] < -5.0), "markers shown where nothing is seen"
    shown = page.evaluate(VISIBLE_JS)
    fields = [path for path in shown if "/set_" in path]
    assert fields and all(path.endswith("/clear") for path in fields), shown
