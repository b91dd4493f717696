"""Safety of the shared workcell: ISO/TS 15066 speed and separation monitoring (SSM) and
power and force limiting (PFL) math, the body-region limits, the monitor's config and
messages. The Drake system that applies them is `hrc_drake.systems.safety_monitor`.
"""
