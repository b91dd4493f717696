"""The scenario's `ergonomics:` section: how often the person's posture is sampled for
the scores, and what the run cannot show of the job (how long a shift does this work, how
well hands hold an object whose type does not say)."""

from dataclasses import dataclass


@dataclass
class ErgonomicsOptions:
    period: float = 0.1
    """s between the samples of the person's joint positions the scores are taken from"""
    work_hours: float = 8.0
    """hours a day the person does this work: the lifting equation's duration (up to 1 h
    short, up to 2 h moderate, longer long)"""
    coupling: str = "fair"
    """NIOSH coupling (good, fair, poor) of objects whose type has no `coupling` attribute:
    fair fits a box without handles that the fingers can grip under (the manual's Table 6)"""
