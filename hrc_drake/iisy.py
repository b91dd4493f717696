"""KUKA LBR iisy variants: published limits, model files, controller gains, plant helpers.

The numbers are those of docs/robot-data.md (public `kuka_lbr_iisy_support` data),
written here in the published units (degrees, deg/s) and converted to radians once. The
model generator (`python -m hrc_drake.modelgen`) writes the same limits into the model files,
so `MultibodyPlant.GetPosition/Velocity/Effort/AccelerationUpperLimits()` return them too.
"""

import math
from dataclasses import dataclass

from pydrake.multibody.parsing import Parser
from pydrake.multibody.plant import MultibodyPlant
from pydrake.multibody.tree import ModelInstanceIndex

from hrc_drake.paths import MODEL_PACKAGE, add_bundled_model, add_model_package, bundled_model_file

JOINT_NAMES = ("A1", "A2", "A3", "A4", "A5", "A6")
LINK_NAMES = ("base_link", "link_1", "link_2", "link_3", "link_4", "link_5", "link_6")
BASE_FRAME = "base_link"
FLANGE_FRAME = "flange"
"""At the flange face on the A6 axis; z points out of the flange (ISO 9409-1)."""

TOOL_URL = f"package://{MODEL_PACKAGE}/tools/vacuum_gripper.sdf"
TOOL_BODY = "vacuum_gripper"
TCP_FRAME = "tcp"
"""Suction cup face of the vacuum gripper; z points out of the cup."""

HOME_DEG = (0.0, -75.0, 90.0, 0.0, 75.0, 0.0)
"""Upper arm 15 deg forward of vertical, forearm 15 deg below horizontal, tool pointing down.

The joint conventions of all three variants agree (A2 = -90 deg is upright, A5 = +90 deg
turns the tool down when the forearm is horizontal), so one home pose serves all.
"""


@dataclass(frozen=True)
class RobotVariant:
    """One LBR iisy variant: what the builder, planner and controller need to know.

    All joint tuples are ordered A1..A6, in SI units (rad, rad/s, N*m, rad/s^2).
    Controller gains are RobotController's (hrc_drake.systems.robot_controller): they act
    on accelerations.
    """

    name: str
    payload: float
    reach: float
    total_mass: float
    position_lower: tuple[float, ...]
    position_upper: tuple[float, ...]
    velocity_limits: tuple[float, ...]
    effort_limits: tuple[float, ...]
    acceleration_limits: tuple[float, ...]
    home: tuple[float, ...]
    kp: tuple[float, ...]
    kd: tuple[float, ...]
    joint_names: tuple[str, ...] = JOINT_NAMES

    @property
    def model_url(self) -> str:
        return f"package://{MODEL_PACKAGE}/iisy/{self.name}.sdf"


def _radians(degrees: tuple[float, ...]) -> tuple[float, ...]:
    return tuple(math.radians(d) for d in degrees)


def _variant(
    name: str,
    payload: float,
    reach: float,
    total_mass: float,
    a4_range_deg: float,
    speed_deg: tuple[float, ...],
    effort: tuple[float, ...],
    acceleration: tuple[float, ...],
    kp: tuple[float, ...],
) -> RobotVariant:
    """Variant from the published table rows; the joint ranges differ only in A4."""
    upper_deg = (185.0, 50.0, 150.0, a4_range_deg, 110.0, 220.0)
    lower_deg = (-185.0, -230.0, -150.0, -a4_range_deg, -110.0, -220.0)
    return RobotVariant(
        name=name,
        payload=payload,
        reach=reach,
        total_mass=total_mass,
        position_lower=_radians(lower_deg),
        position_upper=_radians(upper_deg),
        velocity_limits=_radians(speed_deg),
        effort_limits=effort,
        acceleration_limits=acceleration,
        home=_radians(HOME_DEG),
        kp=kp,
        kd=tuple(2.0 * math.sqrt(k) for k in kp),
    )


VARIANTS: dict[str, RobotVariant] = {
    v.name: v
    for v in (
        _variant(
            "lbr_iisy3_r760",
            payload=3.0,
            reach=0.7605,
            total_mass=17.8,
            a4_range_deg=175.0,
            speed_deg=(200.0, 200.0, 200.0, 300.0, 300.0, 400.0),
            effort=(74.9, 74.5, 43.4, 14.8, 13.2, 4.8),
            acceleration=(17.6, 2.10, 10.7, 27.3, 21.8, 112.3),
            kp=(400.0, 400.0, 400.0, 300.0, 300.0, 200.0),
        ),
        _variant(
            "lbr_iisy11_r1300",
            payload=11.0,
            reach=1.300,
            total_mass=46.4,
            a4_range_deg=180.0,
            speed_deg=(200.0, 200.0, 200.0, 230.0, 260.0, 430.0),
            effort=(405.8, 366.2, 147.2, 65.5, 64.7, 15.7),
            acceleration=(11.1, 1.11, 1.84, 40.2, 43.7, 134.6),
            kp=(300.0, 250.0, 250.0, 300.0, 300.0, 200.0),
        ),
        _variant(
            "lbr_iisy15_r930",
            payload=15.0,
            reach=0.930,
            total_mass=43.6,
            a4_range_deg=180.0,
            speed_deg=(200.0, 200.0, 200.0, 230.0, 260.0, 430.0),
            effort=(398.0, 286.5, 137.7, 63.6, 58.6, 15.9),
            acceleration=(17.9, 1.32, 1.93, 20.8, 17.7, 98.8),
            kp=(300.0, 250.0, 250.0, 300.0, 300.0, 200.0),
        ),
    )
}


def add_iisy(plant: MultibodyPlant, variant_name: str, parser: Parser) -> ModelInstanceIndex:
    """Parse one iisy variant into `plant`; the caller welds its `base_link` frame."""
    add_model_package(parser.package_map())
    return add_bundled_model(parser, bundled_model_file(VARIANTS[variant_name].model_url))


def add_tool(
    plant: MultibodyPlant, robot: ModelInstanceIndex, parser: Parser
) -> ModelInstanceIndex:
    """Parse the vacuum gripper and weld it to the robot's flange (tool z = flange z)."""
    add_model_package(parser.package_map())
    tool = add_bundled_model(parser, bundled_model_file(TOOL_URL))
    plant.WeldFrames(
        plant.GetFrameByName(FLANGE_FRAME, robot),
        plant.GetBodyByName(TOOL_BODY, tool).body_frame(),
    )
    return tool
