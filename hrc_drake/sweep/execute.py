"""Running sweep specs: on local worker processes, or on an existing Dask scheduler.

Each worker builds its own diagram from the scenario file (nothing of Drake is pickled) and
runs with one thread, so N workers use N cores. A run that raises becomes a failed row
inside the worker; a worker that dies (killed, out of memory, a crash in Drake) becomes a
failed row of the run it had, and a fresh worker takes its place: the sweep goes on. Each
worker is handed one run at a time, so the pool always knows which run a dead worker had,
and specs are drawn from the plan only as workers free up. Workers die with the sweep's
main process (Linux: the kernel kills them; elsewhere they notice within a second).
"""

import contextlib
import os
import re
import signal
import sys
import threading
import time
from collections.abc import Callable, Iterator
from functools import lru_cache
from multiprocessing import get_context
from multiprocessing.connection import wait

from hrc_drake.scenario.overrides import overridden
from hrc_drake.sweep.rows import RunSpec, make_row
from hrc_drake.yaml_check import InputError

THREAD_VARIABLES = (
    "OMP_NUM_THREADS",
    "OPENBLAS_NUM_THREADS",
    "MKL_NUM_THREADS",
    "DRAKE_NUM_THREADS",
)
DASK_CONNECT_TIMEOUT = 5.0
"""Seconds to wait for a Dask scheduler to answer before giving up with one line."""
DASK_IN_FLIGHT = 64
"""Runs handed to Dask at once; more are submitted as these finish."""
PR_SET_PDEATHSIG = 1


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
        scenario = overridden(_scenario(spec.scenario_path), spec.overrides)
        metrics = run(scenario, seed=spec.seed, out_dir=spec.out_dir or None).metrics
    except Exception as e:  # any failure of one run is that run's result, not the sweep's
        message = " ".join(f"{type(e).__name__}: {e}".split())
        return make_row(spec, None, error=message, wall_time=time.perf_counter() - start)
    return make_row(spec, metrics, wall_time=time.perf_counter() - start)


def run_in_pool(specs: Iterator[RunSpec], workers: int, on_row: Callable[[dict], None]) -> None:
    """Runs on up to `workers` local processes (spawned, so each starts clean)."""
    with LocalPool(workers) as pool:
        pool.run(specs, on_row)


class LocalPool:
    """Up to `workers` local worker processes, kept between `run` calls (a search runs
    round after round on the same workers); closing it stops them."""

    def __init__(self, workers: int):
        self.workers = workers
        self._context = get_context("spawn")
        self._idle: list[_Worker] = []

    def run(self, specs: Iterator[RunSpec], on_row: Callable[[dict], None]) -> None:
        """Runs every spec, reporting each row as its run ends; returns when all ended."""
        busy: list[_Worker] = []
        try:
            for spec in specs:
                if not self._idle and len(busy) < self.workers:
                    self._idle.append(_Worker(self._context))
                while not self._idle:
                    self._idle += _finished(busy, on_row, self._context)
                worker = self._idle.pop()
                worker.start(spec)
                busy.append(worker)
            while busy:
                self._idle += _finished(busy, on_row, self._context)
        finally:
            for worker in busy:  # interrupted: their runs are lost with them
                worker.stop()

    def close(self) -> None:
        for worker in self._idle:
            worker.stop()
        self._idle = []

    def __enter__(self) -> "LocalPool":
        return self

    def __exit__(self, *exc) -> None:
        self.close()


def _finished(busy: list["_Worker"], on_row, context) -> list["_Worker"]:
    """Waits for runs to end; reports their rows and returns the workers free again."""
    ready = set(wait([w.connection for w in busy] + [w.process.sentinel for w in busy]))
    free = []
    for worker in [w for w in busy if {w.connection, w.process.sentinel} & ready]:
        busy.remove(worker)
        row = worker.result()
        if row is None:  # the worker died with the run
            row = make_row(worker.spec, None, error=worker.death())
            worker.stop()
            worker = _Worker(context)
        on_row(row)
        free.append(worker)
    return free


