"""Collision-free joint-space paths: the straight line when it is free, else RRT-Connect.

The search samples from a seeded Generator and stops after a number of tree nodes (never
after a time), so the same problem always gives the same path or the same failure; the
result is shortened greedily (each waypoint joined to the farthest one it sees, at most
n²/2 edge checks for n waypoints).
"""

import numpy as np

from hrc_drake.motion.errors import PlanningFailed

STEP = 0.25
"""rad: longest edge the trees grow at once."""
GOAL_BIAS = 0.1


def collision_free_waypoints(
    model, q_start: np.ndarray, q_goal: np.ndarray, rng: np.random.Generator, max_nodes: int
) -> list[np.ndarray] | None:
    """Waypoints from start to goal whose straight segments are collision-free, or None when
    the two search trees together reach `max_nodes` nodes without meeting."""
    if not model.collision_free(q_start):
        raise PlanningFailed(
            "the robot starts closer to the cell than the planning clearance: "
            "retreat with MoveLinear first"
        )
    if model.edge_collision_free(q_start, q_goal):
        return [q_start, q_goal]
    path = _rrt_connect(model, q_start, q_goal, rng, max_nodes)
    return _shortcut(model, path) if path is not None else None


class _Tree:
    def __init__(self, root: np.ndarray):
        self.nodes = [root]
        self.parents = [-1]
        self._array = root[None, :]

    def nearest(self, q: np.ndarray) -> int:
        return int(np.argmin(np.linalg.norm(self._array - q, axis=1)))

    def add(self, q: np.ndarray, parent: int) -> int:
        self.nodes.append(q)
        self.parents.append(parent)
        self._array = np.vstack([self._array, q])
        return len(self.nodes) - 1

    def path_to_root(self, index: int) -> list[np.ndarray]:
        path = []
        while index >= 0:
            path.append(self.nodes[index])
            index = self.parents[index]
        return path


def _rrt_connect(model, q_start, q_goal, rng, max_nodes: int) -> list[np.ndarray] | None:
    start_tree = _Tree(q_start)
    grow, other = start_tree, _Tree(q_goal)
    while len(grow.nodes) + len(other.nodes) < max_nodes:
        target = (
            other.nodes[0] if rng.random() < GOAL_BIAS else rng.uniform(model.lower, model.upper)
        )
        new = _extend(model, grow, target)
        if new is not None:
            reached = _connect(model, other, grow.nodes[new])
            if reached is not None:
                path = grow.path_to_root(new)[::-1] + other.path_to_root(reached)[1:]
                return path if grow is start_tree else path[::-1]
        grow, other = other, grow
    return None


def _extend(model, tree: _Tree, target: np.ndarray) -> int | None:
    """One step of at most STEP from the nearest node toward `target`, if it is free."""
    nearest = tree.nearest(target)
    q_from = tree.nodes[nearest]
    delta = target - q_from
    distance = np.linalg.norm(delta)
    q_new = target if distance <= STEP else q_from + delta * (STEP / distance)
    if distance < 1e-9 or not model.edge_collision_free(q_from, q_new):
        return None
    return tree.add(q_new, nearest)


def _connect(model, tree: _Tree, target: np.ndarray) -> int | None:
    """Steps toward `target` until it is reached (its index) or blocked (None)."""
    while True:
        index = _extend(model, tree, target)
        if index is None:
            return None
        if np.linalg.norm(tree.nodes[index] - target) < 1e-9:
            return index


def _shortcut(model, path: list[np.ndarray]) -> list[np.ndarray]:
    """Greedy shortening: from each kept waypoint jump to the farthest visible one."""
    kept = [path[0]]
    i = 0
    while i < len(path) - 1:
        j = len(path) - 1
        while j > i + 1 and not model.edge_collision_free(path[i], path[j]):
            j -= 1
        kept.append(path[j])
        i = j
    return kept
