"""hrc_drake: simulate and evaluate human-robot collaboration with Drake.

The Python API is `load_scenario(path)`, `build_diagram(scenario, meshcat=None)` and
`run(scenario, seed=...) -> Report`; `run` is `simulate(scenario) -> RunRecord` (what the
run recorded) followed by `evaluate(record)` (report.json's metrics). They are imported
lazily so that `hrc_drake.bt` (the behavior tree engine) stays free of Drake.
"""

__version__ = "0.1.0"

_API = {
    "load_scenario": "hrc_drake.scenario",
    "build_diagram": "hrc_drake.builder",
    "run": "hrc_drake.runner",
    "simulate": "hrc_drake.runner",
    "evaluate": "hrc_drake.evaluation.report",
    "Report": "hrc_drake.evaluation.report",
}


def __getattr__(name):
    if name in _API:
        import importlib

        return getattr(importlib.import_module(_API[name]), name)
    raise AttributeError(f"module 'hrc_drake' has no attribute '{name}'")
