"""What every scenario run must show of the person: the realism audit's limits
(hrc_drake.evaluation.realism.LIMITS and PELVIS_SPEED_SWING; docs/realism.md). A failure
names every measure over its limit with what, where and when."""

from hrc_drake.evaluation.realism import LIMITS, PELVIS_SPEED_SWING

KEEPS_OUT = ("penetration_static", "penetration_objects", "penetration_carried")
HOLDS = ("hand_object_gap", "carried_tilt_deg")
WALKS = ("foot_slip",)


def _excesses(realism: dict, measures) -> list[str]:
    """'measure value > limit (what at time)' for each of `measures` over its limit."""
    found = []
    for measure in measures:
        worst = realism[measure]
        if worst["max"] > LIMITS[measure]:
            what = next(v for k, v in worst.items() if k not in ("max", "time"))
            found.append(
                f"{measure} {worst['max']} > {LIMITS[measure]} ({what} at {worst['time']} s)"
            )
    return found


def assert_keeps_out_of_things(realism: dict) -> None:
    """No body segment goes into the cell's geometry or into an object it does not hold
    deeper than the limit, nor does what the person holds."""
    excesses = _excesses(realism, KEEPS_OUT)
    assert not excesses, "; ".join(excesses)


def assert_holds_what_it_carries(realism: dict) -> None:
    """Every held object stays at its holding hand(s) and level."""
    excesses = _excesses(realism, HOLDS)
    assert not excesses, "; ".join(excesses)


def _walking_excesses(realism: dict) -> list[str]:
    swing = realism["pelvis_speed"]["variation_max"]
    too_much = [f"pelvis speed swing {swing} > {PELVIS_SPEED_SWING}"]
    return _excesses(realism, WALKS) + (too_much if swing > PELVIS_SPEED_SWING else [])


def assert_walks_like_a_person(realism: dict) -> None:
    """No sole point slides on the floor it stands on, and the pelvis speed of every steady
    stride swings no more than published gait data (docs/realism.md)."""
    excesses = _walking_excesses(realism)
    assert not excesses, "; ".join(excesses)


def assert_within_the_audit_limits(realism: dict) -> None:
    """Every measure of the audit within its limit (all excesses named at once)."""
    excesses = _excesses(realism, (*KEEPS_OUT, *HOLDS)) + _walking_excesses(realism)
    assert not excesses, "; ".join(excesses)
