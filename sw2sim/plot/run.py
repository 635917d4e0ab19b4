"""The course of one `sw2sim plot`: choose the ROS, wait for the topics, check the names
against their types, subscribe, record until the time is up, Ctrl-C or the window closes,
then write the PNG (and the CSV).

Which ROS: `ros` "1" or "2", else ROS 1 where rospy imports and a master answers at
ROS_MASTER_URI, else ROS 2 where rclpy imports. The time limit counts ROS time from the
first sample: simulated seconds under /clock, the seconds the plot's axis shows, however
fast the simulation runs against the wall clock.
"""

from __future__ import annotations

import re
import signal
import threading
import time
from dataclasses import dataclass
from pathlib import Path

from . import fields
from .fields import PlotError
from .recording import Recording

EXIT_OK, EXIT_UNUSABLE = 0, 2
TOPIC_WAIT = 10.0   # s of wall time for the named topics to be published
TICK = 0.05         # s between looks when no window is open
QUIET = 0.5         # s of wall time without a sample: the topics have gone quiet


@dataclass
class Options:
    names: list[str]
    ros: str | None = None          # "1", "2" or None: whichever runs
    output: Path | None = None      # the PNG; None: a window, or a PNG named after the plot
    live: bool = False              # a window (when there is a display and no output)
    csv: Path | None = None
    duration: float | None = None   # s of ROS time from the first sample
    window: float | None = None     # s shown: the last `window` seconds


def choose(ros: str | None, say) -> object | None:
    """The ROS module to use (sw2sim.plot.ros1 or .ros2), or None after saying why not."""
    from . import ros1, ros2
    if ros == "1":
        why = ros1.problem()
        return ros1 if why is None else say(f"sw2sim plot: --ros 1: {why}")
    if ros == "2":
        why = ros2.problem()
        return ros2 if why is None else say(f"sw2sim plot: --ros 2: {why}")
    one, two = ros1.problem(), ros2.problem()
    if one is None:
        return ros1
    if two is None:
        return ros2
    say(f"sw2sim plot: no ROS to plot from. ROS 1: {one.rstrip('.')}. ROS 2: {two.rstrip('.')}.")
    return None


def default_png(names: list[str]) -> Path:
    """plot_joint_states_velocity_0.png for /joint_states/velocity[0] (the first name)."""
    stem = re.sub(r"[^A-Za-z0-9]+", "_", names[0]).strip("_")[:80] or "topic"
    return Path(f"plot_{stem}.png")


def run(options: Options, say=print) -> int:
    try:
        names = fields.expand(options.names)
    except PlotError as exc:
        say(f"sw2sim plot: {exc}")
        return EXIT_UNUSABLE
    output = options.output
    for path, what in ((output, "PNG"), (options.csv, "CSV")):
        if path is not None and not path.parent.is_dir():
            say(f"sw2sim plot: the folder {path.parent} for the {what} does not exist; "
                "create it first")
            return EXIT_UNUSABLE
    ros = choose(options.ros, say)
    if ros is None:
        return EXIT_UNUSABLE
    if ros.NAME == "ROS 2":
        ros.prepare()   # (which may start the process again)
    live = output is None and options.live
    if output is None and not live:
        output = default_png(names)
        say(f"sw2sim plot: no display: the plot goes to {output} when it ends")
    if not live:
        # matplotlib takes a second or more to import: while the topics are awaited, not
        # after Ctrl-C, when the reader (or a terminal closing) waits for the PNG. (A live
        # window imports it at once, in this thread.)
        threading.Thread(target=_import_drawing, daemon=True).start()
    stop = {"signal": None}

    def ctrl_c(signum, frame):
        stop["signal"] = signum

    previous = {sig: signal.signal(sig, ctrl_c) for sig in (signal.SIGINT, signal.SIGTERM)}
    source = recording = None
    try:
        source = ros.Source()
        recording = _subscribed(source, names, stop, say)
        if recording is None:
            return EXIT_UNUSABLE if stop["signal"] is None else EXIT_OK
        return _record(source, recording, options, live, stop, say)
    except PlotError as exc:
        say(f"sw2sim plot: {exc}")
        return EXIT_UNUSABLE
    finally:
        label = _xlabel(source) if source is not None else ""
        if source is not None:
            source.close()
        for sig, handler in previous.items():
            signal.signal(sig, handler)
        if recording is not None and options.duration is not None:
            recording.cut(options.duration)
        if recording is not None and recording.count():
            _write(recording, output, options.csv, options.window, label, say)


