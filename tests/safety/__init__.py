"""The safety monitor, closed-loop: a person walks in, the robot slows and stops."""
