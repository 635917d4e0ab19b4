"""One look for every plot on the site."""

from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

STYLE = {
    "figure.figsize": (8.0, 4.2),
    "figure.dpi": 100,
    "savefig.dpi": 130,
    "axes.grid": True,
    "grid.alpha": 0.3,
    "axes.spines.top": False,
    "axes.spines.right": False,
    "font.size": 11,
    "legend.frameon": False,
    "svg.hashsalt": "sw2sim",
}


def figure(nrows: int = 1, ncols: int = 1, **kwargs):
    """A new figure and its axes, in the site's style."""
    with plt.rc_context(STYLE):
        return plt.subplots(nrows, ncols, layout="constrained", **kwargs)


def save(fig, path: str | Path) -> None:
    """Save and close; no metadata, so identical plots give identical files."""
    with plt.rc_context(STYLE):
        fig.savefig(path, metadata={"Software": None})
    plt.close(fig)
