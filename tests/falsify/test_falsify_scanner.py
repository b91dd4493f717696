"""`hrc-drake falsify` finds the blind spot of the guarded cell (one laser scanner, a shelf of
cartons shadowing the corner behind it): within 8 trials of where the person goes, the
search finds a run in which the monitor, seeing nothing, let the robot run at full speed
beside the person, and the run's margin (judged on the real body) is below zero; 8 seeds of
the cell as written (the person watching from the walkway, in the scanner's view) find none.
The worst case is the blind spot: the person stood right of the table, behind the shelf,
and the scanner did not see them for a while.

12 s runs: the person reaches their place and reaches in within 10 s.
"""

import pytest

from hrc_drake.falsify import falsify, prepare
from hrc_drake.sweep import parse_seeds, plan, sweep

RUNS = (("duration", 12.0),)
BUDGET = 8
BLIND_SPOT = "right_side"
"""The area behind the shelf of cartons, as the scanner sees it"""
NOT_SEEN = 0.3
"""s the worst case's person is not seen at least (the person stands there for seconds)"""


@pytest.mark.long
def test_the_search_finds_the_blind_spot_where_as_many_seeds_find_none(tmp_path):
    search = prepare("guarded_cell", 0, RUNS)
    found = falsify(search, BUDGET, tmp_path / "search", workers=2)
    assert found.violations and not found.failed
    worst = found.worst[0]
    assert worst.margin["violation"] and worst.values["side"] == BLIND_SPOT
    assert worst.row["metrics"]["sensing"]["time_not_seen"] >= NOT_SEEN
    seeds = plan(search.scenario_path, parse_seeds(f"0:{BUDGET}"), ["duration=12"])
    rows = sweep(seeds, tmp_path / "seeds", 2).rows
    assert all(row["status"] == "ok" for row in rows)
    assert not any(row["metrics"]["margin"]["violation"] for row in rows)