def _import_drawing() -> None:
    from . import drawing  # noqa: F401
    from matplotlib.backends import backend_agg  # noqa: F401
    from matplotlib import figure  # noqa: F401


def _subscribed(source, names, stop, say) -> Recording | None:
    """Wait for the topics (TOPIC_WAIT s), check every name and subscribe: the recording,
    or None after saying what is missing (or on Ctrl-C)."""
    deadline, said, topics = time.monotonic() + TOPIC_WAIT, False, {}
    while stop["signal"] is None:
        topics = source.topics()
        absent = [n for n in names if not any(n == t or n.startswith(t.rstrip("/") + "/")
                                              for t in topics)]
        if not absent:
            break
        if time.monotonic() > deadline:
            for name in absent:
                say(f"sw2sim plot: {fields.unpublished(name, topics)}")
            return None
        if not said:
            say(f"sw2sim plot: waiting for {', '.join(absent)} to be published ({source.name}) ...")
            said = True
        time.sleep(0.2)
    if stop["signal"] is not None:
        return None
    series, types = [], {}
    for name in names:
        topic, kind, rest = fields.split(name, topics)
        types[topic] = kind
        series += [s for s in fields.plan(name, topic, kind, rest, source.describe)
                   if s.name not in {x.name for x in series}]
    recording = Recording(series)
    for topic, kind in types.items():
        mine = [s for s in series if s.topic == topic]
        source.subscribe(topic, kind, _callback(source, recording, mine))
    return recording


def _callback(source, recording: Recording, series):
    def on_message(message) -> None:
        t = source.stamp(message)
        if t is None:
            t = source.now()
            if t == 0.0 and source.uses_sim_time():
                return   # no /clock message yet: the time is not known
        for s in series:
            try:
                recording.add(s.name, t, fields.value(message, s))
            except PlotError as exc:
                recording.fail(exc)
    return on_message


def _record(source, recording: Recording, options: Options, live: bool, stop, say) -> int:
    topics = sorted({s.topic for s in recording.series})
    say(f"sw2sim plot: {len(recording.series)} series from {', '.join(topics)} "
        f"({source.name}); waiting for the first message ...")
    window = None
    if live:
        from .drawing import LiveWindow
        try:
            window = LiveWindow(recording, options.window, _xlabel(source),
                                "sw2sim plot: " + " ".join(topics))
        except RuntimeError as exc:
            say(f"sw2sim plot: {exc}")
            return EXIT_UNUSABLE
    announced = False
    while stop["signal"] is None:
        if recording.error is not None:
            say(f"sw2sim plot: {recording.error}")
            return EXIT_UNUSABLE
        if recording.first is not None and not announced:
            announced = True
            say("sw2sim plot: plotting" + (f" for {options.duration:g} s of "
                                           f"{'simulated' if source.uses_sim_time() else 'ROS'} "
                                           "time" if options.duration else "")
                + "; Ctrl-C ends it" + (" (or close the window)" if window else ""))
        if options.duration is not None and _done(source, recording, options.duration):
            break
        if window is not None:
            window.update()
            if window.closed:
                break
        else:
            time.sleep(TICK)
    if window is not None:
        window.close()
    if recording.first is None:
        say("sw2sim plot: no message came; nothing to draw")
    return EXIT_OK


def _done(source, recording: Recording, duration: float) -> bool:
    """The samples span `duration`; or the ROS clock has passed it and no sample came for
    QUIET s (the topics went quiet). (The clock alone would end it early where the
    messages lag behind it: a simulation running far faster than real time.)"""
    if recording.first is None:
        return False
    if recording.span() >= duration:
        return True
    return (source.now() >= recording.first + duration
            and time.monotonic() - recording.arrived > QUIET)


def _xlabel(source) -> str:
    clock = "simulated time" if source.uses_sim_time() else "ROS time"
    return f"{clock} since the first sample (s)"


def _write(recording: Recording, output: Path | None, csv: Path | None, window: float | None,
           label: str, say) -> None:
    from .drawing import save_png
    span, count = recording.span(), recording.count()
    if output is not None:
        try:
            save_png(recording, output, window, label)
            say(f"sw2sim plot: wrote {output} ({count} samples over {span:.2f} s)")
        except OSError as exc:
            say(f"sw2sim plot: cannot write {output}: {exc.strerror or exc}")
    if csv is not None:
        try:
            recording.write_csv(csv)
            say(f"sw2sim plot: wrote {csv} ({count} rows)")
        except OSError as exc:
            say(f"sw2sim plot: cannot write {csv}: {exc.strerror or exc}")
