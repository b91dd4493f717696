"""The search for the worst case: an Optuna study over the scenario's `falsify:` parameters
that minimises each run's safety margin (`hrc_drake.evaluation.margin`).

Trials are asked in rounds of `batch`, run on the sweep's workers (local processes or a
Dask cluster) and told in trial order, so one seed gives the same trials on any number of
workers. Every run is a sweep row (runs.jsonl: its `--set` values are the fixed ones and the
trial's), written as it finishes. A restarted search replays the study from the seed: the
sampler asks the same trials again, those already in runs.jsonl are told their stored
rows, and only the rest run, so an interrupted search ends as an uninterrupted one would.
"""

import contextlib
import math
import shutil
import warnings
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field
from pathlib import Path

from tqdm import tqdm

from hrc_drake.evaluation.rows import OK
from hrc_drake.scenario.falsify import FalsifyConfig, SearchParameter
from hrc_drake.scenario.overrides import Overrides, field_type, label
from hrc_drake.sweep import scenario_hash
from hrc_drake.sweep.execute import LocalPool, connect_dask, run_on_dask
from hrc_drake.sweep.rows import RowStore, RunSpec
from hrc_drake.yaml_check import InputError

NO_ENCOUNTER = 100.0
"""What the optimiser is told for a run without a margin (the robot never moved while the
person was there): far safer than any encounter."""
CASES = "cases"
"""The sub-directory of the worst cases' run directories."""
COMMAND = "command.txt"
"""The file in a worst case's run directory that holds the command reproducing it."""


@dataclass(frozen=True)
class Search:
    """One search: the scenario, the fixed `--set` values, the seed of the runs and of the
    sampler, and the search space."""

    scenario_path: Path
    scenario_arg: str
    """how the user named the scenario (the reproducing commands name it the same way)"""
    fixed: Overrides
    seed: int
    config: FalsifyConfig
    digest: str
    name: str
    """the scenario's `name`: what the search's directory, report and progress are called"""

    def spec(self, values: dict, out_dir: str = "") -> RunSpec:
        """The run of a trial that set the parameters to `values` (by name)."""
        chosen = tuple((p.bind, values[name]) for name, p in self.config.parameters.items())
        sets = self.fixed + chosen
        return RunSpec(str(self.scenario_path), self.seed, sets, self.digest, out_dir)

    def command(self, values: dict) -> str:
        """The `hrc-drake run` command that reproduces the trial with these values."""
        from hrc_drake.evaluation.sweep_report import replay_command

        row = {"seed": self.seed, "set": dict(self.spec(values).overrides)}
        return replay_command(self.scenario_arg, row)


@dataclass
class Trial:
    """One trial: its number, the parameter values it set and its run's row."""

    number: int
    values: dict
    row: dict

    @property
    def ok(self) -> bool:
        return self.row["status"] == OK

    @property
    def margin(self) -> dict:
        return self.row["metrics"].get("margin", {}) if self.ok else {}

    @property
    def score(self) -> float:
        """The margin as the optimiser sees it (NO_ENCOUNTER without one)."""
        value = self.margin.get("value")
        return NO_ENCOUNTER if value is None else value


@dataclass
class FalsifyResult:
    search: Search
    trials: list[Trial]
    worst: list[Trial]
    """the lowest-margin trials, lowest first"""
    cases: dict[int, Path] = field(default_factory=dict)
    """trial number -> its run directory"""
    files: dict[str, Path] = field(default_factory=dict)
    warnings: list[str] = field(default_factory=list)

    @property
    def failed(self) -> list[Trial]:
        return [trial for trial in self.trials if not trial.ok]

    @property
    def violations(self) -> list[Trial]:
        return [trial for trial in self.trials if trial.margin.get("violation")]


