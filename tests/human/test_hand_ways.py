"""The ways of the hands off a surface (hrc_drake.human.hand_ways), planned alone."""

import warnings

import numpy as np
import pytest
import shapely

from hrc_drake.human.body import human_body
from hrc_drake.human.furniture import Furniture
from hrc_drake.human.hand_ways import over_the_edge
from hrc_drake.human.navigation import Obstacle
from tests.human.cell_walks import Cell
from tests.human.cell_walks import Furniture as CellPiece

BENCH = Furniture((Obstacle("bench", shapely.box(-0.6, 0.35, 0.6, 1.15), 0.0, 0.9),))
"""Coexistence's bench as the person standing at (0, 0) facing +y sees it (top 0.9 m, its
front edge 0.35 m ahead, its right side at x = 0.6)."""
FACING = np.pi / 2


def test_hands_that_put_an_object_down_at_a_tables_side_leave_over_its_front_together():
    """Coexistence seed 2 at 104.75 s: a part (0.16 m across) put down with both hands at
    the bench's right end, the right palm on its face beyond the bench's side. Only the left
    hand went back over the front edge (0.29 m ahead); the right one was left beside the
    part (0.44 m ahead, 0.09 m in front of that edge), and from there its way back to the
    body's side went 1.3 cm into the part. Both go back over the front edge, the right one
    where it is across."""
    palms = {
        "left": (np.array([0.473, 0.439, 1.03]), None),
        "right": (np.array([0.649, 0.439, 1.03]), None),
    }
    opened = {
        side: (p + [0.06 * (1 if side == "right" else -1), 0.0, 0.06], None)
        for side, (p, _) in palms.items()
    }
    edge = over_the_edge(human_body(), BENCH, palms, opened, np.zeros(2), FACING, held=True)
    left, right = edge["left"][0], edge["right"][0]
    assert left[1] < 0.35
    assert right[1] == pytest.approx(left[1]), (left, right)
    assert right[0] == opened["right"][0][0]


def test_hands_leaving_a_pallets_top_are_worked_out_without_a_warning():
    """A user's tray stack on a euro pallet at (-1.9, 1.0): its slats joined into one outline
    left steps of 1e-16 m, and the mitred buffer of the hands' way off its edge printed
    numpy's "divide by zero encountered in buffer" at every validate of a small woman (for
    this margin, the hand's extent there, and not for a rounder one)."""
    margin = 0.05190356410638735
    cell = Cell([CellPiece("tray_pallet", "euro_pallet", -1.9, 1.0)])
    furniture = Furniture(tuple(cell.navigation.obstacles))
    deck = max(furniture.pieces, key=lambda piece: piece.high)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        edge = furniture.behind_edge(furniture.pile(deck), (-1.282, 1.295), (0, 1), margin)
    assert edge[1] == pytest.approx(deck.outline.bounds[3] + margin, abs=1e-6)
