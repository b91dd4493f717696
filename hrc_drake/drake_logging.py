"""Drake's own log messages, kept out of what the project prints."""

import logging


def quiet_drake_logging() -> None:
    """Drake's INFO messages (e.g. "Allocating contexts to support implicit context
    parallelism") off in this process: the CLI and every sweep worker print only what we
    print. pydrake is imported first because it sets the "drake" logger's level on import."""
    import pydrake.common  # noqa: F401

    logging.getLogger("drake").setLevel(logging.WARNING)