class _Worker:
    """One worker process and the pipe that hands it one run at a time."""

    def __init__(self, context):
        self.connection, theirs = context.Pipe()
        self.process = context.Process(target=_serve, args=(theirs, os.getpid()), daemon=True)
        self.process.start()
        theirs.close()
        self.spec: RunSpec | None = None

    def start(self, spec: RunSpec) -> None:
        """Hands the worker its run; one that died before taking it (killed between runs:
        the send broke the sweep with BrokenPipeError) is reported by `_finished` as it is
        when it dies during the run."""
        self.spec = spec
        with contextlib.suppress(OSError):
            self.connection.send(spec)

    def result(self) -> dict | None:
        try:
            return self.connection.recv()
        except (EOFError, OSError):
            return None

    def death(self) -> str:
        self.process.join(timeout=5)
        code = self.process.exitcode
        if code is not None and code < 0:
            how = f"killed by {signal.Signals(-code).name}"
        else:
            how = f"exit status {code}"
        return f"WorkerDied: the worker process running this run died ({how})"

    def stop(self) -> None:
        with contextlib.suppress(OSError):  # a dead worker's pipe is closed
            self.connection.send(None)
        self.connection.close()
        self.process.join(timeout=5)
        if self.process.is_alive():
            self.process.kill()
            self.process.join()


def _serve(connection, parent: int) -> None:
    """A worker's life: runs until told to stop, its parent dies, or Ctrl-C."""
    _die_with(parent)
    prepare_worker()
    try:
        while (spec := connection.recv()) is not None:
            connection.send(run_spec(spec))
    except (EOFError, KeyboardInterrupt, BrokenPipeError):
        pass


def _die_with(parent: int) -> None:
    """No worker outlives the sweep's main process, however that process ends."""
    if sys.platform.startswith("linux"):
        import ctypes

        ctypes.CDLL(None, use_errno=True).prctl(PR_SET_PDEATHSIG, signal.SIGKILL)
    else:
        threading.Thread(target=_watch_parent, args=(parent,), daemon=True).start()
    if os.getppid() != parent:  # it died before we asked to follow it
        os._exit(1)


def _watch_parent(parent: int) -> None:
    while os.getppid() == parent:
        time.sleep(0.5)
    os._exit(1)


ADDRESS = re.compile(r"^(inproc://\S+|((tcp|tls|ws|wss|ucx)://)?(\[[0-9a-fA-F:.]+\]|[\w.-]+):\d+)$")


def connect_dask(address: str):
    """A client of the Dask scheduler at `address`; InputError (one line) when the address
    is malformed or nothing answers within DASK_CONNECT_TIMEOUT seconds."""
    from distributed import Client

    if not ADDRESS.match(address):
        raise InputError(f"--dask {address}: expected a scheduler address like tcp://HOST:PORT")
    try:
        client = Client(address, timeout=DASK_CONNECT_TIMEOUT)
    except (OSError, TimeoutError, ValueError) as e:
        reason = " ".join(str(e).split()) or type(e).__name__
        raise InputError(f"--dask {address}: no Dask scheduler answered ({reason})") from None
    client.run(prepare_worker)
    return client


def run_on_dask(specs: Iterator[RunSpec], client, on_row: Callable[[dict], None]) -> None:
    """Runs on the client's cluster (hrc_drake installed on its workers), a window of
    DASK_IN_FLIGHT runs at a time; a lost worker's run is a failed row (Dask retries a
    task whose worker died a few times first)."""
    from distributed import as_completed

    spec_of = {}

    def submit(spec):
        future = client.submit(run_spec, spec, pure=False)
        spec_of[future] = spec
        return future

    first = [submit(spec) for _, spec in zip(range(DASK_IN_FLIGHT), specs, strict=False)]
    running = as_completed(first)
    for future in running:
        on_row(_dask_row(future, spec_of.pop(future)))
        spec = next(specs, None)
        if spec is not None:
            running.add(submit(spec))


def _dask_row(future, spec: RunSpec) -> dict:
    """The run's row; a lost worker (the task never returned) makes a failed row too."""
    try:
        return future.result()
    except Exception as e:
        return make_row(spec, None, error=" ".join(f"{type(e).__name__}: {e}".split()))
