"""A row: one run of a sweep or a falsification search, as `hrc_drake.sweep` stores it
(runs.jsonl) and the reports read it: `key`, `seed`, `set`, `status`, `error`, `metrics`
(report.json's dict; empty for a failed run), ...

`status` says whether the run gave metrics."""

OK = "ok"
FAILED = "failed"
