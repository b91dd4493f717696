"""Robot motion: messages, planning, time-parameterisation, speed-scaled execution, and the
state machine that RobotMotion (`systems/robot_motion.py`) runs at each update.

Everything here is plain Python on top of pydrake, with no Drake systems, so it can be
tested and benchmarked without building the whole station.
"""
