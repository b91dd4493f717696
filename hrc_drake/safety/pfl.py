"""Power and force limiting (ISO/TS 15066 Annex A): body-region limits and the
energy-transfer estimate of a contact's peak force and pressure (docs/safety.md).

A contact at relative speed v between the robot (effective mass m_R) and a body region
(effective mass m_H, spring constant k) peaks at F = v·sqrt(μ k), μ = (1/m_H + 1/m_R)⁻¹;
the pressure is F over the contact area. Two kinds of contact:

- transient: the region can recoil. Limits are twice the quasi-static ones, except on the
  skull, forehead and face, where transient contact is not permitted at all;
- quasi-static (clamping): the region is pinned against fixed cell geometry or another
  robot part. It cannot recoil, so its effective mass does not soften the impact (μ = m_R),
  and the robot pressing on keeps compressing it (F = k·depth); the Table A.2 limits apply
  as they are.

Pressure limits are each region's most restrictive location: where on a region a contact
lands is not known.
"""

import math
from dataclasses import dataclass

TRANSIENT_FACTOR = 2.0
N_PER_MM = 1000.0
"""N/m per N/mm (spring constants are tabulated in N/mm)."""

TRANSIENT = "transient"
QUASI_STATIC = "quasi-static"


@dataclass(frozen=True)
class RegionLimits:
    """One row of ISO/TS 15066 Table A.2 and its body model (docs/safety.md)."""

    max_force: float
    """N, quasi-static"""
    max_pressure: float
    """N/cm², quasi-static, the region's most restrictive location"""
    effective_mass: float
    """kg"""
    spring_constant: float
    """N/mm"""
    transient_allowed: bool = True

    def limits(self, kind: str) -> tuple[float, float]:
        """(force N, pressure N/cm²) permitted in a contact of this kind; a transient
        contact where it is banned keeps the quasi-static figures (and is a violation)."""
        factor = TRANSIENT_FACTOR if kind == TRANSIENT and self.transient_allowed else 1.0
        return factor * self.max_force, factor * self.max_pressure

    def permitted(self, kind: str) -> bool:
        return kind == QUASI_STATIC or self.transient_allowed


REGION_LIMITS: dict[str, RegionLimits] = {
    "skull_forehead": RegionLimits(130, 110, 4.4, 150, transient_allowed=False),
    "face": RegionLimits(65, 110, 4.4, 75, transient_allowed=False),
    "neck": RegionLimits(150, 140, 1.2, 50),
    "back_shoulders": RegionLimits(210, 160, 40, 35),
    "chest": RegionLimits(140, 120, 40, 25),
    "abdomen": RegionLimits(110, 140, 40, 10),
    "pelvis": RegionLimits(180, 210, 40, 25),
    "upper_arm": RegionLimits(150, 190, 3, 30),
    "lower_arm": RegionLimits(160, 180, 2, 40),
    "hand": RegionLimits(140, 190, 0.6, 75),
    "thigh": RegionLimits(220, 220, 75, 50),
    "lower_leg": RegionLimits(130, 210, 75, 60),
}


@dataclass(frozen=True)
class ContactAssessment:
    """One body region touched by one robot part, judged against its limits."""

    region: str
    part: str
    kind: str
    """TRANSIENT or QUASI_STATIC"""
    relative_speed: float
    """m/s, towards each other along the contact normal"""
    depth: float
    """m the robot part reaches into the region"""
    force: float
    """N"""
    pressure: float
    """N/cm²"""
    force_limit: float
    pressure_limit: float
    robot_moving: bool
    """False: the robot stood still, the person moved into it"""

    @property
    def force_ratio(self) -> float:
        return self.force / self.force_limit

    @property
    def pressure_ratio(self) -> float:
        return self.pressure / self.pressure_limit

    @property
    def violation(self) -> bool:
        """Over a limit, or a kind of contact the region must never have."""
        permitted = REGION_LIMITS[self.region].permitted(self.kind)
        return not permitted or self.force_ratio > 1.0 or self.pressure_ratio > 1.0

    @property
    def severity(self) -> tuple[bool, float]:
        """Orders contacts from harmless to worst."""
        return self.violation, max(self.force_ratio, self.pressure_ratio)


def robot_effective_mass(moving_mass: float, payload: float) -> float:
    """m_R = M/2 + m_L: half the moving robot parts plus tool and carried load (kg)."""
    return moving_mass / 2.0 + payload


def reduced_mass(human_mass: float, robot_mass: float) -> float:
    """μ = (1/m_H + 1/m_R)⁻¹ (kg)."""
    return 1.0 / (1.0 / human_mass + 1.0 / robot_mass)


def impact_stiffness(region: str, robot_mass: float, kind: str) -> float:
    """sqrt(μ k) in N·s/m: the peak force per m/s of relative speed. A pinned region takes
    the robot's whole effective mass (μ = m_R)."""
    limits = REGION_LIMITS[region]
    mu = robot_mass if kind == QUASI_STATIC else reduced_mass(limits.effective_mass, robot_mass)
    return math.sqrt(mu * limits.spring_constant * N_PER_MM)


def max_permissible_speed(
    region: str, robot_mass: float, contact_area_cm2: float, kind: str = TRANSIENT
) -> float:
    """v_max = min(F_max, p_max · A) / sqrt(μ k) with the limits of the contact kind; 0
    where that kind of contact is not permitted."""
    limits = REGION_LIMITS[region]
    if not limits.permitted(kind):
        return 0.0
    force, pressure = limits.limits(kind)
    return min(force, pressure * contact_area_cm2) / impact_stiffness(region, robot_mass, kind)


def assess_contact(
    region: str,
    part: str,
    relative_speed: float,
    robot_mass: float,
    contact_area_cm2: float,
    kind: str = TRANSIENT,
    depth: float = 0.0,
    robot_moving: bool = True,
) -> ContactAssessment:
    """Peak force and pressure of a contact, with the limits of its kind."""
    limits = REGION_LIMITS[region]
    speed = max(relative_speed, 0.0)
    force = speed * impact_stiffness(region, robot_mass, kind)
    if kind == QUASI_STATIC:
        force = max(force, limits.spring_constant * N_PER_MM * max(depth, 0.0))
    force_limit, pressure_limit = limits.limits(kind)
    return ContactAssessment(
        region=region,
        part=part,
        kind=kind,
        relative_speed=speed,
        depth=max(depth, 0.0),
        force=force,
        pressure=force / contact_area_cm2,
        force_limit=force_limit,
        pressure_limit=pressure_limit,
        robot_moving=robot_moving,
    )
