"""Robot motion: messages, planning, time-parameterisation, speed-scaled execution, stopping data.

Everything here except `systems/robot_motion.py` is plain Python on top of pydrake, so it
can be tested and benchmarked without building the whole station.
"""
