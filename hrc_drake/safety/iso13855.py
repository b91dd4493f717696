"""ISO 13855's positioning of electro-sensitive protective equipment (docs/safety.md): the
minimum distance S = K·T + C of a detection zone from the hazard, its intrusion distance C
and the heights a detection zone may have (SI units: m, s, m/s).

    S = K · T + C          K the approach speed, T the overall stopping time (the sensor's
                           response time, the controller's, the machine's stop)

- Orthogonal approach (a light curtain, clause 6.2.3): C = 8 (d − 14 mm) for a detection
  capability d up to 40 mm (at least 0), with K = 2000 mm/s where S is at most 500 mm, else
  K = 1600 mm/s and S at least 500 mm; C = 850 mm above 40 mm (reaching through with the
  arm), with K = 1600 mm/s.
- A light curtain against whole-body access (clause 6.2): its lowest beam at most 300 mm
  above the floor (else a person crawls under it), its highest at least 900 mm (else one
  steps or reaches over it: Table 1, C_RO for reaching over a detection zone, has no upper
  edge below 900 mm).
- Parallel approach (a horizontal laser scanner, clause 6.3): K = 1600 mm/s and
  C = 1200 mm − 0.4 H, at least 850 mm, for a detection zone H above the floor; H is at
  most 1000 mm and at least 15 (d − 50 mm), so that a leg is detected.
"""

K_WALK = 1.6
"""m/s: ISO 13855's approach speed of the body (walking)"""
K_HAND = 2.0
"""m/s: ISO 13855's approach speed of hand and arm"""
NEAR = 0.5
"""m: K_HAND applies where S computed with it is at most this, and S is at least this with
K_WALK"""
ARM_INTRUSION = 0.85
"""m: C of reaching over or through with the arm (the least C of a horizontal zone)"""
HORIZONTAL_BASE = 1.2
"""m: C of a horizontal detection zone on the floor"""
HORIZONTAL_SLOPE = 0.4
"""C of a horizontal zone falls by this much per metre of its height"""
HIGHEST_HORIZONTAL = 1.0
"""m: the highest a horizontal detection zone may be"""
LEG_HEIGHT_FACTOR = 15.0
"""H ≥ 15 (d − 50 mm): a detection zone low enough that a leg crosses it"""
LEG_FREE_CAPABILITY = 0.05
"""m: detection capabilities up to this may lie on the floor"""
FINGER = 0.014
"""m: the detection capability whose C is 0 (a finger)"""
FINGER_SLOPE = 8.0
"""C = 8 (d − 14 mm) for orthogonal zones of high resolution"""
FINE = 0.04
"""m: orthogonal detection capabilities up to this use C = 8 (d − 14 mm)"""
COARSEST = 0.07
"""m: the coarsest detection capability ISO 13855's orthogonal formulas cover"""

LOWEST_BEAM_AT_MOST = 0.3
"""m: a curtain's lowest beam no higher than this, so that no one crawls under it"""
TOP_BEAM_AT_LEAST = 0.9
"""m: a curtain's highest beam no lower than this, so that no one steps or reaches over"""


def horizontal_intrusion(height: float) -> float:
    """C of a horizontal detection zone `height` above the floor (parallel approach)."""
    return max(HORIZONTAL_BASE - HORIZONTAL_SLOPE * height, ARM_INTRUSION)


def lowest_horizontal_height(capability: float) -> float:
    """The least height of a horizontal zone with detection capability `capability`."""
    return max(LEG_HEIGHT_FACTOR * (capability - LEG_FREE_CAPABILITY), 0.0)


def orthogonal_intrusion(capability: float) -> float:
    """C of a vertical detection zone approached head on (a light curtain)."""
    if capability <= FINE:
        return max(FINGER_SLOPE * (capability - FINGER), 0.0)
    return ARM_INTRUSION


def orthogonal_distance(stopping_time: float, capability: float) -> float:
    """S of a light curtain with detection capability `capability` and overall stopping
    time `stopping_time`: K = 2000 mm/s where that gives at most 500 mm (fine resolutions),
    else K = 1600 mm/s and at least 500 mm."""
    intrusion = orthogonal_intrusion(capability)
    if capability <= FINE:
        near = K_HAND * stopping_time + intrusion
        if near <= NEAR:
            return near
    return max(K_WALK * stopping_time + intrusion, NEAR)


def horizontal_distance(stopping_time: float, height: float) -> float:
    """S of a horizontal detection zone `height` above the floor."""
    return K_WALK * stopping_time + horizontal_intrusion(height)
