"""The picture of a recording, with matplotlib (imported here only, when a plot is drawn):
a PNG drawn off-screen, or a live window that scrolls as rqt_plot's does.

rqt_plot shows the last 10 s and moves on with the newest sample (plot.py sets the x
range to 0-10 s: https://github.com/ros-visualization/rqt_plot/blob/0.4.14/src/rqt_plot/plot.py#L62;
data_plot's autoscroll keeps the width); its y range grows to take in what it shows.
"""

from __future__ import annotations

from pathlib import Path

from .recording import Recording

LIVE_WINDOW = 10.0   # s shown in a live window, as rqt_plot
SIZE = (8.0, 4.5)    # inches, at DPI
DPI = 100
NOT_INTERACTIVE = {"agg", "cairo", "pdf", "pgf", "ps", "svg", "template"}


def _limits(times: list[list[float]], window: float | None) -> tuple[float, float]:
    last = max((t[-1] for t in times if t), default=0.0)
    if window is None:
        return 0.0, max(last, 1e-3)
    return max(0.0, last - window), max(window, last)


def _layout(axes, recording: Recording, xlabel: str):
    lines = {}
    for series in recording.series:
        lines[series.name], = axes.plot([], [], label=series.name, linewidth=1.2)
    axes.set_xlabel(xlabel)
    axes.grid(True, alpha=0.3)
    axes.legend(loc="upper left", fontsize="small")
    return lines


def _fill(axes, lines, recording: Recording, window: float | None) -> None:
    data = recording.since_start()
    for name, (t, v) in data.items():
        lines[name].set_data(t, v)
    left, right = _limits([t for t, _ in data.values()], window)
    axes.set_xlim(left, right)
    shown = [v for t, vs in data.values() for x, v in zip(t, vs) if left <= x <= right]
    if shown:
        low, high = min(shown), max(shown)
        pad = 0.05 * (high - low) or max(abs(high) * 0.05, 0.05)
        axes.set_ylim(low - pad, high + pad)


def save_png(recording: Recording, path: Path, window: float | None, xlabel: str) -> None:
    """The recording (its last `window` seconds, or all of it) as a PNG."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure
    figure = Figure(figsize=SIZE, dpi=DPI, layout="tight")
    FigureCanvasAgg(figure)
    axes = figure.add_subplot()
    lines = _layout(axes, recording, xlabel)
    _fill(axes, lines, recording, window)
    figure.savefig(path, dpi=DPI)


class LiveWindow:
    """A matplotlib window redrawn with `update()`; `closed` once the user closes it."""

    def __init__(self, recording: Recording, window: float | None, xlabel: str, title: str):
        import matplotlib.pyplot as plt
        backend = plt.get_backend().lower()
        if backend in NOT_INTERACTIVE or backend.endswith("inline"):
            raise RuntimeError(f"matplotlib has no window toolkit here (backend {backend}): "
                               "install python3-tk (Debian) or PyQt, or give -o FILE.png")
        self.plt, self.recording = plt, recording
        self.window = LIVE_WINDOW if window is None else window
        self.figure = plt.figure(figsize=SIZE, dpi=DPI, layout="tight")
        self.figure.canvas.manager.set_window_title(title)
        self.axes = self.figure.add_subplot()
        self.lines = _layout(self.axes, recording, xlabel)
        self.closed = False
        self.figure.canvas.mpl_connect("close_event", self._on_close)
        plt.show(block=False)

    def _on_close(self, event) -> None:
        self.closed = True

    def update(self, pause: float = 0.05) -> None:
        """Redraw with the newest samples, and let the window handle its events for
        `pause` seconds."""
        if self.closed:
            return
        _fill(self.axes, self.lines, self.recording, self.window)
        self.figure.canvas.draw_idle()
        self.plt.pause(pause)

    def close(self) -> None:
        if not self.closed:
            self.closed = True
            self.plt.close(self.figure)
