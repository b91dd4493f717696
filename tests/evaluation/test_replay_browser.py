"""replay.html as a user sees it: opened in headless Chromium (tests/browser.py), the
animation sought to a carry and to a hand-over (the times and holders come from the run's own
timeline in the page), the held object must touch the holding hand(s) in the page's three.js
scene, and the canvas must show the scene.
"""

import json
from pathlib import Path

import numpy as np
import pytest
from matplotlib.image import imread

from hrc_drake.evaluation.realism import over_limits, realism_verdict
from hrc_drake.runner import run
from hrc_drake.scenario import load_scenario
from tests.browser import chromium_page, opened

SCENARIO = Path(__file__).resolve().parents[2] / "scenarios" / "collaboration.yaml"
SEED = 15
"""Its first box is porous (the person carries it to the belt), its second fragile (the
robot hands it over): both happen in the first 40 s."""
DURATION = 42.0
HAND_GAP = 0.02
"""m: the held object's surface lies within this of the holding hand's surface (outside it
or inside it)."""
MB_PER_MINUTE = 5.0
LOAD_TIMEOUT = 120_000
"""ms the page may take to load its animation (a busy machine takes more than 30 s)"""

GAPS_JS = """
(span) => {
  const object3d = (path) => viewer.scene_tree.find(path.split("/").filter((x) => x)).object;
  const meshes = (root) => {
    const found = [];
    root.traverse((o) => { if (o.isMesh) found.push(o); });
    return found;
  };
  viewer.scene.updateMatrixWorld(true);
  const box = meshes(object3d(span.object))[0];
  box.geometry.computeBoundingBox();
  const Vector3 = box.position.constructor, Matrix4 = box.matrixWorld.constructor;
  const position = new Vector3(), scale = new Vector3(), quaternion = box.quaternion.clone();
  box.matrixWorld.decompose(position, quaternion, scale);
  const toBox = new Matrix4().compose(position, quaternion, new Vector3(1, 1, 1)).invert();
  const low = box.geometry.boundingBox.min.clone().multiply(scale);
  const high = box.geometry.boundingBox.max.clone().multiply(scale);
  const signedDistance = (p) => {
    const d = [low.x - p.x, p.x - high.x, low.y - p.y, p.y - high.y, low.z - p.z, p.z - high.z];
    const out = [Math.max(d[0], d[1]), Math.max(d[2], d[3]), Math.max(d[4], d[5])];
    const outside = Math.hypot(...out.map((v) => Math.max(v, 0)));
    return outside + Math.min(Math.max(...out), 0);
  };
  return span.hands.map((hand) => {
    let nearest = Infinity;
    for (const mesh of meshes(object3d(hand))) {
      const vertices = mesh.geometry.attributes.position;
      for (let i = 0; i < vertices.count; i++) {
        const p = new Vector3().fromBufferAttribute(vertices, i).applyMatrix4(mesh.matrixWorld);
        nearest = Math.min(nearest, signedDistance(p.applyMatrix4(toBox)));
      }
    }
    return nearest;
  });
}
"""


@pytest.fixture(scope="module")
def replay(tmp_path_factory) -> Path:
    out = tmp_path_factory.mktemp("collaboration")
    report = run(load_scenario(SCENARIO), seed=SEED, duration=DURATION, out_dir=out)
    return report.files["replay"]


@pytest.fixture(scope="module")
def page(replay):
    yield from open_page(replay)


def open_page(replay: Path):
    """The replay opened in headless Chromium, its animation loaded (a generator: the
    browser closes when it is resumed)."""
    with chromium_page() as page:
        yield loaded(page, replay)


def loaded(page, replay: Path):
    """`page` showing the replay, its animation loaded."""
    opened(page, replay)
    ready = "() => window.viewer && viewer.animator.actions.length > 0"
    page.wait_for_function(ready, timeout=LOAD_TIMEOUT)
    return page


def timeline(page) -> dict:
    return json.loads(page.locator("#hrc-replay").text_content())


