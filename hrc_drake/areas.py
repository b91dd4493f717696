"""Named floor areas: 2-D polygons kept as triangles, for containment tests and sampling.

The thesis system this project re-creates (docs/thesis-system.md) described an area as a list of
triangles and sampled it by picking a triangle with probability proportional to its area, then a
uniform point inside it. We keep that representation and triangulate user polygons (ear clipping)
into it."""

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class Area:
    """A union of triangles in the floor plane; `triangles` has shape (n, 3, 2)."""

    triangles: np.ndarray

    @staticmethod
    def from_polygon(points) -> "Area":
        """Triangulates a simple polygon given by its vertices (either winding)."""
        return Area(np.asarray(triangulate(np.asarray(points, dtype=float)), dtype=float))

    @staticmethod
    def from_triangles(triangles) -> "Area":
        tris = np.asarray(triangles, dtype=float).reshape(-1, 3, 2)
        return Area(tris)

    @property
    def triangle_areas(self) -> np.ndarray:
        a, b, c = self.triangles[:, 0], self.triangles[:, 1], self.triangles[:, 2]
        return 0.5 * np.abs(_cross(b - a, c - a))

    @property
    def area(self) -> float:
        return float(self.triangle_areas.sum())

    def contains(self, xy) -> bool:
        """True when the point lies in (or on the border of) any triangle."""
        p = np.asarray(xy, dtype=float)[:2]
        return any(_in_triangle(p, tri) for tri in self.triangles)

    def sample(self, rng: np.random.Generator) -> np.ndarray:
        """A point uniformly distributed over the area."""
        weights = self.triangle_areas / self.triangle_areas.sum()
        a, b, c = self.triangles[rng.choice(len(self.triangles), p=weights)]
        u, v = rng.random(2)
        if u + v > 1.0:
            u, v = 1.0 - u, 1.0 - v
        return a + u * (b - a) + v * (c - a)


def _cross(u: np.ndarray, v: np.ndarray):
    return u[..., 0] * v[..., 1] - u[..., 1] * v[..., 0]


def _in_triangle(p: np.ndarray, tri: np.ndarray, eps: float = 1e-12) -> bool:
    signs = [_cross(tri[(i + 1) % 3] - tri[i], p - tri[i]) for i in range(3)]
    return min(signs) >= -eps or max(signs) <= eps


def triangulate(polygon: np.ndarray) -> list[np.ndarray]:
    """Ear-clipping triangulation of a simple polygon (n >= 3 vertices, no self-crossing)."""
    if polygon.ndim != 2 or polygon.shape[1] != 2:
        raise ValueError(
            "every point needs exactly two coordinates [x, y] (areas lie on the floor)"
        )
    if len(polygon) < 3:
        raise ValueError(f"a polygon needs at least 3 points, got {len(polygon)}")
    crossing = _crossing_edges(polygon)
    if crossing:
        i, j = crossing
        raise ValueError(f"its edges cross (the edge from point {i} and the edge from point {j})")
    signed_area = 0.5 * sum(_cross(polygon[i - 1], polygon[i]) for i in range(len(polygon)))
    if abs(signed_area) < 1e-12:
        raise ValueError("the polygon has zero area")
    remaining = list(range(len(polygon))) if signed_area > 0 else list(range(len(polygon)))[::-1]
    triangles = []
    while len(remaining) > 3:
        ear = _find_ear(polygon, remaining)
        n = len(remaining)
        triangles.append(polygon[[remaining[ear - 1], remaining[ear], remaining[(ear + 1) % n]]])
        del remaining[ear]
    triangles.append(polygon[remaining])
    return triangles


def _crossing_edges(polygon: np.ndarray) -> tuple[int, int] | None:
    """Two edges (by their first point) that touch though they are not neighbours; ear
    clipping would give such a polygon a wrong area and wrong containment."""
    n = len(polygon)
    edges = [(polygon[i], polygon[(i + 1) % n]) for i in range(n)]
    for i in range(n):
        for j in range(i + 1, n):
            neighbours = j == i + 1 or (i == 0 and j == n - 1)
            if neighbours:
                continue
            if _segments_touch(*edges[i], *edges[j]):
                return i, j
    return None


def _segments_touch(a, b, c, d) -> bool:
    def side(p, q, r):
        return _cross(q - p, r - p)

    d1, d2, d3, d4 = side(c, d, a), side(c, d, b), side(a, b, c), side(a, b, d)
    if d1 * d2 < 0 and d3 * d4 < 0:
        return True
    return any(
        abs(s) < 1e-12 and _on_segment(p, q, r)
        for s, p, q, r in ((d1, c, d, a), (d2, c, d, b), (d3, a, b, c), (d4, a, b, d))
    )


def _on_segment(p, q, r) -> bool:
    return bool(np.all(np.minimum(p, q) - 1e-12 <= r) and np.all(r <= np.maximum(p, q) + 1e-12))


def _find_ear(polygon: np.ndarray, ring: list[int]) -> int:
    n = len(ring)
    for i in range(n):
        a, b, c = polygon[ring[i - 1]], polygon[ring[i]], polygon[ring[(i + 1) % n]]
        if _cross(b - a, c - b) <= 0:
            continue
        others = (polygon[j] for j in ring if j not in (ring[i - 1], ring[i], ring[(i + 1) % n]))
        if not any(_in_triangle(p, np.array([a, b, c])) for p in others):
            return i
    raise ValueError("the polygon is not simple (its edges cross)")
