"""`validate` plans the person's picks and put-downs for the person the run has, and both
refuse the same ones, saying the same (#26: two cut-down cells of a user's assembly station)."""

from pathlib import Path

from hrc_drake.runner import run
from hrc_drake.scenario import load_scenario

CELLS = Path(__file__).resolve().parent / "cells"
HEAD_IN_THE_RACK = "the head would go 2.5 cm into 'klt_rack'"


def _copied(cell: str, to: Path) -> Path:
    """The cell's files in `to`, its `{dir}` there (its own rack model's URL)."""
    for source in (CELLS / cell).iterdir():
        (to / source.name).write_text(source.read_text().replace("{dir}", str(to)))
    return to / "cell.yaml"


def test_a_small_person_by_percentile_is_planned_with_their_own_clips(tmp_path, hrc_drake):
    """`human: {percentile: 5}` with no sex, a 1.64 m man: the run refused his pick of a
    housing off a rack's 0.5 m board 55 times, the head 2.5 cm in the rack, and `validate`
    said ok: it planned his body with the clips of a 1.75 m person. Both now plan the
    same person, and `validate` says which person the percentile took."""
    cell = _copied("small_man_rack", tmp_path)
    status, out, err = hrc_drake("validate", cell)
    assert status == 2 and "ActorPick" in err and HEAD_IN_THE_RACK in err, err
    assert "person: 5th-percentile male of ANSUR II, 1.643 m and 62.0 kg" in out, out
    report = run(load_scenario(cell))
    pick = report.metrics["bt"]["human"]["ActorPick::3"]
    assert pick["successes"] == 0 and HEAD_IN_THE_RACK in pick["first_failure"], pick
