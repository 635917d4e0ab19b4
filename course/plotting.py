"""One look for every plot on the site, and text that stays readable where it is shown.

The pages show a figure at most SHOWN_PX wide (the text column at desktop width), and at
its own width when it is narrower, and beside it a sharp file for screens of 2 device
pixels to the CSS pixel (course/sharp.py). `save` sets every text of a plot at least large enough
to be MIN_TEXT_PX high there, whatever the figure's width, and records the smallest text
it drew, in pixels of the image, in the PNG (TEXT_KEY), where tests/site/browser measure
it at the width the page shows the picture.

A phone shows the column some 330 px wide, where a plot laid out for 736 px would have
its lettering at half its size. So `variants` draws a plot twice with the same code: as
the pages show it on wider screens, and for phones (course/phone.py), narrower, its
panels one above the other and its text at least PHONE.min_text_px high in a column
PHONE.shown_px wide, in two files, for screens of 2 and of 3 pixels to the CSS pixel.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import matplotlib
import numpy as np

from . import phone
from .phone import dense_path, phone_path
from .sharp import sharp_path, sharp_pixels

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


@dataclass(frozen=True)
class Layout:
    """Where a variant of a figure is shown: at most `shown_px` CSS pixels wide, with no
    text smaller than `min_text_px` there."""

    shown_px: float
    min_text_px: float


DESKTOP = Layout(SHOWN_PX, MIN_TEXT_PX)
PHONE = Layout(phone.SHOWN_PX, phone.MIN_TEXT_PX)
# The phone variant is laid out 5 in wide, and saved twice: for screens of 2 and of 3
# device pixels to the CSS pixel, PHONE_PIXELS wide, 2 and 3 times the column of a 390 px
# phone (358 px; a 360 px phone's, 328 px, takes the same files), the page offering both
# (_plugins/phone_figures.rb).
PHONE_WIDTH_IN = 5.0
PHONE_PIXELS = (720, 1080)
# A panel on the phone keeps its shape, a little taller (its lettering takes a larger
# share of it), and is never flatter or taller than these shares of the width.
PHONE_STRETCH = 1.15
PHONE_PANEL = (0.42, 0.75)


def figure(nrows: int = 1, ncols: int = 1, **kwargs):
    """A new figure and its axes, in the site's style."""
    with plt.rc_context(STYLE):
        return plt.subplots(nrows, ncols, layout="constrained", **kwargs)


def variants(path: str | Path, nrows: int = 1, ncols: int = 1, *, figsize: tuple[float, float],
             phone_figsize: tuple[float, float] | None = None,
             phone_grid: tuple[int, int] | None = None, **kwargs):
    """The figure at `path` and its phone variant, drawn by the same code:

        for fig, (ax, err), phone in variants(path, 1, 2, figsize=(12, 4.6)):
            ax.plot(...)            # drawn twice: data computed once, above the loop
            ax.legend(loc="lower right" if phone else "upper left")

    Each pass gives a new figure with axes shaped as `figure(nrows, ncols, ...)` gives
    them (same sharing, same gridspec_kw), and saves it when the loop body is done: first
    at `path` as the pages show it, then at `phone_path(path)` laid out for a phone, where
    the panels of each column go one above the other, the columns one after the other
    (`phone_grid` (rows, columns) places them row by row in another grid instead, a strip
    of pictures two by two, say), `PHONE_WIDTH_IN` wide (or `phone_figsize`)."""
    path = Path(path)
    fig, axes = figure(nrows, ncols, figsize=figsize, **kwargs)
    yield fig, axes, False
    save(fig, path, sharp=sharp_path(path))
    fig, axes = phone_figure(nrows, ncols, figsize=figsize, phone_figsize=phone_figsize,
                             phone_grid=phone_grid, **kwargs)
    yield fig, axes, True
    save(fig, phone_path(path), PHONE, dense=dense_path(path))