def prepare(
    scenario_arg: str, seed: int | None = None, fixed: Overrides = (), options=None
) -> Search:
    """The search as the user asked for it, checked before any run: the scenario (with
    the fixed `--set` values) must load and have a `falsify:` section."""
    from hrc_drake.scenario import load_scenario, resolve_scenario_path

    path = resolve_scenario_path(scenario_arg).resolve()
    scenario = load_scenario(path, fixed, options)
    if scenario.falsify is None:
        raise InputError(
            f"{path}: no 'falsify:' section (name the parameters to search; see the "
            "README, 'What is the worst thing a person could do here?')"
        )
    runs = tuple((name, value) for name, value in fixed if not name.startswith("falsify."))
    chosen = scenario.seed if seed is None else seed
    digest = scenario_hash(path)
    return Search(path, scenario_arg, runs, chosen, scenario.falsify, digest, scenario.name)


def falsify(
    search: Search,
    budget: int,
    out_dir: Path,
    workers: int = 1,
    dask_address: str | None = None,
    progress: bool = False,
    retry_failed: bool = False,
) -> FalsifyResult:
    """Runs the search's first `budget` trials (those not already in `out_dir`), then the
    worst cases' run directories, and writes the trials and the report."""
    from hrc_drake.evaluation.falsify_report import write_falsify_report

    with _executor(workers, dask_address) as execute:  # a bad address writes nothing
        store = RowStore(Path(out_dir))
        trials = run_trials(search, budget, store, execute, progress, retry_failed)
        worst = ranked(trials)[: search.config.worst]
        result = FalsifyResult(search, trials, worst, warnings=list(store.warnings))
        result.cases = _cases(search, worst, store.out_dir / CASES, execute, result.warnings)
    result.files = {"rows": store.jsonl, "csv": store.csv}
    setups = _case_setups(search, result)
    result.files.update(write_falsify_report(store.out_dir, search, result, setups))
    return result


Execute = Callable[[Iterator[RunSpec], Callable[[dict], None]], None]


@contextlib.contextmanager
def _executor(workers: int, dask_address: str | None) -> Iterator[Execute]:
    """Runs specs on the sweep's local workers (kept for the whole search) or on Dask."""
    if dask_address:
        client = connect_dask(dask_address)
        try:
            yield lambda specs, on_row: run_on_dask(iter(specs), client, on_row)
        finally:
            client.close()
    else:
        with LocalPool(workers) as pool:
            yield pool.run


def run_trials(
    search: Search,
    budget: int,
    store: RowStore,
    execute: Execute,
    progress: bool = False,
    retry_failed: bool = False,
) -> list[Trial]:
    """The search's first `budget` trials, told to the study round by round: rows already
    in `store` are reused (failed ones run again with `retry_failed`), the rest run."""
    import optuna
    from optuna.trial import TrialState

    config = search.config
    space = search_space(config)
    kinds = {name: field_type_of(p) for name, p in config.parameters.items()}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", optuna.exceptions.ExperimentalWarning)
        optuna.logging.set_verbosity(optuna.logging.WARNING)
        study = optuna.create_study(direction="minimize", sampler=sampler(config, search.seed))
        trials: list[Trial] = []
        with tqdm(
            total=budget, unit="trial", desc=search.name, disable=None if progress else True
        ) as bar:
            for start in range(0, budget, config.batch):
                asked = [study.ask(space) for _ in range(min(config.batch, budget - start))]
                values = [_values(config, kinds, trial.params) for trial in asked]
                specs = [search.spec(v) for v in values]
                rows = _rows(specs, store, execute, retry_failed)
                for trial, value, spec in zip(asked, values, specs, strict=True):
                    done = Trial(trial.number, value, rows[spec.identity])
                    trials.append(done)
                    if done.ok:
                        study.tell(trial, done.score)
                    else:
                        study.tell(trial, state=TrialState.FAIL)
                    bar.update()
    return trials


def _rows(specs: list[RunSpec], store: RowStore, execute: Execute, retry_failed: bool) -> dict:
    """The rows of `specs`: stored ones (failed ones again with `retry_failed`) and the
    rest run now, each stored as it finishes."""
    latest = store.latest()
    pending = {}
    for spec in specs:
        row = latest.get(spec.identity)
        if row is None or (retry_failed and row["status"] != OK):
            pending.setdefault(spec.identity, spec)
    execute(iter(pending.values()), store.add)
    return store.latest()


