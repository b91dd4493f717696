"""Evaluation of runs and sweeps: a run's record (`record.RunRecord`, what the runner
recorded) turned into report.json's metrics and the run directory's files (`report`), the
timeline and heat-map figures, report.html of a run, the replay, and the aggregate reports
of a sweep and a falsification search."""
