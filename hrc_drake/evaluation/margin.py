"""The safety margin of a run: how close it came to breaking ISO/TS 15066, as one number
in metres, lower is worse and below zero a violation (docs/falsify.md).

    SSM margin      least (separation - S_p) over the monitor's updates while the robot
                    moves, with S_p as the standard has it (below)
    contact ratio   largest force or pressure ratio (to the permitted limit of the contact's
                    kind) of any contact; a contact the body region must never have
                    (transient contact with the head) counts as 1 + its ratio
    margin          min(SSM margin, CONTACT_SCALE * (1 - contact ratio))

A contact at its limit thus scores like a moving robot right at S_p, and every 10 % over
the limit like 5 cm closer than S_p. Without contacts the margin is the SSM margin; a run in
which the robot never moved while the person was there has none (null).

S_p is recomputed from the safety log with ISO 13855's approach speeds, whatever the
monitor's `safety` section assumes (`hrc_drake.safety.reference`), so a monitor that
assumes a slower person shows its violations here even where its own verdict sees none.
"""

import math

import numpy as np

from hrc_drake.evaluation.metrics import rounded
from hrc_drake.evaluation.record import RunSetup
from hrc_drake.human.skeleton import REGIONS
from hrc_drake.safety.messages import ContactRecord
from hrc_drake.safety.pfl import REGION_LIMITS
from hrc_drake.safety.reference import reference_model, reference_protective
from hrc_drake.safety.ssm import SsmModel
from hrc_drake.safety.stopping import StopModel

CONTACT_SCALE = 0.5
"""Metres of margin per unit of contact ratio below its limit."""


def margin_model(setup: RunSetup) -> SsmModel:
    """The S_p model a run's margin is judged by: the run's reaction time, its robot's stop
    and command latency, ISO 13855's approach speeds."""
    return reference_model(
        setup.safety, StopModel.of_variant(setup.robot_variant), setup.command_latency
    )


def ssm_margins(log: dict[str, np.ndarray], model: SsmModel, moving_speed: float) -> np.ndarray:
    """separation - S_p at every logged update while the robot moves, NaN elsewhere."""
    moving = (log["robot_speed"] > moving_speed) & np.isfinite(log["separation"])
    margins = np.full(moving.shape, np.nan)
    if moving.any():
        moving_log = {n: v[moving] for n, v in log.items() if v.shape == moving.shape}
        margins[moving] = moving_log["separation"] - reference_protective(moving_log, model)
    return margins


def contact_ratio(records: tuple[ContactRecord, ...]) -> float:
    """The largest limit ratio of any contact (0 without contacts)."""
    return max((_ratio(record) for record in records), default=0.0)


def _ratio(record: ContactRecord) -> float:
    worst = record.worst
    ratio = max(worst.force_ratio, worst.pressure_ratio)
    return ratio if REGION_LIMITS[worst.region].permitted(worst.kind) else 1.0 + ratio


def margin_metrics(
    log: dict[str, np.ndarray],
    model: SsmModel,
    moving_speed: float,
    records: tuple[ContactRecord, ...],
    parts: tuple[str, ...],
) -> dict:
    """The run's margin (m), its parts and where the SSM margin was least."""
    margins = ssm_margins(log, model, moving_speed)
    ratio = contact_ratio(records)
    ssm = float(np.nanmin(margins)) if np.isfinite(margins).any() else math.inf
    contact = CONTACT_SCALE * (1.0 - ratio) if records else math.inf
    value = min(ssm, contact)
    found = {
        "value": rounded(value),
        "ssm": rounded(ssm),
        "contact_ratio": rounded(ratio),
        "violation": value < 0.0,
    }
    if math.isfinite(ssm):
        k = int(np.nanargmin(margins))
        found["at"] = {
            "time": rounded(log["time"][k]),
            "separation": rounded(log["separation"][k]),
            "protective": rounded(log["separation"][k] - margins[k]),
            "region": _name(REGIONS, log["region"][k]),
            "part": _name(parts, log["part"][k]),
            "robot_speed": rounded(log["robot_speed"][k]),
        }
    return found


def _name(names, index: float) -> str:
    return names[int(index)] if 0 <= index < len(names) else ""
