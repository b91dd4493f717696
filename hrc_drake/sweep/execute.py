"""Running sweep specs: in a local process pool, or on an existing Dask scheduler.

Each worker builds its own diagram from the scenario file (nothing of Drake is pickled) and
runs with one thread, so N workers use N cores. A run that raises becomes a failed row
inside the worker, so the sweep goes on.
"""

import os
import time
from collections.abc import Callable, Iterable
from concurrent.futures import ProcessPoolExecutor, as_completed
from functools import lru_cache
from multiprocessing import get_context

from hrc_drake.sweep.overrides import apply
from hrc_drake.sweep.rows import RunSpec, make_row

THREAD_VARIABLES = (
    "OMP_NUM_THREADS",
    "OPENBLAS_NUM_THREADS",
    "MKL_NUM_THREADS",
    "DRAKE_NUM_THREADS",
)


def prepare_worker() -> None:
    """One compute thread per worker process (set before Drake and numpy start theirs), and
    Drake's logging as quiet as in the CLI."""
    for name in THREAD_VARIABLES:
        os.environ[name] = "1"
    from hrc_drake.drake_logging import quiet_drake_logging

    quiet_drake_logging()


@lru_cache(maxsize=4)
def _scenario(path: str):
    from hrc_drake.scenario import load_scenario

    return load_scenario(path)


def run_spec(spec: RunSpec) -> dict:
    """Simulate one run and return its row; an exception becomes a failed row."""
    from hrc_drake.runner import run

    start = time.perf_counter()
    try:
        scenario = apply(_scenario(spec.scenario_path), spec.overrides)
        metrics = run(scenario, seed=spec.seed).metrics
    except Exception as e:  # any failure of one run is that run's result, not the sweep's
        message = " ".join(f"{type(e).__name__}: {e}".split())
        return make_row(spec, None, error=message, wall_time=time.perf_counter() - start)
    return make_row(spec, metrics, wall_time=time.perf_counter() - start)


def run_in_pool(specs: Iterable[RunSpec], workers: int, on_row: Callable[[dict], None]) -> None:
    """Runs on `workers` local processes (spawned, so each starts clean)."""
    pool = ProcessPoolExecutor(workers, mp_context=get_context("spawn"), initializer=prepare_worker)
    try:
        futures = [pool.submit(run_spec, spec) for spec in specs]
        for future in as_completed(futures):
            on_row(future.result())
    finally:
        pool.shutdown(wait=True, cancel_futures=True)


def run_on_dask(specs: Iterable[RunSpec], address: str, on_row: Callable[[dict], None]) -> None:
    """Runs on the workers of the Dask scheduler at `address` (hrc_drake installed there)."""
    from distributed import Client
    from distributed import as_completed as dask_completed

    with Client(address) as client:
        client.run(prepare_worker)
        futures = {client.submit(run_spec, spec, pure=False): spec for spec in specs}
        for future in dask_completed(futures):
            on_row(_dask_row(future, futures[future]))


def _dask_row(future, spec: RunSpec) -> dict:
    """The run's row; a lost worker (the task never returned) makes a failed row too."""
    try:
        return future.result()
    except Exception as e:
        return make_row(spec, None, error=" ".join(f"{type(e).__name__}: {e}".split()))
