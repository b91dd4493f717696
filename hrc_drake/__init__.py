"""hrc_drake: simulate and evaluate human-robot collaboration with Drake."""

__version__ = "0.1.0"
