"""A machine-tending cell of our own (machine_cell/: an iisy 11 loads and unloads a machine
modelled as a cabinet with an opening; a person brings totes of raw parts from a rack,
inspects finished parts on an out tote and takes full totes to a shelf, empties to a stack
on the floor) validates cleanly: the put-downs onto the totes' places, emptied by earlier
picks of the same sequence, and onto the stack of empties are planned as the run puts them."""

from pathlib import Path

MACHINE_CELL = Path(__file__).resolve().parent / "machine_cell"


def test_the_machine_tending_cell_validates_cleanly(tmp_path, hrc_drake):
    for source in MACHINE_CELL.iterdir():
        text = source.read_text().replace("{dir}", str(tmp_path))
        (tmp_path / source.name).write_text(text)
    status, out, err = hrc_drake("validate", tmp_path / "cell.yaml")
    assert (status, err) == (0, "")
    assert "ok (machine_tending; trees robot: robot.xml, human: human.xml)" in out
