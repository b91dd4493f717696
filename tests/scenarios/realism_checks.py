"""What every scenario's short run must show of the person (the realism audit's limits,
hrc_drake.evaluation.realism.LIMITS; docs/realism.md)."""

from hrc_drake.evaluation.realism import LIMITS, PELVIS_SPEED_SWING


def assert_holds_what_it_carries(realism: dict) -> None:
    """Every held object stays at its holding hand(s) and level."""
    for measure in ("hand_object_gap", "carried_tilt_deg"):
        worst = realism[measure]
        assert worst["max"] <= LIMITS[measure], f"{measure}: {worst}"


def assert_walks_like_a_person(realism: dict) -> None:
    """No sole point slides on the floor it stands on, and the pelvis speed of every steady
    stride swings no more than published gait data (docs/realism.md)."""
    assert realism["foot_slip"]["max"] <= LIMITS["foot_slip"], realism["foot_slip"]
    swing = realism["pelvis_speed"]["variation_max"]
    assert swing <= PELVIS_SPEED_SWING, realism["pelvis_speed"]
