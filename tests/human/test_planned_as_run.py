"""`validate` plans the person's picks and put-downs for the person the run has, and both
refuse the same ones, saying the same (#26: two cut-down cells of a user's assembly station)."""

from hrc_drake.runner import run
from hrc_drake.scenario import load_scenario
from hrc_drake.scenario.findings import findings
from tests.human.user_cells import CELLS, copied
from tests.scenarios.realism_checks import assert_within_the_audit_limits

HEAD_IN_THE_RACK = "the head would go 2.5 cm into 'klt_rack'"


def test_a_small_person_by_percentile_is_planned_with_their_own_clips(tmp_path, hrc_drake):
    """`human: {percentile: 5}` with no sex, a 1.64 m man: the run refused his pick of a
    housing off a rack's 0.5 m board 55 times, the head 2.5 cm in the rack, and `validate`
    said ok: it planned his body with the clips of a 1.75 m person. Both now plan the
    same person, and `validate` says which person the percentile took."""
    cell = copied("small_man_rack", tmp_path)
    status, out, err = hrc_drake("validate", cell)
    assert status == 2 and "ActorPick" in err and HEAD_IN_THE_RACK in err, err
    assert "person: 5th-percentile male of ANSUR II, 1.643 m and 62.0 kg" in out, out
    report = run(load_scenario(cell))
    pick = report.metrics["bt"]["human"]["ActorPick::3"]
    assert pick["successes"] == 0 and HEAD_IN_THE_RACK in pick["first_failure"], pick


PALMS_OFF = "the arms kept out of the cell would leave the point between the palms 8 cm"


def test_a_large_mans_pick_is_judged_as_it_takes_over_from_him_at_ease(tmp_path, hrc_drake):
    """A user's kitting cell, cut down: a 95th-percentile man (1.87 m, 109 kg) takes an
    empty KLT off a 0.9 m table. The pick's plan itself keeps out of the table, and
    `validate` said ok; the run, taking over from him standing at ease, keeps the arms out
    of the table on the way up and refused it every time, the palms 8 cm from the KLT.
    `validate` now judges the pick as the run does, and says so on one line."""
    cell = copied("klt_off_the_table_large_man", tmp_path)
    status, _, err = hrc_drake("validate", cell)
    assert status == 2 and len(err.strip().splitlines()) == 1, err
    assert "node 'ActorPick::2'" in err and PALMS_OFF in err, err
    report = run(load_scenario(cell))
    pick = report.metrics["bt"]["human"]["ActorPick::2"]
    assert pick["successes"] == 0 and PALMS_OFF in pick["first_failure"], pick


OFF_THE_EDGE = CELLS / "off_the_edge" / "cell.yaml"
OFF_THE_TOP = (
    "where it is put is 15.0 cm off the top of 'table_b', nothing but the floor under it: "
    "put it on the top, at about (-1.00, 1.80, 0.77)"
)


def test_a_put_down_past_a_tables_edge_is_refused_by_validate_and_the_run():
    """A tray put down 15 cm past a table's front edge: the objects' world rested it on
    the table its footprint touched, in the air against the person's belly (2.5 cm in it),
    and `validate` said ok. Both now refuse it as on nothing, saying where on the top it
    would go; the person keeps it, within the audit's limits."""
    scenario = load_scenario(OFF_THE_EDGE)
    said = [f.message for f in findings(scenario, OFF_THE_EDGE)]
    assert len(said) == 1 and said[0].endswith(OFF_THE_TOP), said
    report = run(scenario)
    place = report.metrics["bt"]["human"]["ActorPlace::5"]
    assert place["successes"] == 0 and place["first_failure"].endswith(OFF_THE_TOP), place
    assert_within_the_audit_limits(report.metrics["realism"])


def test_a_put_down_on_a_flow_racks_top_board_is_done_whenever_it_comes(tmp_path, hrc_drake):
    """A user's machine-tending cell: a blank put on a flow rack's 1.4 m board. `validate`,
    planning it from the start of its clock, said ok; the run refused it when it came
    11.07 s in ("the right arm would go 3.2 cm into 'flow_rack'") and did it at 6.32 s:
    the arms' correction, checked again at half steps that missed its own instants by
    1e-16 from such a start, kept two keys side by side. It is the same whenever it
    comes: both say it is done, within the audit's limits (the hand 0.5 cm in the rack)."""
    _validated_and_done(hrc_drake, copied("flow_rack_top", tmp_path), "ActorPlace::6")


