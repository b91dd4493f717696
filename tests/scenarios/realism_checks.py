"""What every scenario's short run must show of the person (the realism audit's limits,
hrc_drake.evaluation.realism.LIMITS; docs/realism.md)."""

from hrc_drake.evaluation.realism import LIMITS


def assert_holds_what_it_carries(realism: dict) -> None:
    """Every held object stays at its holding hand(s) and level."""
    for measure in ("hand_object_gap", "carried_tilt_deg"):
        worst = realism[measure]
        assert worst["max"] <= LIMITS[measure], f"{measure}: {worst}"
