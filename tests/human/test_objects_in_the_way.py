"""Objects on the cell are in the person's way as the furniture is: walks go round them and
`validate` names a place to stand with no room beside one (#26: the cell's map held only
the furniture)."""

from hrc_drake.runner import run
from hrc_drake.scenario import load_scenario
from tests.human.user_cells import CELLS
from tests.scenarios.realism_checks import assert_within_the_audit_limits

CRATE = CELLS / "crate_on_the_floor" / "cell.yaml"
NO_ROOM = (
    "locations.by_the_crate: a person at (0.00, 0.60) facing 90°, turning on the spot, "
    "reaches 0.06 m into the crate at (0.00, 1.00, 0.15): the nearest place with room to "
    "stand and turn is [0.00, 0.54]"
)


def test_a_walk_goes_round_a_crate_on_the_floor():
    """The walk went straight through the crate between the person and the place (24.9 cm,
    a shin); it now goes round it, within the audit's limits."""
    report = run(load_scenario(CRATE))
    walk = report.metrics["bt"]["human"]["ActorMovement::2"]
    assert walk["successes"] == 1, walk
    assert_within_the_audit_limits(report.metrics["realism"])


def test_validate_names_a_place_to_stand_with_no_room_beside_an_object(hrc_drake):
    """A place 0.2 m from the crate: validate said ok; it now says what a person there
    reaches into, and where the walk there ends instead."""
    status, _, err = hrc_drake("validate", CRATE)
    assert status == 2 and NO_ROOM in err, err
    assert err.count("locations.") == 1, err
