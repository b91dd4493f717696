"""What stands in the person's way over the floor besides the cell (what the robot holds
still): the obstacles a walk goes round, and the rest of a walk under way that might pass
through them (hrc_drake.human.protocol asks when the robot comes to rest mid-walk)."""

from hrc_drake.human.activity import Activity
from hrc_drake.human.messages import Box
from hrc_drake.human.navigation import Obstacle, box_obstacle
from hrc_drake.human.walking import WalkSegment


def in_the_way(boxes: tuple[Box, ...]) -> tuple[Obstacle, ...]:
    """The obstacles of the `boxes` that stand within the body's heights."""
    found = (box_obstacle(b.name, b.center, b.yaw, b.size) for b in boxes)
    return tuple(o for o in found if o is not None)


def rest_of_walk(activity: Activity, t: float) -> list[tuple[float, float]]:
    """The pelvis's path from where it is at t to the end of the activity's walks (empty
    when none is left)."""
    path = []
    for segment in activity.segments:
        if isinstance(segment, WalkSegment) and segment.over > t:
            along = segment.distance(max(t, segment.start))
            path.append(segment.point(along))
            path += [p for p, at in zip(segment.path, segment.lengths, strict=True) if at > along]
    return path