def search_space(config: FalsifyConfig) -> dict:
    """Optuna distributions of the parameters, by name."""
    from optuna.distributions import (
        CategoricalDistribution,
        FloatDistribution,
        IntDistribution,
    )

    space = {}
    for name, p in config.parameters.items():
        if p.choices:
            space[name] = CategoricalDistribution(p.choices)
        elif p.integral:
            space[name] = IntDistribution(int(p.low), int(p.top), step=int(p.step))
        else:
            space[name] = FloatDistribution(p.low, p.top, step=p.step)
    return space


def sampler(config: FalsifyConfig, seed: int):
    """The configured Optuna sampler, seeded."""
    import optuna

    if config.sampler == "random":
        return optuna.samplers.RandomSampler(seed=seed)
    if config.sampler == "cmaes":
        return optuna.samplers.CmaEsSampler(
            seed=seed,
            n_startup_trials=config.startup_trials,
            independent_sampler=optuna.samplers.RandomSampler(seed=seed),
            warn_independent_sampling=False,
        )
    return optuna.samplers.TPESampler(
        seed=seed,
        n_startup_trials=config.startup_trials,
        multivariate=True,
        constant_liar=True,
    )


def field_type_of(parameter: SearchParameter):
    from hrc_drake.scenario import Scenario

    return field_type(Scenario, parameter.bind)


def _values(config: FalsifyConfig, kinds: dict, params: dict) -> dict:
    """What each parameter sets its field to for these sampled params."""
    return {
        name: parameter.value(params[name], kinds[name])
        for name, parameter in config.parameters.items()
    }


def ranked(trials: list[Trial]) -> list[Trial]:
    """Successful trials, lowest margin first (ties: the earlier trial)."""
    return sorted((t for t in trials if t.ok), key=lambda t: (t.score, t.number))


def _cases(search: Search, worst: list[Trial], cases_dir: Path, execute, notes) -> dict:
    """A run directory for each worst trial (cases/trial-N), made once: run again with
    replay and report, and the command that reproduces it (command.txt). A run that does not
    reproduce its trial's margin is noted."""
    directories = {trial.number: cases_dir / f"trial-{trial.number:04d}" for trial in worst}
    missing = [t for t in worst if not (directories[t.number] / "report.json").is_file()]
    partial = {
        t.number: directories[t.number].with_name(f".{directories[t.number].name}") for t in missing
    }
    for path in partial.values():
        shutil.rmtree(path, ignore_errors=True)  # left by an interrupted search
    specs = {t.number: search.spec(t.values, str(partial[t.number])) for t in missing}
    rows = {}
    execute(
        iter(specs.values()), lambda row: rows.setdefault(label(tuple(row["set"].items())), row)
    )
    for trial in missing:
        row = rows.get(label(specs[trial.number].overrides))
        if row is None or row["status"] != OK:
            notes.append(f"trial {trial.number}: its run directory failed: {row and row['error']}")
            continue
        again = row["metrics"].get("margin", {}).get("value")
        if not _same(again, trial.margin.get("value")):
            notes.append(
                f"trial {trial.number}: run again, its margin is {again}, not "
                f"{trial.margin.get('value')} (the run is not deterministic)"
            )
        (partial[trial.number] / COMMAND).write_text(search.command(trial.values) + "\n")
        partial[trial.number].rename(directories[trial.number])
    return {n: d for n, d in directories.items() if (d / "report.json").is_file()}


def _case_setups(search: Search, result: FalsifyResult) -> dict:
    """Each worst case's RunSetup (its S_p model and moving speed, for the report), by
    trial number."""
    from hrc_drake.runner import run_setup
    from hrc_drake.scenario import load_scenario

    return {
        trial.number: run_setup(
            load_scenario(search.scenario_path, search.spec(trial.values).overrides)
        )
        for trial in result.worst
        if trial.number in result.cases
    }


def _same(a, b) -> bool:
    return a == b or (a is not None and b is not None and math.isclose(a, b, abs_tol=1e-9))
