"""What the Workpieces system costs per update and per output evaluation, the code at a git
revision (`--base`) against the working tree, in one process.

Both versions of the `hrc_drake` package are imported side by side (the base one from
`git archive` of the revision, laid out as pyproject's package-dir; `sys.modules` is swapped
while a version runs). Each repetition runs the scenario once per version as a sweep runs
it (`hrc_drake.runner.run`, no run directory), each version first in every other
repetition, and times by this process's CPU time: Workpieces' update (what it evaluates
included: the hands and tool pose adapters), the updates that acted and those that did
nothing, its two outputs, and the whole run. Prints the best of the repetitions per figure
and new / base ratios.

    .venv/bin/python benchmarks/workpieces_update.py [--base HEAD] [--repeat 3]
        [--duration 20] [scenario ...]
"""

import argparse
import contextlib
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from system_updates import SCENARIOS, Timed

ROOT = Path(__file__).resolve().parent.parent
PACKAGE = "hrc_drake"
MAPPED = ("systems", "models", "trees", "scenarios")
"""Folders that pyproject's package-dir maps into the package (hrc_drake.systems, ...)."""
CALLBACKS = ("_update", "_calc_status", "_calc_poses")
FIGURES = ("update", "acting update", "idle update", "_calc_status", "_calc_poses", "run")


def _own_modules() -> list[str]:
    return [name for name in sys.modules if name == PACKAGE or name.startswith(f"{PACKAGE}.")]


class Version:
    """One version of the package, importable while it is `active`."""

    def __init__(self, name: str, path: Path | None = None):
        self.name, self.path, self.modules = name, path, {}
        with self.active():
            import hrc_drake.runner  # noqa: F401
            import hrc_drake.scenario  # noqa: F401
            import hrc_drake.systems.workpieces  # noqa: F401

    @contextlib.contextmanager
    def active(self):
        """The version's modules (and those it imports meanwhile) stand in `sys.modules`."""
        others = {name: sys.modules.pop(name) for name in _own_modules()}
        sys.modules.update(self.modules)
        if self.path is not None:
            sys.path.insert(0, str(self.path))
        try:
            yield self.modules
        finally:
            if self.path is not None:
                sys.path.remove(str(self.path))
            self.modules = {name: sys.modules.pop(name) for name in _own_modules()}
            sys.modules.update(others)

    def measure(self, scenario: str, duration: float) -> dict[str, float]:
        """µs per call of each figure, and the run's CPU seconds ("run")."""
        with self.active() as modules:
            workpieces = modules[f"{PACKAGE}.systems.workpieces"].Workpieces
            runner, loading = modules[f"{PACKAGE}.runner"], modules[f"{PACKAGE}.scenario"]
            with Timed([(workpieces, name) for name in CALLBACKS]) as timed:
                start = time.process_time()
                runner.run(loading.load_scenario(scenario), duration=duration)
                run = time.process_time() - start
        return _figures(timed, run)


def _figures(timed: Timed, run: float) -> dict[str, float]:
    key = "Workpieces._update"
    updates, idle = timed.calls[key], timed.idle[key]
    seconds, idle_seconds = timed.seconds[key], timed.idle_seconds[key]
    figures = {
        "update": 1e6 * seconds / updates,
        "acting update": 1e6 * (seconds - idle_seconds) / max(updates - idle, 1),
        "idle update": 1e6 * idle_seconds / max(idle, 1),
        "run": run,
    }
    for name in CALLBACKS[1:]:
        key = f"Workpieces.{name}"
        figures[name] = 1e6 * timed.seconds[key] / timed.calls[key]
    figures["calls"] = (updates, updates - idle, timed.calls["Workpieces._calc_status"])
    return figures


def version_at(revision: str, into: Path) -> Version:
    """The package as it was at `revision` of this repository."""
    archive = subprocess.run(
        ["git", "archive", revision], cwd=ROOT, check=True, capture_output=True
    ).stdout
    subprocess.run(["tar", "-x", "-C", str(into)], input=archive, check=True)
    for folder in MAPPED:
        (into / folder).rename(into / PACKAGE / folder)
    return Version(revision, into)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("scenarios", nargs="*", default=SCENARIOS)
    parser.add_argument("--base", default="HEAD", help="git revision to compare with")
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--duration", type=float, default=20.0)
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as folder:
        versions = (version_at(args.base, Path(folder)), Version("working tree"))
        for scenario in args.scenarios:
            best = [{}, {}]
            for repetition in range(args.repeat):
                for k in (0, 1) if repetition % 2 == 0 else (1, 0):
                    figures = versions[k].measure(scenario, args.duration)
                    calls = figures.pop("calls")
                    best[k] = {n: min(v, best[k].get(n, v)) for n, v in figures.items()}
                    best[k]["calls"] = calls
            _print(scenario, args, versions, best)


def _print(scenario, args, versions, best) -> None:
    print(f"\n{scenario} ({args.duration:g} s simulated, best of {args.repeat})")
    for version, figures in zip(versions, best, strict=True):
        updates, acting, statuses = figures["calls"]
        print(f"  {version.name}: {updates} updates, {acting} acting, {statuses} statuses")
    print(f"  {'figure':16s} {'base':>12s} {'new':>10s} {'new/base':>9s}")
    for name in FIGURES:
        unit = "s" if name == "run" else "us"
        old, new = best[0][name], best[1][name]
        print(f"  {name:16s} {old:10.2f}{unit} {new:8.2f}{unit} {new / old:9.2f}")


if __name__ == "__main__":
    main()
