"""Power and force limiting (ISO/TS 15066 Annex A): body-region limits and the
energy-transfer estimate of a transient contact's peak force and pressure.

A contact at relative speed v between the robot (effective mass m_R) and a body region
(effective mass m_H, spring constant k) peaks at F = v·sqrt(μ k), μ = (1/m_H + 1/m_R)⁻¹;
the pressure is F over the contact area. Transient contact may reach twice the
quasi-static limits, except on the skull, forehead and face, where it is not permitted.
"""

import math
from dataclasses import dataclass

TRANSIENT_FACTOR = 2.0
CM2 = 1e-4
"""m² per cm² (pressures are tabulated in N/cm²)."""


@dataclass(frozen=True)
class RegionLimits:
    """One row of the ISO/TS 15066 table: quasi-static limits and the region's model."""

    max_force: float
    """N, quasi-static"""
    max_pressure: float
    """N/cm², quasi-static"""
    effective_mass: float
    """kg"""
    spring_constant: float
    """N/mm"""
    transient_allowed: bool = True

    @property
    def _factor(self) -> float:
        return TRANSIENT_FACTOR if self.transient_allowed else 1.0

    @property
    def force_limit(self) -> float:
        """Transient force limit (N); the quasi-static one where transient contact is banned."""
        return self._factor * self.max_force

    @property
    def pressure_limit(self) -> float:
        """Transient pressure limit (N/cm²), like `force_limit`."""
        return self._factor * self.max_pressure


REGION_LIMITS: dict[str, RegionLimits] = {
    "skull_forehead": RegionLimits(130, 130, 4.4, 150, transient_allowed=False),
    "face": RegionLimits(65, 110, 4.4, 75, transient_allowed=False),
    "neck": RegionLimits(150, 140, 1.2, 50),
    "back_shoulders": RegionLimits(210, 160, 40, 35),
    "chest": RegionLimits(140, 120, 40, 25),
    "abdomen": RegionLimits(110, 140, 40, 10),
    "pelvis": RegionLimits(180, 210, 40, 25),
    "upper_arm": RegionLimits(150, 190, 3, 30),
    "lower_arm": RegionLimits(160, 180, 2, 40),
    "hand": RegionLimits(140, 260, 0.6, 75),
    "thigh": RegionLimits(220, 250, 75, 50),
    "lower_leg": RegionLimits(130, 220, 75, 60),
}


@dataclass(frozen=True)
class ContactAssessment:
    """A contact judged against its region's transient limits."""

    region: str
    relative_speed: float
    """m/s, towards each other along the contact normal"""
    force: float
    """N"""
    pressure: float
    """N/cm²"""
    limit_ratio: float
    """largest of force / limit and pressure / limit; > 1 exceeds a limit"""
    violation: bool


def robot_effective_mass(moving_mass: float, payload: float) -> float:
    """m_R = M/2 + m_L: half the moving robot parts plus tool and carried load (kg)."""
    return moving_mass / 2.0 + payload


def reduced_mass(human_mass: float, robot_mass: float) -> float:
    """μ = (1/m_H + 1/m_R)⁻¹ (kg)."""
    return 1.0 / (1.0 / human_mass + 1.0 / robot_mass)


def transient_force(speed: float, mu: float, spring_constant_n_per_mm: float) -> float:
    """F = v·sqrt(μ k), k converted from N/mm to N/m."""
    return speed * math.sqrt(mu * spring_constant_n_per_mm * 1000.0)


def max_permissible_speed(region: str, robot_mass: float) -> float:
    """v_max = F_max / sqrt(μ k) with the transient F_max; 0 where transient contact is banned."""
    limits = REGION_LIMITS[region]
    if not limits.transient_allowed:
        return 0.0
    mu = reduced_mass(limits.effective_mass, robot_mass)
    return limits.force_limit / transient_force(1.0, mu, limits.spring_constant)


def assess_contact(
    region: str, relative_speed: float, robot_mass: float, contact_area_cm2: float
) -> ContactAssessment:
    """Peak force and pressure of a transient contact, compared with the region's limits."""
    limits = REGION_LIMITS[region]
    speed = max(relative_speed, 0.0)
    mu = reduced_mass(limits.effective_mass, robot_mass)
    force = transient_force(speed, mu, limits.spring_constant)
    pressure = force / contact_area_cm2
    ratio = max(force / limits.force_limit, pressure / limits.pressure_limit)
    violation = ratio > 1.0 or not limits.transient_allowed
    return ContactAssessment(region, speed, force, pressure, ratio, violation)
