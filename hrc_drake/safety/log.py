"""The run's safety log, safety.npz: the monitor's `safety_signals` at every update, so that
anyone can check the verdict (numpy: `np.load("safety.npz")`).

Arrays: one per entry of SIGNALS (see `hrc_drake.safety.messages`; `time` is when each
update measured), plus the names the numbered entries refer to: `regions` (for `region`),
`parts` (for `part`), `zones` (for `zone`) and `fields` (for `field`).
"""

from pathlib import Path

import numpy as np

from hrc_drake.human.skeleton import REGIONS
from hrc_drake.safety.messages import SIGNALS
from hrc_drake.safety.sensors_reading import FIELD_STATES
from hrc_drake.safety.ssm import ZONES


def signal(signals: np.ndarray, name: str) -> np.ndarray:
    """One signal of the logged `safety_signals` (SIGNALS x samples), over the samples."""
    return signals[SIGNALS.index(name)]


def log_of(signals: np.ndarray) -> dict[str, np.ndarray]:
    """The logged `safety_signals` by name, as safety.npz holds them."""
    return {name: signals[k] for k, name in enumerate(SIGNALS)}


def write_safety_log(path: Path, signals: np.ndarray, parts) -> Path:
    """`signals`: the logged `safety_signals` (SIGNALS × samples). Samples of the same time
    are written once, the last: a logger faster than the monitor repeats updates, and the
    first sample (the initial values, time 0) is followed by the update at 0."""
    times = signal(signals, "time")
    updates = np.flatnonzero(np.diff(times, append=np.inf) != 0.0)
    np.savez_compressed(
        path,
        **{name: signals[k, updates] for k, name in enumerate(SIGNALS)},
        regions=np.array(REGIONS),
        parts=np.array(parts),
        zones=np.array(ZONES),
        fields=np.array(FIELD_STATES),
    )
    return path


def read_safety_log(path: Path) -> dict[str, np.ndarray]:
    with np.load(path) as log:
        return {name: log[name] for name in log.files}