def phone_figure(nrows: int, ncols: int, *, figsize: tuple[float, float],
                 phone_figsize: tuple[float, float] | None = None,
                 phone_grid: tuple[int, int] | None = None, sharex=False, sharey=False,
                 gridspec_kw: dict | None = None, **kwargs):
    """The phone layout of `figure(nrows, ncols, figsize=figsize, ...)`: see `variants`.
    Returns the figure and its axes in the shape the desktop figure's have."""
    gridspec_kw = dict(gridspec_kw or {})
    widths = np.asarray(gridspec_kw.pop("width_ratios", [1.0] * ncols), dtype=float)
    heights = np.asarray(gridspec_kw.pop("height_ratios", [1.0] * nrows), dtype=float)
    cells = [(r, c) for c in range(ncols) for r in range(nrows)]   # column by column
    if phone_grid is None:
        grid = (nrows * ncols, 1)
        # each panel as tall, for the phone's width, as it is for its own column's width
        column_in = figsize[0] * widths / widths.sum()
        row_in = figsize[1] * heights / heights.sum()
        panel = [PHONE_STRETCH * row_in[r] * PHONE_WIDTH_IN / column_in[c] for r, c in cells]
        share = heights[[r for r, _ in cells]] / heights.max()   # a short row stays short
        panel = np.clip(panel, PHONE_WIDTH_IN * PHONE_PANEL[0] * share,
                        PHONE_WIDTH_IN * PHONE_PANEL[1] * share)
        ratios = {"height_ratios": list(panel)}
    else:
        grid = phone_grid
        cells = [(r, c) for r in range(nrows) for c in range(ncols)]   # row by row
        if grid[0] * grid[1] < len(cells):
            raise ValueError(f"phone_grid {grid} has fewer places than {nrows} × {ncols} axes")
        panel = [figsize[1] / nrows * PHONE_WIDTH_IN / figsize[0] * ncols / grid[1]] * grid[0]
        ratios = {}
    size = phone_figsize or (PHONE_WIDTH_IN, float(np.sum(panel)))
    with plt.rc_context(STYLE):
        fig = plt.figure(figsize=size, layout="constrained")
        placed = fig.subplots(*grid, squeeze=False, gridspec_kw={**gridspec_kw, **ratios}, **kwargs)
    flat = list(placed.flat)
    for extra in flat[len(cells):]:
        extra.remove()
    axes = np.empty((nrows, ncols), dtype=object)
    for (r, c), ax in zip(cells, flat):
        axes[r, c] = ax
    _share(axes, "x", sharex)
    _share(axes, "y", sharey)
    if nrows == 1 and ncols == 1:
        return fig, axes[0, 0]
    return fig, (axes.ravel() if nrows == 1 or ncols == 1 else axes)


def _share(axes: np.ndarray, which: str, how) -> None:
    """Share the x or y axis of the axes (in the desktop figure's shape) as plt.subplots
    would (`how`: True or "all", "row", "col")."""
    if how in (False, "none", None):
        return
    if how in (True, "all"):
        groups = [list(axes.flat)]
    elif how == "row":
        groups = [list(row) for row in axes]
    else:
        groups = [list(col) for col in axes.T]
    for group in groups:
        for ax in group[1:]:
            getattr(ax, f"share{which}")(group[0])
    if which == "x":   # as plt.subplots does: only the lowest panel of a column labels x
        shared = {ax for group in groups for ax in group}
        for r, c in np.ndindex(*axes.shape):
            if r + 1 < axes.shape[0] and axes[r, c] in shared and axes[r + 1, c] in shared:
                axes[r, c].tick_params(axis="x", labelbottom=False)


def save(fig, path: str | Path, layout: Layout = DESKTOP, dense: str | Path | None = None,
         sharp: str | Path | None = None) -> None:
    """Raise any text too small for where the figure is shown (`layout`), then save and
    close. The only metadata is the smallest text's size, so identical plots give
    identical files. With `dense` (a phone variant), the figure is saved PHONE_PIXELS[0]
    wide at `path` and PHONE_PIXELS[1] wide at `dense`; with `sharp`, also
    sharp_pixels(its width) wide at `sharp`, in 256 colours as the phone variants."""
    with plt.rc_context(STYLE):
        dpi = plt.rcParams["savefig.dpi"]
        width = fig.get_figwidth() * dpi
        # points for min_text_px on the page: the image is shown min(shown_px, width) wide
        # (a phone variant is wider than the column at any density: shown_px wide)
        least = layout.min_text_px * 72.0 / dpi * width / min(layout.shown_px, width)
        for ax in fig.axes:
            ax.tick_params(which="both", labelsize=max(least, _tick_size(ax)))
        fig.canvas.draw()
        for text in _texts(fig):
            if text.get_fontsize() < least:
                text.set_fontsize(least)
        fig.canvas.draw()
        points = min((t.get_fontsize() for t in _texts(fig)), default=0.0)
        if dense is None:   # (file, dpi, in 256 colours)
            files = [(path, dpi, False)]
            if sharp is not None:
                files.append((sharp, sharp_pixels(width) / fig.get_figwidth(), True))
        else:
            files = [(file, pixels / fig.get_figwidth(), True)
                     for file, pixels in zip((path, dense), PHONE_PIXELS)]
        for file, file_dpi, paletted in files:
            text = {TEXT_KEY: f"{points * file_dpi / 72.0:.2f}"}
            if paletted:
                _save_paletted(fig, file, file_dpi, text)
            else:
                fig.savefig(file, dpi=file_dpi, metadata={"Software": None, **text})
    plt.close(fig)


def _save_paletted(fig, path: str | Path, dpi: float, text: dict[str, str]) -> None:
    """Save the figure as a PNG of 256 colours (the phone variants: a phone downloads the
    sharper files in fewer bytes than the full-colour ones; the renders some plots show
    keep their shading but for faint steps in the sky), with `text` its only metadata."""
    from io import BytesIO

    from PIL import Image, PngImagePlugin
    buffer = BytesIO()
    fig.savefig(buffer, dpi=dpi, format="png")
    buffer.seek(0)
    with Image.open(buffer) as image:
        paletted = image.convert("RGB").quantize(256, method=Image.Quantize.FASTOCTREE)
    info = PngImagePlugin.PngInfo()
    for key, value in text.items():
        info.add_text(key, value)
    paletted.save(path, format="PNG", optimize=True, pnginfo=info)


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
