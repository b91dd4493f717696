"""RobotController: inverse-dynamics control of the arm, built from Drake's C++ systems.

    desired acceleration  a* = a_d + Kp (q_d - q) + Kd (v_d - v)
    joint torque          tau = M(q) a* + C(q, v) v - tau_g(q)      (InverseDynamics)

This is InverseDynamicsController without the integral term, on purpose: the controller's
plant is the simulated arm and tool, so there is no model error for an integrator to remove,
and its continuous state would make the Simulator integrate (and call every Python system for
derivatives and witness functions) at each 1 kHz plant step. Without it the diagram has no
continuous state at all.

Inputs `estimated_state` (q, v), `desired_state` (q_d, v_d) and, with
`reference_acceleration`, `desired_acceleration` (a_d); output `generalized_force`.
"""

import numpy as np
from pydrake.multibody.plant import MultibodyPlant
from pydrake.systems.controllers import InverseDynamics
from pydrake.systems.framework import Diagram, DiagramBuilder
from pydrake.systems.primitives import MatrixGain, Multiplexer

from hrc_drake.iisy import VARIANTS
from hrc_drake.station import StationSpec, make_control_plant
from hrc_drake.wiring import ROBOT_CONTROLLER


class RobotController(Diagram):
    def __init__(
        self,
        control_plant: MultibodyPlant,
        kp: tuple[float, ...],
        kd: tuple[float, ...],
        reference_acceleration: bool = True,
    ):
        super().__init__()
        self._control_plant = control_plant  # InverseDynamics keeps only a pointer to it
        n = control_plant.num_positions()
        builder = DiagramBuilder()
        sizes = [2 * n, 2 * n] + ([n] if reference_acceleration else [])
        stacked = builder.AddNamedSystem("stacked_inputs", Multiplexer(sizes))
        gain = builder.AddNamedSystem(
            "pd_gain", MatrixGain(_acceleration_gain(kp, kd, reference_acceleration))
        )
        dynamics = builder.AddNamedSystem("inverse_dynamics", InverseDynamics(control_plant))
        builder.Connect(stacked.get_output_port(), gain.get_input_port())
        builder.Connect(gain.get_output_port(), dynamics.get_input_port_desired_acceleration())
        builder.ExportInput(dynamics.get_input_port_estimated_state(), "estimated_state")
        builder.ConnectInput("estimated_state", stacked.get_input_port(1))
        builder.ExportInput(stacked.get_input_port(0), "desired_state")
        if reference_acceleration:
            builder.ExportInput(stacked.get_input_port(2), "desired_acceleration")
        builder.ExportOutput(dynamics.get_output_port_generalized_force(), "generalized_force")
        builder.BuildInto(self)


def _acceleration_gain(kp, kd, reference_acceleration: bool) -> np.ndarray:
    """The matrix taking (x_d, x[, a_d]) to a*: [K, -K(, I)] with K = [diag(Kp), diag(Kd)]."""
    gains = np.hstack([np.diag(kp), np.diag(kd)])
    blocks = [gains, -gains] + ([np.eye(len(kp))] if reference_acceleration else [])
    return np.hstack(blocks)


def add_robot_controller(
    builder, station: StationSpec, plant, arm, reference_acceleration: bool = True
) -> RobotController:
    """Adds the station robot's controller as ROBOT_CONTROLLER, reading the arm's state from
    `plant` and driving its actuation (its model of the robot has the plant's time step);
    the caller connects the desired state."""
    variant = VARIANTS[station.variant]
    control_plant = make_control_plant(station, plant.time_step())
    controller = builder.AddNamedSystem(
        ROBOT_CONTROLLER,
        RobotController(control_plant, variant.kp, variant.kd, reference_acceleration),
    )
    builder.Connect(plant.get_state_output_port(arm), controller.GetInputPort("estimated_state"))
    builder.Connect(
        controller.GetOutputPort("generalized_force"), plant.get_actuation_input_port(arm)
    )
    return controller
