"""Falsification: search the person's behaviour for the run with the smallest safety margin
(`hrc-drake falsify`; the search space is the scenario's `falsify:` section)."""

from hrc_drake.falsify.search import FalsifyResult, Search, Trial, falsify, prepare, ranked

__all__ = ["FalsifyResult", "Search", "Trial", "falsify", "prepare", "ranked"]
