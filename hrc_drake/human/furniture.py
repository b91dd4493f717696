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
import shapely
import shapely.ops
from shapely.geometry import LineString, Point, Polygon

from hrc_drake.human.navigation import Obstacle, box_obstacle

RESTING = 0.02
"""m: a point this far above a surface, or less, rests on it."""
FAR = 5.0
"""m: further than any piece of furniture is across."""
UNION_GRID = 1e-9
"""m: outlines joined into one are snapped to this grid: a pallet's slats joined without it
left steps of 1e-16 m in the outline, on which a mitred buffer divides by zero (a warning
printed to a user)."""


@dataclass(frozen=True)
class Furniture:
    """The cell's fixed geometry in the body's height (none: an empty hall)."""

    pieces: tuple[Obstacle, ...] = ()

    def with_boxes(self, boxes) -> "Furniture":
        """The furniture and, as pieces of it, boxes (hrc_drake.human.messages.Box): objects
        standing near what the hands work on."""
        if not boxes:
            return self
        return Furniture((*self.pieces, *(box_obstacle(box) for box in boxes)))

    def not_over(self, area: Polygon, height: float) -> "Furniture":
        """The furniture but the pieces that stand over the middle of a floor area wholly
        above `height` (the board above what lies there; not a column of cartons whose edge
        the area overlaps: a carton carried 0.55 m from one, its outline 2.5 cm into the
        column's, was carried onto its top through the column's top carton, 14 cm in)."""
        middle = area.centroid
        return Furniture(
            tuple(p for p in self.pieces if p.low < height or not p.outline.covers(middle))
        )

    def not_above(self, area: Polygon, height: float) -> "Furniture":
        """The furniture but the pieces over any part of a floor area with their undersides
        at or above `height` (a board over one end of a held object's way: the way cannot
        cross over it and come down to that end)."""
        return Furniture(
            tuple(p for p in self.pieces if p.low < height or not p.outline.intersects(area))
        )

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

    def nearest_top(self, point, across: float) -> tuple[Obstacle, float, np.ndarray] | None:
        """The top at or below a point (x, y, z) that is nearest to it, how far the point is
        off it along the floor, and the point on it nearest to the point with `across` of
        room round it (the top's middle when it has not that room; None: no top is so
        low). Nearest in space: a table's top 15 cm off, not its leg's foot under the
        point."""
        x, y, z = point
        below = [piece for piece in self.pieces if piece.high <= z + RESTING]
        if not below:
            return None
        at = Point(x, y)
        piece = min(below, key=lambda p: np.hypot(at.distance(p.outline), z - p.high))
        room = piece.outline.buffer(-across)
        inside = room if not room.is_empty else piece.outline.centroid
        onto = shapely.ops.nearest_points(inside, at)[0]
        return piece, at.distance(piece.outline), np.array([onto.x, onto.y, piece.high])

    def pile(self, piece: Obstacle) -> Obstacle:
        """`piece` and what it stands on, down to the floor, as one prism (its outlines'
        union): hands leaving the top of a stack go down outside all of it, not only outside
        its top box (coexistence seed 9: a hand went down into the box under it)."""
        pile, added = [piece], [piece]
        while added:
            added = [
                other
                for other in self.pieces
                if all(other is not p for p in pile)
                and any(_stands_on(top, other) for top in added)
            ]
            pile += added
        outline = shapely.union_all([p.outline for p in pile], grid_size=UNION_GRID)
        return Obstacle(piece.name, outline, min(p.low for p in pile), piece.high)

    def room(self, point, direction, low: float, high: float) -> float:
        """How far (m) a hand spanning the heights `low` to `high` can move from `point`
        along the floor direction `direction` before it meets a piece (FAR: no piece)."""
        start = Point(point[0], point[1])
        far = np.asarray(point[:2], dtype=float) + FAR * np.asarray(direction[:2], dtype=float)
        way = LineString([tuple(point[:2]), tuple(far)])
        return min(
            (
                start.distance(piece.outline)
                for piece in self.pieces
                if piece.low < high and piece.high > low and piece.outline.intersects(way)
            ),
            default=FAR,
        )

    def clear_way(self, start, direction, half_width: float, low: float, high: float) -> float:
        """How far (m) a band `half_width` either side of `start` (x, y) is clear along the
        floor direction `direction` (a unit vector) of the pieces spanning the heights `low`
        to `high` (FAR: all the way; 0: a piece covers `start`)."""
        ahead = np.asarray(direction[:2], dtype=float)
        side = half_width * np.array([-ahead[1], ahead[0]])
        at = np.asarray(start[:2], dtype=float)
        band = Polygon([at - side, at + side, at + side + FAR * ahead, at - side + FAR * ahead])
        reached = [
            float((shapely.get_coordinates(inside) @ ahead).min() - at @ ahead)
            for piece in self.pieces
            if piece.low < high
            and piece.high > low
            and not (inside := piece.outline.intersection(band)).is_empty
        ]
        return max(min(reached, default=FAR), 0.0)

    def highest_between(self, area: Polygon, low: float, high: float) -> float | None:
        """The highest top of the pieces over a floor area that reach between the heights
        `low` and `high` (None: none does)."""
        tops = [
            p.high
            for p in self.pieces
            if p.high > low and p.low < high and p.outline.intersects(area)
        ]
        return max(tops, default=None)

    def walls_round(self, surface: Obstacle) -> "Furniture":
        """The pieces that rise past the top of `surface` from below it: a bin's walls round
        its floor (what lies on a surface starts at its top; a shelf's board above it, over
        it)."""
        low, high = surface.high - RESTING / 2, surface.high + RESTING / 2
        return Furniture(tuple(p for p in self.pieces if p.low < low and p.high > high))

    def above(self, area: Polygon, height: float) -> "Furniture":
        """The pieces over a floor area wholly at or above `height` (the board above a
        shelf's compartment)."""
        return Furniture(
            tuple(p for p in self.pieces if p.low >= height and p.outline.intersects(area))
        )

    def lowest(self) -> float | None:
        """The lowest underside of the pieces (None: there are none)."""
        return min((p.low for p in self.pieces), default=None)

    def behind_edge(self, piece: Obstacle, point, back, margin: float):
        """`point` (x, y) moved along the floor direction `back` until it is `margin` outside
        the piece's outline (None: it is outside already)."""
        start = Point(point[0], point[1])
        grown = piece.outline.buffer(margin, join_style="mitre")
        if not grown.covers(start):
            return None
        far = np.asarray(point[:2], dtype=float) + FAR * np.asarray(back[:2], dtype=float)
        crossing = LineString([tuple(point[:2]), tuple(far)]).intersection(grown.boundary)
        nearest = min(getattr(crossing, "geoms", [crossing]), key=start.distance)
        return np.array([nearest.x, nearest.y])


def _stands_on(top: Obstacle, under: Obstacle) -> bool:
    """Whether `top` rests on `under`."""
    return abs(under.high - top.low) <= RESTING and under.outline.intersects(top.outline)
