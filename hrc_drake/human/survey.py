"""People by sex and percentile: stature and body mass from a published anthropometric
survey, the size `hrc_drake.human.anthropometry.build_skeleton` scales the body to."""

from statistics import NormalDist

SEXES = ("female", "male")
SURVEY = {
    "female": {"stature": (1.6285, 0.0642), "mass": (67.8, 11.3)},
    "male": {"stature": (1.7562, 0.0686), "mass": (85.4, 14.2)},
}
"""Mean and standard deviation of stature (m) and body mass (kg) by sex in the 2012
Anthropometric Survey of U.S. Army Personnel, ANSUR II (Gordon et al., NATICK/TR-15/007,
2014; docs/ergonomics.md)."""
PERCENTILE_RANGE = (1.0, 99.0)


def survey_size(sex: str, percentile: float) -> tuple[float, float]:
    """Height (m) and mass (kg) of a person of `sex` at the same `percentile` of stature and
    of mass (as digital human models scale a "5th-percentile woman"), from the survey's
    mean and standard deviation taken as normal."""
    z = NormalDist().inv_cdf(percentile / 100.0)
    (height, height_sd), (mass, mass_sd) = SURVEY[sex]["stature"], SURVEY[sex]["mass"]
    return round(height + z * height_sd, 4), round(mass + z * mass_sd, 2)
