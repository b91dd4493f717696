"""Shared matplotlib setup: a non-interactive backend and one way to save figures."""

from pathlib import Path

import matplotlib

matplotlib.use("Agg")

DPI = 110


def save_figure(fig, path: Path) -> Path:
    """Writes the figure and frees it (figures are many in a sweep)."""
    import matplotlib.pyplot as plt

    if fig.get_layout_engine() is None:
        fig.tight_layout()
    fig.savefig(path, dpi=DPI, metadata={"Software": None})
    plt.close(fig)
    return path
