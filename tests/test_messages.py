"""Command ports carry windows of recent commands; actors take the new ones, cancels first."""

from dataclasses import dataclass

from hrc_drake.messages import newer_commands


@dataclass(frozen=True)
class Go:
    seq: int


@dataclass(frozen=True)
class Cancel:
    seq: int


def test_none_one_or_a_window_of_commands():
    assert newer_commands(None, 0) == []
    assert newer_commands(Go(3), 2) == [Go(3)]
    assert newer_commands(Go(3), 3) == []
    assert newer_commands((Go(1), Go(3), Go(5)), 2) == [Go(3), Go(5)]


def test_cancels_come_first_and_the_rest_keep_their_order():
    window = (Go(1), Go(3), Cancel(5), Go(7))
    assert newer_commands(window, 2, cancels=(Cancel,)) == [Cancel(5), Go(3), Go(7)]
