"""One look for every plot on the site, and text that stays readable where it is shown.

The pages show a figure at most SHOWN_PX wide (the text column at desktop width), and at
its own width when it is narrower. `save` sets every text of a plot at least large enough
to be MIN_TEXT_PX high there, whatever the figure's width, and records the smallest text
it drew, in pixels of the image, in the PNG (TEXT_KEY), where tests/site/browser measure
it at the width the page shows the picture.
"""

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

SHOWN_PX = 736        # the widest a figure is shown: the text column at desktop width
MIN_TEXT_PX = 10.5    # the smallest text, in CSS pixels, at that width
TEXT_KEY = "sw2sim:smallest-text-px"   # PNG text chunk: the smallest text, image pixels


def figure(nrows: int = 1, ncols: int = 1, **kwargs):
    """A new figure and its axes, in the site's style."""
    with plt.rc_context(STYLE):
        return plt.subplots(nrows, ncols, layout="constrained", **kwargs)


def save(fig, path: str | Path) -> None:
    """Raise any text too small for where the figure is shown, then save and close. The
    only metadata is the smallest text's size, so identical plots give identical files."""
    with plt.rc_context(STYLE):
        dpi = plt.rcParams["savefig.dpi"]
        width = fig.get_figwidth() * dpi
        # points for MIN_TEXT_PX on the page: the image is shown min(SHOWN_PX, width) wide
        least = MIN_TEXT_PX * 72.0 / dpi * width / min(SHOWN_PX, width)
        for ax in fig.axes:
            ax.tick_params(which="both", labelsize=max(least, _tick_size(ax)))
        fig.canvas.draw()
        for text in _texts(fig):
            if text.get_fontsize() < least:
                text.set_fontsize(least)
        fig.canvas.draw()
        smallest = min((t.get_fontsize() for t in _texts(fig)), default=0.0) * dpi / 72.0
        fig.savefig(path, metadata={"Software": None, TEXT_KEY: f"{smallest:.2f}"})
    plt.close(fig)


def _tick_size(ax) -> float:
    labels = ax.get_xticklabels() + ax.get_yticklabels()
    return min((t.get_fontsize() for t in labels), default=0.0)


def _texts(fig):
    """The texts a reader sees: visible, not empty, in the figure."""
    from matplotlib.text import Text
    return [t for t in fig.findobj(Text) if t.get_visible() and t.get_text().strip()
            and t.get_figure() is not None and _on_figure(t, fig)]


def _on_figure(text, fig) -> bool:
    """Whether the text is drawn inside the figure (tick labels beyond the axis limits are
    kept but not drawn)."""
    box = text.get_window_extent(fig.canvas.get_renderer())
    return box.width > 0 and box.x1 > 0 and box.x0 < fig.bbox.width and \
        box.y1 > 0 and box.y0 < fig.bbox.height
