"""Monte Carlo sweeps: many seeds (and `--set` parameter grids) of one scenario.

`sweep()` runs every (grid point, seed) of a plan not already in the output directory,
writes one row per run as it finishes (runs.jsonl, runs.csv) and then the aggregate report
(`hrc_drake.evaluation.sweep_report`). A row is known by everything that decides it: the
scenario's content (its file and tree files), the package version, the seed and the grid
point; rows of an edited scenario are never taken for the new one's. Rows of failed runs
(a run that raised, or a worker process that died) carry the error; `retry_failed` runs
them again. Seeds are streamed, never listed up front.
"""

import hashlib
from dataclasses import dataclass, field
from pathlib import Path

from tqdm import tqdm

import hrc_drake
from hrc_drake.evaluation.rows import OK
from hrc_drake.scenario.overrides import Overrides, grid, parse_sets
from hrc_drake.sweep.execute import connect_dask, run_in_pool, run_on_dask
from hrc_drake.sweep.rows import RowStore, RunSpec, row_identity
from hrc_drake.yaml_check import InputError

__all__ = ["RunSpec", "Seeds", "SweepPlan", "SweepResult", "parse_seeds", "plan", "sweep"]


@dataclass
class SweepResult:
    """The rows of this sweep's runs (in seed order per grid point), the written files,
    and warnings about the directory (damaged rows set aside)."""

    rows: list[dict]
    skipped: int
    files: dict[str, Path] = field(default_factory=dict)
    warnings: list[str] = field(default_factory=list)

    @property
    def failed(self) -> list[dict]:
        return [row for row in self.rows if row["status"] != OK]


@dataclass(frozen=True)
class Seeds:
    """Seed ranges and single seeds in the order given, each seed once; never a list."""

    parts: tuple[range, ...]

    def __iter__(self):
        for i, part in enumerate(self.parts):
            for seed in part:
                if not any(seed in earlier for earlier in self.parts[:i]):
                    yield seed

    def __len__(self) -> int:
        count, reach = 0, None
        for part in sorted(self.parts, key=lambda r: r.start):
            start = part.start if reach is None else max(part.start, reach)
            count += max(0, part.stop - start)
            reach = part.stop if reach is None else max(reach, part.stop)
        return count

    def __contains__(self, seed: int) -> bool:
        return any(seed in part for part in self.parts)


def parse_seeds(text: str) -> Seeds:
    """`0:500` (half-open range), `7`, or a comma list of both: `0:4,10,12`."""
    from hrc_drake.scenario import MAX_SEED

    parts = []
    for part in text.split(","):
        start, sep, stop = part.partition(":")
        try:
            parts.append(range(int(start), int(stop)) if sep else range(int(start), int(start) + 1))
        except ValueError:
            raise InputError(f"--seeds {text}: expected START:STOP, N or a comma list") from None
        if parts[-1].start < 0 or parts[-1].stop - 1 > MAX_SEED:
            raise InputError(f"--seeds {text}: seeds lie within 0..{MAX_SEED}")
    seeds = Seeds(tuple(parts))
    if not len(seeds):
        raise InputError(f"--seeds {text}: no seeds in that range")
    return seeds


@dataclass(frozen=True)
class SweepPlan:
    """Every grid point × seed of one scenario, grid point outermost; iterated lazily."""

    scenario_path: str
    scenario_hash: str
    points: tuple[Overrides, ...]
    seeds: Seeds
    name: str = ""
    """the scenario's `name`: what the sweep's report and progress are called"""

    def __iter__(self):
        for point in self.points:
            for seed in self.seeds:
                yield RunSpec(self.scenario_path, seed, point, self.scenario_hash)

    def __len__(self) -> int:
        return len(self.points) * len(self.seeds)

    def holds(self, row: dict) -> bool:
        """Whether a stored row is one of this plan's runs (same scenario and version)."""
        return (
            row.get("scenario_hash") == self.scenario_hash
            and row.get("version") == hrc_drake.__version__
            and row["seed"] in self.seeds
            and row["set"] in [dict(point) for point in self.points]
        )


def plan(
    scenario_path: Path,
    seeds: Seeds,
    sets: list[str],
    fixed: Overrides = (),
    options: dict[str, str] | None = None,
) -> SweepPlan:
    """The sweep's runs; every grid point is checked like a scenario file before any run.
    `fixed` overrides hold for every run (`--duration`), `options` name the options that
    gave them (as for `load_scenario`)."""
    from hrc_drake.scenario import Scenario, load_scenario

    axes = parse_sets(sets, Scenario)
    for path, _ in axes:
        if path == "seed":
            raise InputError("--set seed: use --seeds to choose seeds")
        if path in dict(fixed):
            raise InputError(f"--set {path}: {(options or {}).get(path)} sets it already")
    points = tuple(tuple(fixed) + point for point in grid(axes))
    names = [load_scenario(scenario_path, point, options).name for point in points]
    path = Path(scenario_path).resolve()
    return SweepPlan(str(path), scenario_hash(path), points, seeds, names[0])


def scenario_hash(path: Path) -> str:
    """A digest of the scenario file and the tree files it names: what a row depends on
    besides the seed, the grid point and the package version."""
    from hrc_drake.scenario import load_scenario

    digest = hashlib.sha256(path.read_bytes())
    for tree in load_scenario(path).trees.values():
        digest.update(Path(tree.file).read_bytes())
    return digest.hexdigest()[:16]


def sweep(
    specs: SweepPlan,
    out_dir: Path,
    workers: int = 1,
    dask_address: str | None = None,
    progress: bool = False,
    retry_failed: bool = False,
) -> SweepResult:
    """Runs the plan's runs not yet in `out_dir` (and with `retry_failed` those that
    failed), then writes the aggregate report there."""
    from hrc_drake.evaluation.sweep_report import write_sweep_report

    out_dir = Path(out_dir)
    client = connect_dask(dask_address) if dask_address else None
    try:
        store = RowStore(out_dir)
        done = {
            row_identity(row)
            for row in store.latest().values()
            if specs.holds(row) and (row["status"] == OK or not retry_failed)
        }
        pending = (spec for spec in specs if spec.identity not in done)
        with tqdm(
            total=len(specs),
            initial=len(done),
            unit="run",
            desc=specs.name,
            disable=None if progress else True,
        ) as bar:

            def on_row(row: dict) -> None:
                store.add(row)
                bar.update()

            if client is not None:
                run_on_dask(pending, client, on_row)
            else:
                run_in_pool(pending, workers, on_row)
    finally:
        if client is not None:
            client.close()
    latest = store.latest()
    rows = [latest[spec.identity] for spec in specs]
    result = SweepResult(rows, skipped=len(done), warnings=store.warnings)
    result.files = {"rows": store.jsonl, "csv": store.csv}
    if store.set_aside.is_file():
        result.files["damaged_rows"] = store.set_aside
    result.files.update(write_sweep_report(out_dir, rows, specs.scenario_path, specs.name))
    return result
