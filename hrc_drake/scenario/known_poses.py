"""A node's known pose as validate's checks read it: its location name resolved, the way
it turns."""

import math

from hrc_drake.tree_types import Pose


def resolved(agent, value) -> Pose | None:
    """A Pose with its location name resolved (None: a name the scenario lacks, which
    loading reports)."""
    try:
        return agent.resolve_pose(value)
    except KeyError:
        return None


def heading(pose: Pose) -> float | None:
    """The yaw (rad) a pose turns to (None: it gives no orientation)."""
    if pose.quaternion is None:
        return None
    R = pose.to_transform().rotation().matrix()
    return math.atan2(R[1, 0], R[0, 0])
