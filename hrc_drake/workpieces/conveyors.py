"""Belt conveyors: objects resting on a belt move along it at its speed.

Along a belt, positions are measured from its start towards its end. Each update plans how
far every object on the belt may advance: at most speed x period, never past the end of a
queueing belt, never into the object ahead of it (objects whose lateral extents overlap
queue behind each other). On a removing belt an object leaves once its centre passes the end.
"""

import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from hrc_drake.workpieces.config import QUEUE, ConveyorConfig
from hrc_drake.workpieces.geometry import OVERLAP_MARGIN
from hrc_drake.workpieces.surfaces import Surface

HELD_OVER_THE_BELT = 0.1
"""m: what is held with its bottom this little above a belt stands in its riders' way."""
HAND_REACH = 0.1
"""m: how far the hand reaches round its palm's grasp point (the fingers, the heel of the
hand): a palm this near a rider's way is in it."""


@dataclass(frozen=True)
class Extent:
    """An outline's extent in belt coordinates: along the belt and across it."""

    back: float
    front: float
    right: float
    left: float

    def beside(self, other: "Extent") -> bool:
        """Whether the two pass each other without touching (their lanes do not overlap)."""
        return self.left < other.right + OVERLAP_MARGIN or other.left < self.right + OVERLAP_MARGIN


@dataclass(frozen=True)
class Belt:
    name: str
    start: np.ndarray
    height: float
    axis: np.ndarray
    length: float
    width: float
    speed: float
    queues: bool
    queue_gap: float

    @staticmethod
    def of(name: str, config: ConveyorConfig) -> "Belt":
        start, end = np.asarray(config.start, float), np.asarray(config.end, float)
        length = float(np.linalg.norm(end[:2] - start[:2]))
        return Belt(
            name=name,
            start=start[:2],
            height=float(start[2]),
            axis=(end[:2] - start[:2]) / length,
            length=length,
            width=config.width,
            speed=config.speed,
            queues=config.at_end == QUEUE,
            queue_gap=config.queue_gap,
        )

    @cached_property
    def across(self) -> np.ndarray:
        """The unit vector across the belt, to its left (every rider's extent uses it)."""
        return np.array([-self.axis[1], self.axis[0]])

    @property
    def surface(self) -> Surface:
        corners = [(0.0, -1.0), (self.length, -1.0), (self.length, 1.0), (0.0, 1.0)]
        half = self.width / 2 * self.across
        outline = np.array([self.start + s * self.axis + side * half for s, side in corners])
        return Surface(self.name, self.height, outline)

    def extent(self, outline: np.ndarray) -> Extent:
        along = (outline - self.start) @ self.axis
        across = (outline - self.start) @ self.across
        return Extent(along.min(), along.max(), across.min(), across.max())

    def under(self, outline: np.ndarray) -> bool:
        """Whether some of the outline is over the belt."""
        e, half = self.extent(outline), self.width / 2
        return e.front > 0.0 and e.back < self.length and e.left > -half and e.right < half

    def riders(self, pieces) -> dict[int, np.ndarray]:
        """The outlines of the free pieces resting on the belt, by id."""
        return {p.id: p.footprint for p in pieces if p.holder is None and p.support == self.name}

    def held_over(self, pieces) -> list[np.ndarray]:
        """The outlines of what is held just over the belt (HELD_OVER_THE_BELT)."""
        return [
            p.footprint
            for p in pieces
            if p.holder is not None
            and p.bottom < self.height + HELD_OVER_THE_BELT
            and self.under(p.footprint)
        ]

    def in_the_way(self, outline: np.ndarray, top: float, palm: np.ndarray) -> bool:
        """Whether a palm (its grasp point) is where the rider with `outline` and `top`
        goes: ahead of its front, or beside or over it, within HAND_REACH of its lane and
        top (a palm behind it is left behind; one on a short rider's back face counts)."""
        e, (along, across) = self.extent(outline), self._coordinates(palm[:2])
        return (
            along + HAND_REACH > e.front
            and e.right - HAND_REACH < across < e.left + HAND_REACH
            and palm[2] < top + HAND_REACH
        )

    def _coordinates(self, p: np.ndarray) -> tuple[float, float]:
        """A point's place along the belt and across it."""
        return float((p - self.start) @ self.axis), float((p - self.start) @ self.across)

    def past_end(self, p_W: np.ndarray) -> bool:
        return float((p_W[:2] - self.start) @ self.axis) > self.length

    def velocity(self, speed: float) -> np.ndarray:
        return np.array([*(speed * self.axis), 0.0])

    def plan(
        self, riders: dict[int, np.ndarray], dt: float, blockers=(), held=frozenset()
    ) -> dict[int, float]:
        """Speed along the belt of each rider (id -> outline) for the next `dt`; `blockers`
        (outlines) stop the riders behind them as a rider ahead does: what is held just over
        the belt (a carton taken off a queueing belt's end: the next one moved into its
        place, 4.1 cm into it, in a user's palletizing cell). The `held` riders (ids) stay
        where they are, and hold back those behind them."""
        advances = self._advances(riders, self.speed * dt, blockers, held)
        return {i: advance / dt for i, advance in advances.items()}

    def rest_places(self, riders: dict[int, np.ndarray], blockers=()) -> dict[int, float]:
        """How far along the belt each rider of a queueing belt goes before it comes to rest
        in the queue as it stands (nothing taken off): where the person's hands keep out of
        a carton still on its way (a hand went 1.0 cm into the next carton, which came to
        rest after the pick had been planned, a user's palletizing cell)."""
        return self._advances(riders, math.inf, blockers) if self.queues else {}

    def _advances(
        self, riders: dict[int, np.ndarray], reach: float, blockers, held=frozenset()
    ) -> dict[int, float]:
        """How far each rider may advance, at most `reach` (none, the `held` ones), front
        ones first."""
        extents = {i: self.extent(outline) for i, outline in riders.items()}
        advances: dict[int, float] = {}
        moved_ahead: list[Extent] = [self.extent(outline) for outline in blockers]
        for i in sorted(extents, key=lambda i: (-extents[i].front, i)):
            extent = extents[i]
            limit = self.length if self.queues else math.inf
            for ahead in moved_ahead:
                if ahead.front >= extent.front and not extent.beside(ahead):
                    limit = min(limit, ahead.back - self.queue_gap)
            advance = 0.0 if i in held else min(reach, max(limit - extent.front, 0.0))
            advances[i] = advance
            moved_ahead.append(
                Extent(extent.back + advance, extent.front + advance, extent.right, extent.left)
            )
        return advances
