"""report.html of a run and of a sweep as a reader sees them in a browser (headless
Chromium, tests/browser.py): the verdicts come first and are marked when they are bad news,
safety and productivity lead the sweep's page, and the behaviour trees' statistics are
folded away at its end."""

import pytest

from hrc_drake.evaluation.run_report import write_run_html
from hrc_drake.evaluation.sweep_report import summarize, sweep_html
from tests.browser import chromium_page, opened
from tests.evaluation.test_verdicts import OVER, ROWS, realism

RED, GREEN = "rgb(248, 215, 211)", "rgb(227, 241, 227)"
"""The backgrounds of bad news and of good news (evaluation/html.py's style)."""


@pytest.fixture(scope="module")
def page():
    with chromium_page() as page:
        yield page


def background(locator) -> str:
    return locator.evaluate("(e) => getComputedStyle(e).backgroundColor")


def test_a_run_over_the_realism_limits_says_so_above_everything_else(page, tmp_path):
    metrics = {"scenario": "cell", "seed": 3, "realism": OVER, "safety": {"stops": 1}}
    files = {"timeline": tmp_path / "timeline.png"}
    opened(page, write_run_html(tmp_path / "report.html", metrics, files))
    verdict = page.locator("#realism-verdict")
    assert verdict.is_visible() and background(verdict) == RED
    assert verdict.inner_text() == (
        "The person's realism audit: 3 of 7 measures over their limits; worst: body in the "
        "cell's geometry 16.3 cm (limit 1 cm): pelvis in work_table at 36.2 s; also: "
        "standing foot slid 3.8 cm (limit 1 cm): right_heel at 12.0 s; also: carried object "
        "tilted 20.0° (limit 15°): box 3 at 50.5 s"
    )
    below_title = page.locator("h1").bounding_box()
    box = verdict.bounding_box()
    assert below_title["y"] < box["y"] < page.locator("img").bounding_box()["y"]
    assert box["y"] + box["height"] < page.viewport_size["height"]  # seen without scrolling
    rows = page.locator("h2:text('Realism') + table tr")
    flagged = {
        rows.nth(k).locator("td").first.inner_text()
        for k in range(1, rows.count())
        if background(rows.nth(k)) == RED
    }
    assert flagged == {"penetration_static", "foot_slip", "carried_tilt_deg"}


def test_a_run_within_the_limits_says_so_in_green(page, tmp_path):
    metrics = {"scenario": "cell", "seed": 3, "realism": realism()}
    opened(page, write_run_html(tmp_path / "report.html", metrics, {}))
    verdict = page.locator("#realism-verdict")
    assert verdict.inner_text() == "The person's realism audit: within its limits (7 measures)"
    assert background(verdict) == GREEN


def bt_statistics(nodes: int) -> dict:
    stats = {"ticks": 10, "successes": 9, "failures": 1, "time_running": 2.5}
    return {"robot": {f"Main::1/Step{k}::{k + 2}": stats for k in range(nodes)}}


@pytest.fixture
def sweep_page(page, tmp_path):
    rows = [{**row, "metrics": {**row["metrics"], "bt": bt_statistics(75)}} for row in ROWS]
    html = tmp_path / "report.html"
    html.write_text(sweep_html(summarize(rows, "Refill cell", "cell.yaml"), None))
    return opened(page, html)


def test_the_sweep_leads_with_its_verdict_safety_and_productivity(sweep_page):
    assert sweep_page.title() == "sweep Refill cell"
    assert sweep_page.locator("h1").inner_text() == "Sweep of Refill cell: 4 runs (0 failed)"
    verdict = sweep_page.locator("#verdict-0")
    assert verdict.inner_text() == (
        "as written: 1 of 4 runs violate ISO/TS 15066 (a safety margin below 0); 2 of 4 runs "
        "over the realism audit's limits (carried_tilt_deg in 1, foot_slip in 2, "
        "penetration_static in 1)"
    )
    assert background(verdict) == RED
    headings = sweep_page.locator("h2").all_inner_texts()
    assert headings[0] == "Safety and productivity"
    headline = {
        row[0]: row[1:]
        for row in (
            r.locator("td").all_inner_texts()
            for r in sweep_page.locator("h2:text('Safety and productivity') + table tr").all()
        )
        if row
    }
    assert headline["runs that violate ISO/TS 15066"] == ["1 of 4"]
    assert headline["safety margin (m)"] == ["0.2 [-0.07, 0.29] (3 of 4 runs)"]
    assert headline["inspect_conveyor per run"] == ["0 [0, 0.85]"]
    assert headline["runs over the realism audit's limits"] == [
        "2 of 4 (carried_tilt_deg in 1, foot_slip in 2, penetration_static in 1)"
    ]


def test_the_trees_statistics_are_folded_at_the_end(sweep_page):
    folded = sweep_page.locator("details#tree-statistics")
    assert folded.locator("summary").inner_text() == (
        "The behaviour trees: 300 statistics of their nodes"
    )
    assert not folded.locator("table").is_visible()
    last = sweep_page.locator("body > *").last
    assert last.evaluate("(e) => e.id") == "tree-statistics"
    page_height = sweep_page.evaluate("() => document.body.scrollHeight")
    assert page_height < 3000  # 300 rows of tree statistics would be far longer
    folded.locator("summary").click()
    assert folded.locator("table tr").count() == 301
