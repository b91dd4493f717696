"""Monte Carlo sweeps: many seeds (and `--set` parameter grids) of one scenario.

`sweep()` runs every (grid point, seed) not already in the output directory, writes one row
per run as it finishes (runs.jsonl, runs.csv) and then the aggregate report
(`hrc_drake.evaluation.sweep_report`). Rows of failed runs carry the error.
"""

from dataclasses import dataclass, field
from pathlib import Path

from tqdm import tqdm

from hrc_drake.sweep.execute import run_in_pool, run_on_dask
from hrc_drake.sweep.overrides import Overrides, grid, parse_sets
from hrc_drake.sweep.rows import OK, RowStore, RunSpec
from hrc_drake.yaml_check import InputError

__all__ = ["RunSpec", "SweepResult", "parse_seeds", "plan", "sweep"]


@dataclass
class SweepResult:
    """The rows of this sweep's runs (in seed order per grid point) and the written files."""

    rows: list[dict]
    skipped: int
    files: dict[str, Path] = field(default_factory=dict)

    @property
    def failed(self) -> list[dict]:
        return [row for row in self.rows if row["status"] != OK]


def parse_seeds(text: str) -> list[int]:
    """`0:500` (half-open range), `7`, or a comma list of both: `0:4,10,12`."""
    seeds = []
    for part in text.split(","):
        start, sep, stop = part.partition(":")
        try:
            seeds += list(range(int(start), int(stop))) if sep else [int(start)]
        except ValueError:
            raise InputError(f"--seeds {text}: expected START:STOP, N or a comma list") from None
    if not seeds:
        raise InputError(f"--seeds {text}: no seeds in that range")
    return list(dict.fromkeys(seeds))


def plan(scenario_path: Path, seeds: list[int], sets: list[str]) -> list[RunSpec]:
    """Every grid point × seed, grid point outermost."""
    from hrc_drake.scenario import Scenario

    axes = parse_sets(sets, Scenario)
    if any(path == "seed" for path, _ in axes):
        raise InputError("--set seed: use --seeds to choose seeds")
    points: list[Overrides] = grid(axes)
    path = str(Path(scenario_path).resolve())
    return [RunSpec(path, seed, point) for point in points for seed in seeds]


def sweep(
    specs: list[RunSpec],
    out_dir: Path,
    workers: int = 1,
    dask_address: str | None = None,
    progress: bool = False,
    scenario_name: str = "",
) -> SweepResult:
    """Runs the specs not yet in `out_dir`, then writes the aggregate report there."""
    from hrc_drake.evaluation.sweep_report import write_sweep_report

    store = RowStore(Path(out_dir))
    done = store.done()
    pending = [spec for spec in specs if spec.key not in done]
    with tqdm(
        total=len(pending),
        unit="run",
        desc=scenario_name or "sweep",
        disable=None if progress else True,
    ) as bar:

        def on_row(row: dict) -> None:
            store.add(row)
            bar.update()

        if pending and dask_address:
            run_on_dask(pending, dask_address, on_row)
        elif pending:
            run_in_pool(pending, workers, on_row)
    by_key = {row["key"]: row for row in store.rows}
    rows = [by_key[spec.key] for spec in specs]
    result = SweepResult(rows, skipped=len(specs) - len(pending))
    result.files = {"rows": store.jsonl, "csv": store.csv}
    result.files.update(write_sweep_report(Path(out_dir), rows, specs, scenario_name))
    return result
