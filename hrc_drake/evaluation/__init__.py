"""Evaluation of runs and sweeps: metrics for report.json, timeline and heat-map figures,
report.html of a run, and the aggregate report of a sweep."""
