"""Fixtures shared by the tests: the CLI run in-process, free local ports, and Groot2
clients closed after each test; the longest test files are handed to the workers first."""

from pathlib import Path

import pytest

from hrc_drake.cli import main
from tests.groot_client import GrootClient, first_free_port

LONGEST_FIRST = (
    "test_notebooks.py",
    "falsify/test_falsify.py",
    "evaluation/test_replay_browser.py",
    "test_benchmarks.py",
    "evaluation/test_replay_browser_sensors.py",
    "station/test_trees_in_diagram.py",
    "station/test_groot_live.py",
    "scenarios/test_collaboration.py",
    "test_sweep.py",
    "scenarios/test_coexistence.py",
    "scenarios/test_cooperation.py",
    "ergonomics/test_body_sizes.py",
    "evaluation/test_audit_rate.py",
    "human/test_surfaces.py",
    "corpus/test_sweep_faults.py",
    "safety/test_walk_in_scanner.py",
    "ergonomics/test_closed_loop.py",
    "layout/test_layout.py",
    "evaluation/test_margin.py",
)
"""The test files that take longest (`--durations`, summed per file), longest first. The
workers take whole files in collection order (`--dist loadfile --no-loadscope-reorder`):
a long file left to the end keeps one worker busy while the other idles, and xdist's own
order (most tests first) puts exactly these few-test, long-run files last."""


def pytest_collection_modifyitems(config, items):
    """The files of LONGEST_FIRST before all others, in its order; the rest as collected."""
    tests = Path(__file__).parent
    rank = {tests / name: k for k, name in enumerate(LONGEST_FIRST)}
    missing = [str(path) for path in rank if not path.is_file()]
    if missing:
        raise pytest.UsageError(f"tests/conftest.py LONGEST_FIRST names no file: {missing}")
    items.sort(key=lambda item: rank.get(item.path, len(rank)))


@pytest.fixture
def free_ports():
    """``free_ports(count)``: the first of ``count`` consecutive free local ports."""
    return first_free_port


@pytest.fixture
def groot():
    """``groot(port)``: a connected GrootClient, closed after the test."""
    clients = []

    def connect(port: int, **kwargs) -> GrootClient:
        clients.append(GrootClient(port, **kwargs))
        return clients[-1]

    yield connect
    for client in clients:
        client.close()


@pytest.fixture
def hrc_drake(capsys):
    """``hrc_drake(*args)``: the CLI run in this process -> (exit status, stdout, stderr)."""

    def run(*args) -> tuple[int, str, str]:
        capsys.readouterr()
        status = main([str(arg) for arg in args])
        out, err = capsys.readouterr()
        return status, out, err

    return run