def seek(page, time: float) -> None:
    page.evaluate(f"() => {{ viewer.animator.pause(); viewer.animator.seek({time}); }}")
    page.wait_for_timeout(300)


def person_spans(page) -> list[dict]:
    return [span for span in timeline(page)["held"] if span["hands"]]


def handed_over(span: dict, spans: list[dict]) -> bool:
    """The person took the object from the robot's gripper."""
    return any(
        other["object"] == span["object"]
        and other["holder"] == "robot"
        and abs(other["end"] - span["start"]) < 0.1
        for other in spans
    )


SAMPLE_EVERY = 0.5
"""s between the moments checked along a span (walking, turning, standing, placing)."""


def loose_grips(page, span: dict) -> list[str]:
    """The moments of `span` at which a holding hand is not on the held object."""
    loose = []
    for time in np.arange(span["start"] + 0.1, span["end"] - 0.1, SAMPLE_EVERY):
        seek(page, time)
        gaps = page.evaluate(GAPS_JS, span)
        if np.any(np.abs(gaps) > HAND_GAP):
            loose.append(f"{time:.1f} s: {np.round(gaps, 3).tolist()} m")
    return loose


def test_a_carried_object_stays_in_both_hands(page):
    held = timeline(page)["held"]
    carries = [s for s in person_spans(page) if not handed_over(s, held)]
    assert carries, "no carry in the run"
    carry = carries[0]
    assert len(carry["hands"]) == 2  # a box is carried in both hands
    loose = loose_grips(page, carry)
    assert not loose, f"{carry['object']} held by {carry['holder']}, gaps at " + "; ".join(loose)


def test_a_handed_over_object_stays_in_the_hands_that_took_it(page):
    held = timeline(page)["held"]
    handovers = [s for s in person_spans(page) if handed_over(s, held)]
    assert handovers, "no hand-over in the run"
    handover = handovers[0]
    loose = loose_grips(page, handover)
    assert not loose, f"{handover['object']} held by {handover['holder']}, gaps at " + "; ".join(
        loose
    )


def test_the_canvas_shows_the_scene(page, tmp_path):
    seek(page, 1.0)
    shot = tmp_path / "canvas.png"
    page.locator("canvas").first.screenshot(path=shot)
    pixels = imread(shot)[..., :3]
    colours = np.unique((pixels * 255).astype(np.uint8).reshape(-1, 3), axis=0)
    assert pixels.std() > 0.05 and len(colours) > 500, "the canvas is blank"


def test_the_caption_shows_the_robots_safety_state(page):
    states = timeline(page)["safety"]
    assert {state for _, state in states} >= {"full speed", "stopped"}
    start, state = next((t, s) for t, s in states if s == "stopped")
    seek(page, start + 0.05)
    page.wait_for_timeout(200)
    assert page.locator("#hrc-caption").text_content().endswith("robot: stopped")
    shown = page.evaluate(
        """() => Object.entries(viewer.scene_tree.find(["drake", "safety_ring"]).children)
                 .filter(([name, node]) => node.object.visible).map(([name]) => name)"""
    )
    assert shown == ["stopped"]


def test_the_replay_is_small(replay):
    megabytes = replay.stat().st_size / 1e6
    assert megabytes <= MB_PER_MINUTE * DURATION / 60, f"{megabytes:.1f} MB"


def test_the_runs_report_page_opens_with_its_realism_verdict(page, replay):
    """The page of the same run (in a tab beside the replay): the audit's verdict first, as
    report.json has it, marked red when a measure is beyond its limit."""
    metrics = json.loads((replay.parent / "report.json").read_text())
    over = over_limits(metrics["realism"])
    report = opened(page.context.new_page(), replay.parent / "report.html")
    verdict = report.locator("#realism-verdict")
    assert verdict.is_visible()
    assert verdict.inner_text() == "The person's realism audit: " + "; ".join(
        realism_verdict(metrics["realism"])
    )
    assert (verdict.evaluate("(e) => e.className") == "flagged") == bool(over)
    assert verdict.bounding_box()["y"] < report.locator("img").first.bounding_box()["y"]
    report.close()
