"""Conditions on where the person is and how close they are to the robot, for trees that
adapt the robot's behaviour (the thesis system's speed rule, docs/thesis-system.md: slower while
someone is near), and on what the robot does, for a person who must not reach in while it moves."""

from hrc_drake.areas import Area
from hrc_drake.bt import ConditionNode, InputPort, Range, Status
from hrc_drake.motion.messages import IDLE


class HumanInArea(ConditionNode):
    """SUCCESS while the person stands inside the area (their base position)."""

    ports = (InputPort("area", Area, description="area name or triangles"),)

    def tick(self) -> Status:
        status = self.agent.human
        inside = status is not None and self.agent.in_area(
            status.base_pose[:2], self.get_input("area")
        )
        return Status.SUCCESS if inside else Status.FAILURE


class RobotInArea(ConditionNode):
    """SUCCESS while the robot's tool centre point lies above the area (x, y), e.g. while
    it works in a tray: the person waits before putting a hand there."""

    ports = (InputPort("area", Area, description="area name or triangles"),)

    def tick(self) -> Status:
        status = self.agent.robot
        inside = status is not None and self.agent.in_area(
            status.tool_pose.translation()[:2], self.get_input("area")
        )
        return Status.SUCCESS if inside else Status.FAILURE


class RobotAtRest(ConditionNode):
    """SUCCESS while the robot holds still with no motion under way. A robot in a monitored
    stop is not at rest: it goes on along its path as soon as the person steps back, so a
    person waiting for it to reach its waiting pose must not reach in yet."""

    def tick(self) -> Status:
        status = self.agent.robot
        return Status.SUCCESS if status is not None and status.mode == IDLE else Status.FAILURE


class SeparationBelow(ConditionNode):
    """SUCCESS while the smallest person-robot distance is below `distance` (metres)."""

    ports = (InputPort("distance", float, description="threshold in metres", accepts=Range(0)),)

    def tick(self) -> Status:
        status = self.agent.safety
        close = status is not None and status.separation < self.get_input("distance")
        return Status.SUCCESS if close else Status.FAILURE


NODES = (HumanInArea, RobotInArea, RobotAtRest, SeparationBelow)
