"""Vocabulary shared by every actor's command and status messages.

Commands flow down and carry a sequence number; every actor's status reports the last
sequence number it accepted and that command's outcome, so an asynchronous behavior tree
node knows when *its* command finished (DESIGN.md, "Data flow and timing").
"""

RUNNING = "running"
SUCCEEDED = "succeeded"
FAILED = "failed"
REJECTED = "rejected"
CANCELLED = "cancelled"

OUTCOMES = (RUNNING, SUCCEEDED, FAILED, REJECTED, CANCELLED)
FINISHED = (SUCCEEDED, FAILED, REJECTED, CANCELLED)
