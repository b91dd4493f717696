"""Sweep results on disk: one row per run in `runs.jsonl` (the record) and `runs.csv`.

A row is written as soon as its run finishes, so an interrupted sweep keeps what it did;
restarted, it reads the rows back and skips those runs. A line that is not a row (cut
short by a kill, or edited by hand) is never dropped silently: it is moved, as it was, to
`runs.damaged.jsonl` and named with its file and line in the sweep's warnings.
"""

import csv
import json
from dataclasses import dataclass
from pathlib import Path

import hrc_drake
from hrc_drake.evaluation.metrics import flatten
from hrc_drake.evaluation.rows import FAILED, OK
from hrc_drake.scenario.overrides import Overrides, label
from hrc_drake.yaml_check import InputError

FIXED_COLUMNS = ("key", "seed", "status", "error", "wall_time", "scenario_hash", "version")
ROW_FIELDS = {"key": str, "seed": int, "set": dict, "status": str, "error": str, "metrics": dict}


@dataclass(frozen=True)
class RunSpec:
    """One run of a sweep: which scenario file (and its content hash), which seed, which
    grid point (the `--set` values)."""

    scenario_path: str
    seed: int
    overrides: Overrides = ()
    scenario_hash: str = ""
    out_dir: str = ""
    """where to write the run directory ("": none); not part of what decides the row"""

    @property
    def key(self) -> str:
        """How people name the run: its seed and grid point."""
        point = label(self.overrides)
        return f"seed={self.seed}" + (f" {point}" if point else "")

    @property
    def identity(self) -> tuple:
        """Everything that decides the run's row (see `row_identity`)."""
        return (self.scenario_hash, hrc_drake.__version__, self.seed, _fields(self.overrides))


def row_identity(row: dict) -> tuple:
    return (
        row.get("scenario_hash"),
        row.get("version"),
        row["seed"],
        _fields(tuple(row["set"].items())),
    )


def _fields(overrides: Overrides) -> str:
    """The `--set` values in field order: runs.jsonl stores them sorted, and the order
    they were given in changes nothing."""
    return label(tuple(sorted(overrides)))


def make_row(spec: RunSpec, metrics: dict | None, error: str = "", wall_time: float = 0.0):
    return {
        "key": spec.key,
        "seed": spec.seed,
        "set": dict(spec.overrides),
        "scenario_hash": spec.scenario_hash,
        "version": hrc_drake.__version__,
        "status": FAILED if error else OK,
        "error": error,
        "wall_time": round(wall_time, 3),
        "metrics": metrics or {},
    }


class RowStore:
    """Appends rows to runs.jsonl and keeps runs.csv in step with it."""

    def __init__(self, out_dir: Path):
        self.out_dir = out_dir
        self.jsonl = out_dir / "runs.jsonl"
        self.csv = out_dir / "runs.csv"
        self.set_aside = out_dir / "runs.damaged.jsonl"
        self.warnings: list[str] = []
        _prepare_sweep_directory(out_dir, self.jsonl)
        self.rows = self._read()
        self._columns: list[str] = []
        try:
            self._rewrite_jsonl()
            self._write_csv()
        except OSError as e:
            raise InputError(f"{out_dir}: cannot write the sweep's rows: {e.strerror}") from None

    def latest(self) -> dict[tuple, dict]:
        """The newest row of every run (a retried run's new row replaces its failed one)."""
        return {row_identity(row): row for row in self.rows}

    def add(self, row: dict) -> None:
        self.rows.append(row)
        with self.jsonl.open("a") as f:
            f.write(json.dumps(row, sort_keys=True) + "\n")
        record = _csv_record(row)
        if set(record) <= set(self._columns):
            with self.csv.open("a", newline="") as f:
                csv.DictWriter(f, self._columns).writerow(record)
        else:
            self._write_csv()

    def _read(self) -> list[dict]:
        if not self.jsonl.is_file():
            return []
        rows, damaged = [], []
        for number, line in enumerate(self.jsonl.read_text(errors="replace").splitlines(), 1):
            if not line.strip():
                continue
            problem = _row_problem(line)
            if problem:
                damaged.append(line)
                self.warnings.append(
                    f"{self.jsonl}:{number}: damaged row ({problem}), set aside in "
                    f"{self.set_aside.name}; the run will be done again"
                )
            else:
                rows.append(json.loads(line))
        if damaged:
            with self.set_aside.open("a") as f:
                f.write("".join(line + "\n" for line in damaged))
        return rows

    def _rewrite_jsonl(self) -> None:
        self.jsonl.write_text("".join(json.dumps(r, sort_keys=True) + "\n" for r in self.rows))

    def _write_csv(self) -> None:
        records = [_csv_record(row) for row in self.rows]
        extra = sorted({name for r in records for name in r} - set(FIXED_COLUMNS))
        self._columns = [*FIXED_COLUMNS, *extra]
        with self.csv.open("w", newline="") as f:
            writer = csv.DictWriter(f, self._columns)
            writer.writeheader()
            writer.writerows(records)


def _prepare_sweep_directory(out_dir: Path, jsonl: Path) -> None:
    """A sweep directory is new, empty, or an earlier sweep's (it has runs.jsonl)."""
    if out_dir.is_dir() and not jsonl.is_file() and any(out_dir.iterdir()):
        raise InputError(
            f"{out_dir}: holds other files but no runs.jsonl (not a sweep directory); "
            "give a new, empty or earlier sweep directory"
        )
    try:
        out_dir.mkdir(parents=True, exist_ok=True)
    except FileExistsError:
        raise InputError(f"{out_dir}: is a file, not a directory") from None
    except OSError as e:
        raise InputError(f"{out_dir}: cannot create the sweep directory: {e.strerror}") from None


def _row_problem(line: str) -> str:
    try:
        row = json.loads(line)
    except json.JSONDecodeError as e:
        return f"not JSON: {e.msg}"
    if not isinstance(row, dict):
        return "not a JSON object"
    for name, kind in ROW_FIELDS.items():
        if not isinstance(row.get(name), kind):
            return f"no {kind.__name__} '{name}'"
    return ""


def _csv_record(row: dict) -> dict:
    record = {name: row.get(name, "") for name in FIXED_COLUMNS}
    record.update({f"set.{path}": value for path, value in row["set"].items()})
    for path, value in flatten(row["metrics"]).items():
        record[f"metrics.{path}"] = json.dumps(value) if isinstance(value, list) else value
    return record
