"""A test double of the workpieces system's gripper interface (never used in scenarios).

It answers each new GripperRequest at its next update: a grip attaches the object whose
grasp pose is within the tolerance of the suction cup, if it is not too heavy.
"""

from dataclasses import dataclass

import numpy as np
from pydrake.common.value import AbstractValue
from pydrake.math import RigidTransform
from pydrake.systems.framework import EventStatus, LeafSystem

from hrc_drake.messages import FAILED, SUCCEEDED
from hrc_drake.motion.messages import GRIP, GripperRequest, GripperResult

TOLERANCE = 0.005


@dataclass(frozen=True)
class Part:
    name: str
    grasp: RigidTransform
    mass: float


class GripperDouble(LeafSystem):
    def __init__(self, parts: list[Part]):
        super().__init__()
        self._parts = parts
        self.DeclareAbstractInputPort("gripper_request", AbstractValue.Make(None))
        self._result = self.DeclareAbstractState(AbstractValue.Make(None))
        self.DeclareStateOutputPort("gripper_result", self._result)
        self.DeclarePeriodicUnrestrictedUpdateEvent(0.01, 0.005, self._answer)

    def _answer(self, context, state) -> EventStatus:
        request = self.get_input_port().Eval(context)
        last = context.get_abstract_state(self._result).get_value()
        if isinstance(request, GripperRequest) and (last is None or last.seq < request.seq):
            state.get_mutable_abstract_state(self._result).set_value(self._result_for(request))
        return EventStatus.Succeeded()

    def _result_for(self, request: GripperRequest) -> GripperResult:
        if request.action != GRIP:
            return GripperResult(request.seq, SUCCEEDED)
        cup = request.tcp_pose.translation()
        near = [p for p in self._parts if np.linalg.norm(p.grasp.translation() - cup) < TOLERANCE]
        if not near:
            return GripperResult(request.seq, FAILED, reason="no object at the suction cup")
        if near[0].mass > request.max_payload:
            return GripperResult(request.seq, FAILED, reason=f"{near[0].name} is too heavy")
        return GripperResult(request.seq, SUCCEEDED, held_object=near[0].name)
