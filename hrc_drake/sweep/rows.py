"""Sweep results on disk: one row per run in `runs.jsonl` (the record) and `runs.csv`.

A row is written as soon as its run finishes, so an interrupted sweep keeps what it did;
restarted with the same arguments it reads the rows back and skips those runs. A line cut
short by the interruption is dropped on reading.
"""

import csv
import json
from dataclasses import dataclass
from pathlib import Path

from hrc_drake.sweep.overrides import Overrides, label

OK = "ok"
FAILED = "failed"
FIXED_COLUMNS = ("key", "seed", "status", "error", "wall_time")


@dataclass(frozen=True)
class RunSpec:
    """One run of a sweep: which scenario file, which seed, which grid point."""

    scenario_path: str
    seed: int
    overrides: Overrides = ()

    @property
    def key(self) -> str:
        point = label(self.overrides)
        return f"seed={self.seed}" + (f" {point}" if point else "")


def make_row(spec: RunSpec, metrics: dict | None, error: str = "", wall_time: float = 0.0):
    return {
        "key": spec.key,
        "seed": spec.seed,
        "set": dict(spec.overrides),
        "status": FAILED if error else OK,
        "error": error,
        "wall_time": round(wall_time, 3),
        "metrics": metrics or {},
    }


def flatten(metrics: dict, prefix: str = "") -> dict:
    """Nested metrics → `{"a.b.c": value}`; lists stay whole."""
    flat = {}
    for name, value in metrics.items():
        path = f"{prefix}{name}"
        if isinstance(value, dict):
            flat.update(flatten(value, f"{path}."))
        else:
            flat[path] = value
    return flat


class RowStore:
    """Appends rows to runs.jsonl and keeps runs.csv in step with it."""

    def __init__(self, out_dir: Path):
        self.out_dir = out_dir
        self.jsonl = out_dir / "runs.jsonl"
        self.csv = out_dir / "runs.csv"
        self.rows = self._read()
        self._columns: list[str] = []
        out_dir.mkdir(parents=True, exist_ok=True)
        self._rewrite_jsonl()
        self._write_csv()

    def done(self) -> set[str]:
        return {row["key"] for row in self.rows}

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
        rows = []
        for line in self.jsonl.read_text().splitlines():
            try:
                rows.append(json.loads(line))
            except json.JSONDecodeError:
                continue
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


def _csv_record(row: dict) -> dict:
    record = {name: row[name] for name in FIXED_COLUMNS}
    record.update({f"set.{path}": value for path, value in row["set"].items()})
    for path, value in flatten(row["metrics"]).items():
        record[f"metrics.{path}"] = json.dumps(value) if isinstance(value, list) else value
    return record