def test_a_tall_man_puts_a_blank_on_a_flow_racks_top_board(tmp_path, hrc_drake):
    """The same cell with a 95th-percentile man: the 1.4 m board is below his shoulders,
    yet both refused the put-down ("what the hands hold would go 3.0 cm into 'flow_rack'"):
    his hand, held as it took the blank, could not rise that close to his chest, and the
    way fell back to the straight one, through the board's edge. The palm now turns about
    its normal on the way up (the blank stays level): both say it is done, within the
    audit's limits."""
    cell = copied("flow_rack_top", tmp_path).with_name("tall_man.yaml")
    _validated_and_done(hrc_drake, cell, "ActorPlace::6")


def test_a_carton_carried_to_a_table_is_judged_put_down_where_the_carry_stops(tmp_path, hrc_drake):
    """A user's packing cell: a 5th-percentile woman carries a carton round to a labelling
    table. `validate` judged its put-down from the place she walks to, the carton 4.3 cm
    in the table, and said so at the run's start; the run's carry stopped 12 cm short,
    where the carton keeps out of the table, and put it down within the audit's limits.
    `validate` now plans the carry from where she took the carton, and says it is done."""
    cell = copied("carton_to_the_label_table", tmp_path)
    _validated_and_done(hrc_drake, cell, "ActorPlace::5")


def test_a_klt_brought_where_an_emptied_one_lay_is_put_down_there(tmp_path, hrc_drake):
    """A user's kitting cell: the robot takes the parts off a KLT on a table; once it is
    empty the person takes it to the rack table and brings a full one back to where it lay.
    `validate` planned that put-down with the parts still lying where they lay on the
    emptied KLT, gone with it ("what the hands hold would go 7.9 cm into 'part at (-0.30,
    0.80, 1.04)'"), and refused it; the run only takes a KLT with nothing on it. Both now
    put it down there, within the audit's limits."""
    _validated_and_done(hrc_drake, copied("klt_swap", tmp_path), "ActorPlace::15")


def test_a_klt_put_on_a_racks_board_under_another_keeps_under_that_board(tmp_path, hrc_drake):
    """A user's kitting cell: an empty KLT put on a rack's 0.4 m board, under its 1.2 m
    board, from 0.5 m in front of the rack. Carried 6.5 cm under the upper board, its way
    down (in the chest's frame, bulging up as the trunk leans in) was let go straight, and
    the KLT went 1.6 cm into that board's front edge; `validate` said ok. It now comes in
    under the board, then down: both say it is done, within the audit's limits."""
    _validated_and_done(hrc_drake, copied("klt_under_a_board", tmp_path), "ActorPlace::6")


def test_a_klt_taken_off_a_racks_board_under_another_keeps_under_that_board(tmp_path, hrc_drake):
    """The same cell: a KLT taken off that 0.4 m board from 0.5 m in front of the rack.
    In the carry posture it is below the upper board, so its way up was let go straight,
    bulging up as the trunk rose: "what the hands hold would go 6.8 cm into 'rack'", and
    the pick was refused (with no board above, it was done). It now keeps under the board
    until it is out: both say it is done, within the audit's limits."""
    cell = copied("klt_under_a_board", tmp_path).with_name("taken_off.yaml")
    _validated_and_done(hrc_drake, cell, "ActorPick::4")


def _validated_and_done(hrc_drake, cell, node: str) -> None:
    """`validate` says `cell` is ok, and its run does `node` once, refusing it never,
    within the audit's limits."""
    status, out, err = hrc_drake("validate", cell)
    assert status == 0 and out.rstrip().endswith(")") and ": ok (" in out, err
    report = run(load_scenario(cell))
    done = report.metrics["bt"]["human"][node]
    assert done["successes"] == 1 and done["failures"] == 0, done
    assert_within_the_audit_limits(report.metrics["realism"])


def test_a_klt_put_down_in_the_area_a_later_look_searches_is_judged_taken_from_there(
    tmp_path, hrc_drake
):
    """A user's kitting cell: the person puts an empty KLT on a rack's low board, then
    looks for a full one in an area drawn round the board above. An area is a floor
    polygon: the look found the empty one (the older), and the run refused its pick, where
    `validate` had judged only the objects lying there at the start and said ok. Here the
    empty one lies at the board's far end, out of reach of where the person stands for the
    full one (since 7313d7b a KLT is taken from under the board above, so the user's pick
    there works): validate refuses the pick on one line naming the put-down that left it."""
    status, _, err = hrc_drake("validate", copied("klt_on_the_low_board", tmp_path))
    lines = err.strip().splitlines()
    assert status == 2 and len(lines) == 1, err
    assert "node 'ActorPick::10'" in lines[0] and "put down by ActorPlace" in lines[0], err
    assert "out of reach: the hand stays" in lines[0], err
