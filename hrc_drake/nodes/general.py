"""The thesis system's general nodes (docs/thesis-system.md), same names and ports, plus Emit.

GenerateXYPose, InAreaTest, OffsetPose, InterruptableSequence, WeightedRandom,
RandomFailure; Emit records a task event (a part finished, a box handed over, ...) that the
run report counts.
"""

import numpy as np

from hrc_drake.areas import Area
from hrc_drake.bt import (
    ConditionNode,
    ControlNode,
    InputPort,
    OutputPort,
    Range,
    Status,
    SyncActionNode,
)
from hrc_drake.bt.controls.sequences import SequentialControl
from hrc_drake.bt.ports import value_to_text
from hrc_drake.tree_types import Pose


def _status(ok: bool) -> Status:
    return Status.SUCCESS if ok else Status.FAILURE


class GenerateXYPose(SyncActionNode):
    """A random position uniformly distributed over an area (z = 0, no orientation)."""

    ports = (
        InputPort("area", Area, description="area name or triangles x1,y1;x2,y2;x3,y3;..."),
        OutputPort("pose", Pose, description="the random position"),
    )

    def tick(self) -> Status:
        x, y = self.agent.area(self.get_input("area")).sample(self.rng)
        self.set_output("pose", Pose((float(x), float(y), 0.0)))
        return Status.SUCCESS


class InAreaTest(ConditionNode):
    """SUCCESS if the pose's x/y lies in the area."""

    ports = (
        InputPort("pose", Pose, description="pose or location name"),
        InputPort("area", Area, description="area name or triangles"),
    )

    def tick(self) -> Status:
        pose = self.agent.resolve_pose(self.get_input("pose"))
        return _status(self.agent.in_area(pose.xy, self.get_input("area")))


class OffsetPose(SyncActionNode):
    """Adds `offset` to the position; a given `orientation` replaces the pose's."""

    ports = (
        InputPort("input", Pose, description="pose or location name"),
        InputPort("offset", Pose, default=Pose(), description="x;y;z added to the position"),
        InputPort("orientation", str, default="", description="qw;qx;qy;qz (optional)"),
        OutputPort("output", Pose),
    )

    def tick(self) -> Status:
        inputs = {port: self.get_input(port) for port in ("input", "offset", "orientation")}
        try:
            self.set_output("output", self.static_outputs(self.agent, inputs)["output"])
        except ValueError as error:
            raise self.error(str(error), port="orientation") from None
        return Status.SUCCESS

    @staticmethod
    def static_outputs(agent, inputs: dict) -> dict:
        """The output from the inputs alone: what `validate` computes for inputs known
        before a run (hrc_drake.known_values)."""
        pose = agent.resolve_pose(inputs["input"])
        text = inputs["orientation"].strip()
        quaternion = tuple(float(v) for v in text.split(";")) if text else pose.quaternion
        if quaternion is not None and len(quaternion) != 4:
            raise ValueError("orientation needs 4 numbers qw;qx;qy;qz")
        position = tuple(float(v) for v in np.array(pose.position) + inputs["offset"].position)
        return {"output": Pose(position, quaternion)}


class InterruptableSequence(SequentialControl):
    """A Sequence that keeps its position when halted and resumes there when ticked again
    (behaviour that a higher-priority branch can pause)."""

    def __init__(self, config):
        super().__init__(config, stops_on=Status.FAILURE)

    def halt(self) -> None:
        self.skipped = 0
        ControlNode.halt(self)


class WeightedRandom(ControlNode):
    """Picks one child at random by weight and ticks only it until it returns SUCCESS;
    the tick after that picks anew. Returns the picked child's status."""

    ports = (
        InputPort(
            "weights", list[float], description="one weight per child, w1;w2;...", accepts=Range(0)
        ),
    )

    def __init__(self, config):
        super().__init__(config)
        self.picked: int | None = None

    def tick(self) -> Status:
        if self.picked is None:
            self.picked = self._pick()
        self.set_status(Status.RUNNING)
        status = self.children[self.picked].execute_tick()
        if status is not Status.RUNNING:
            self.reset_children()
        if status is Status.SUCCESS:
            self.picked = None
        return status

    def input_problem(self, port: str, value) -> str:
        """One weight per child, none negative, not all zero (as written: `1;2`)."""
        problem = super().input_problem(port, value)
        if port != "weights" or problem:
            return problem
        if len(value) != len(self.children):
            count = len(self.children)
            return f"needs {count} weights, one per child, got {len(value)}: {value_to_text(value)}"
        if sum(value) <= 0:
            return f"needs a weight above 0, got {value_to_text(value)}"
        return ""

    def _pick(self) -> int:
        weights = np.asarray(self.get_input("weights"), dtype=float)
        return int(self.rng.choice(len(weights), p=weights / weights.sum()))

    def on_tree_reset(self) -> None:
        self.picked = None


class RandomFailure(SyncActionNode):
    """FAILURE with probability `failure_chance`, else SUCCESS (an unreliable step)."""

    ports = (
        InputPort(
            "failure_chance", float, description="probability in [0, 1]", accepts=Range(0, 1)
        ),
    )

    def tick(self) -> Status:
        return _status(self.rng.random() >= self.get_input("failure_chance"))


class Emit(SyncActionNode):
    """Records a task event (e.g. part_finished) at the current time; reports count them."""

    ports = (
        InputPort("event", str, description="event name, e.g. part_finished"),
        InputPort("value", None, default="", description="optional detail (any type)"),
    )

    def tick(self) -> Status:
        self.agent.emit(self.get_input("event"), value_to_text(self.get_input("value")))
        return Status.SUCCESS


NODES = (
    GenerateXYPose,
    InAreaTest,
    OffsetPose,
    InterruptableSequence,
    WeightedRandom,
    RandomFailure,
    Emit,
)
