"""Fixtures shared by the tests: the CLI run in-process, free local ports, and Groot2
clients closed after each test."""

import pytest

from hrc_drake.cli import main
from tests.groot_client import GrootClient, first_free_port


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
