"""What the hands work on and must keep out of: the cell's fixed geometry as the person's
arms see it.

Every piece of the cell's static collision geometry within the body's height is a prism (its
floor outline between its lowest and highest point; hrc_drake.human.navigation.Obstacle):
exact for the boxes our cells are made of, a little larger than a cylinder. A hand put on a
surface or on what stands on it comes from above it and from outside its outline; these are
the questions that takes: what a point rests on (`support`), and where a hand coming from the
body is still outside the surface's edge (`behind_edge`).
"""

from dataclasses import dataclass

import numpy as np
from shapely.geometry import LineString, Point

from hrc_drake.human.navigation import Obstacle

RESTING = 0.02
"""m: a point this far above a surface, or less, rests on it."""
FAR = 5.0
"""m: further than any piece of furniture is across."""


@dataclass(frozen=True)
class Furniture:
    """The cell's fixed geometry in the body's height (none: an empty hall)."""

    pieces: tuple[Obstacle, ...] = ()

    def support(self, point) -> Obstacle | None:
        """The piece a point (x, y, z) is over, with the highest top at or below it (a hand
        or an object on a table: the table's top); None when only the floor is below."""
        x, y, z = point
        below = [
            piece
            for piece in self.pieces
            if piece.high <= z + RESTING and piece.outline.covers(Point(x, y))
        ]
        return max(below, key=lambda piece: piece.high, default=None)

    def behind_edge(self, piece: Obstacle, point, back, margin: float):
        """`point` (x, y) moved along the floor direction `back` until it is `margin` outside
        the piece's outline (None: it is outside already)."""
        start = Point(point[0], point[1])
        grown = piece.outline.buffer(margin, join_style="mitre")
        if not grown.covers(start):
            return None
        far = np.asarray(point[:2], dtype=float) + FAR * np.asarray(back[:2], dtype=float)
        crossing = LineString([tuple(point[:2]), tuple(far)]).intersection(grown.exterior)
        nearest = min(getattr(crossing, "geoms", [crossing]), key=start.distance)
        return np.array([nearest.x, nearest.y])
