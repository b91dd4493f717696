"""The robot's motion: planning, execution, speed override, stopping data."""
