"""`sw2sim plot` without ROS: rqt_plot's names, the checks of a name against its message
type (each error naming the problem and the fix), the values read from messages, the
course of a run against a stand-in source (waiting, time limit on ROS time, Ctrl-C), and
the PNG and CSV it writes."""

from __future__ import annotations

import csv
import os
import signal
import threading
import time
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest
from PIL import Image

from sw2sim import cli
from sw2sim.plot import fields, ros1, ros2
from sw2sim.plot import run as plot_run
from sw2sim.plot.drawing import save_png
from sw2sim.plot.fields import Part, PlotError, Slot
from sw2sim.plot.recording import Recording

N, B, T, M = "number", "bool", "text", "message"
TYPES = {
    "sensor_msgs/JointState": {"header": Slot("std_msgs/Header", M), "name": Slot("string", T, -1),
                               "position": Slot("float64", N, -1),
                               "velocity": Slot("float64", N, -1),
                               "effort": Slot("float64", N, -1)},
    "std_msgs/Header": {"seq": Slot("uint32", N), "stamp": Slot("time", M),
                        "frame_id": Slot("string", T)},
    "time": {"secs": Slot("int32", N), "nsecs": Slot("int32", N)},
    "control_msgs/JointControllerState": {"header": Slot("std_msgs/Header", M),
                                          "set_point": Slot("float64", N),
                                          "process_value": Slot("float64", N),
                                          "antiwindup": Slot("bool", B)},
    "geometry_msgs/Vector3": {"x": Slot("float64", N), "y": Slot("float64", N),
                              "z": Slot("float64", N)},
    "demo/Fixed": {"corners": Slot("float32", N, 3), "points": Slot("geometry_msgs/Vector3", M, -1)},
    "rosgraph_msgs/Clock": {"clock": Slot("time", M)},
}
TOPICS = {"/joint_states": "sensor_msgs/JointState", "/clock": "rosgraph_msgs/Clock",
          "/example_3/middle_arm_controller/state": "control_msgs/JointControllerState",
          "/example_3/joint_states": "sensor_msgs/JointState", "/fixed": "demo/Fixed"}
STATE = "/example_3/middle_arm_controller/state"


def planned(name: str) -> list[fields.Series]:
    topic, kind, rest = fields.split(name, TOPICS)
    return fields.plan(name, topic, kind, rest, TYPES.__getitem__)


# -- rqt_plot's names ------------------------------------------------------------------------

def test_names_expand_as_rqt_plot_reads_its_arguments():
    assert fields.expand(["/joint_states/velocity[0]"]) == ["/joint_states/velocity[0]"]
    # commas, and the `:` shorthand: later fields replace the first one's last part
    assert fields.expand([f"{STATE}/set_point:process_value", "/a/x,/b/y"]) == [
        f"{STATE}/set_point", f"{STATE}/process_value", "/a/x", "/b/y"]
    assert fields.expand(["/joint_states/position[0]:velocity[0]"]) == [
        "/joint_states/position[0]", "/joint_states/velocity[0]"]
    # a relative name is resolved in the namespace; a name given twice is plotted once
    assert fields.expand(["joint_states/effort[1]", "/x/y", "/x/y"], namespace="/") == [
        "/joint_states/effort[1]", "/x/y"]
    assert fields.expand(["state/error"], namespace="/robot") == ["/robot/state/error"]
    with pytest.raises(PlotError, match="needs a topic and a field before the first `:`"):
        fields.expand(["/clock:x"])
    with pytest.raises(PlotError, match="full name"):
        fields.expand(["~data"])


def test_a_name_splits_at_the_longest_published_topic():
    topics = {"/a": "t/A", "/a/b": "t/B"}
    assert fields.split("/a/b/c", topics) == ("/a/b", "t/B", "/c")
    assert fields.split("/a/c", topics) == ("/a", "t/A", "/c")
    assert fields.split("/joint_states", TOPICS) == ("/joint_states", "sensor_msgs/JointState", "")


def test_a_topic_that_is_not_published_is_named_with_the_closest_and_the_list():
    with pytest.raises(PlotError) as e:
        fields.split("/joint_state/velocity[0]", TOPICS)
    text = str(e.value)
    assert "/joint_state/velocity[0]: no topic of that name is published" in text
    assert "did you mean /joint_states?" in text or "did you mean /joint_states or" in text
    assert "Published now: /clock, /example_3/joint_states" in text
    with pytest.raises(PlotError, match="Nothing is published yet: start the simulation first"):
        fields.split("/joint_states/velocity[0]", {})


# -- checked against the type ----------------------------------------------------------------

def test_fields_arrays_and_nested_fields_give_one_series_each():
    (s,) = planned("/joint_states/velocity[0]")
    assert (s.topic, s.path) == ("/joint_states", (Part("velocity", 0),))
    (s,) = planned(f"{STATE}/set_point")
    assert s.topic == STATE and s.path == (Part("set_point"),)
    (s,) = planned("/joint_states/header/stamp/secs")
    assert [str(p) for p in s.path] == ["header", "stamp", "secs"]
    (s,) = planned("/fixed/points[2]/z")
    assert [str(p) for p in s.path] == ["points[2]", "z"]


def test_a_message_gives_its_numeric_fields_and_a_fixed_array_its_elements():
    assert [s.name for s in planned(STATE)] == [
        f"{STATE}/set_point", f"{STATE}/process_value", f"{STATE}/antiwindup"]
    assert [s.name for s in planned("/fixed/corners")] == [
        "/fixed/corners[0]", "/fixed/corners[1]", "/fixed/corners[2]"]


@pytest.mark.parametrize("name, said", [
    ("/joint_states/velocty[0]", "sensor_msgs/JointState has no field 'velocty' (did you mean "
                                 "velocity?). Its fields: header, name, position, velocity, effort"),
    ("/joint_states/velocity", "velocity is an array of float64 whose length the message sets; "
                               "give an index, e.g. /joint_states/velocity[0]"),
    ("/joint_states/name[0]", "name[0] is text (string), not a number"),
    ("/joint_states/header/frame_id", "frame_id is text (string), not a number"),
    (f"{STATE}/set_point[0]", "set_point is a single float64, not an array; leave out [0]"),
    ("/fixed/corners[3]", "corners holds 3 values: the index goes from 0 to 2"),
    ("/fixed/points/x", "points is an array; give an index, e.g. /fixed/points[0]"),
    ("/joint_states/velocity[0]/x", "velocity[0] is a float64, which has no field x"),
    ("/joint_states/velocity[a]", "`velocity[a]` is not a field"),
    ("/clock", "rosgraph_msgs/Clock has no numeric field of its own; name one of its fields: clock"),
])
def test_a_name_the_type_cannot_give_is_refused_with_the_fix(name, said):
    with pytest.raises(PlotError) as e:
        planned(name)
    assert str(e.value).startswith(f"{name}: ") and said in str(e.value)


def test_values_are_read_and_an_index_past_the_message_is_said():
    (s,) = planned("/joint_states/velocity[1]")
    message = SimpleNamespace(velocity=[0.5, -2.0])
    assert fields.value(message, s) == -2.0
    (s,) = planned("/joint_states/velocity[4]")
    with pytest.raises(PlotError, match=r"this message's velocity holds 2 values \(index 0 to 1\); "
                                        r"name an index below 2"):
        fields.value(message, s)
    (s,) = planned(f"{STATE}/antiwindup")
    assert fields.value(SimpleNamespace(antiwindup=True), s) == 1.0


@pytest.mark.parametrize("text, slot", [
    ("float64", Slot("float64", N)), ("float64[]", Slot("float64", N, -1)),
    ("uint8[4]", Slot("uint8", N, 4)), ("string", Slot("string", T)),
    ("bool[]", Slot("bool", B, -1)), ("Header", Slot("std_msgs/Header", M)),
    ("geometry_msgs/Vector3[]", Slot("geometry_msgs/Vector3", M, -1)), ("time", Slot("time", M)),
])
def test_ros1_slot_types(text, slot):
    assert ros1.slot(text) == slot


@pytest.mark.parametrize("text, slot", [
    ("double", Slot("double", N)), ("sequence<double>", Slot("double", N, -1)),
    ("sequence<double, 5>", Slot("double", N, -1)), ("float[3]", Slot("float", N, 3)),
    ("boolean", Slot("boolean", B)), ("string", Slot("string", T)),
    ("string<8>", Slot("string<8>", T)), ("sequence<string>", Slot("string", T, -1)),
    ("builtin_interfaces/Time", Slot("builtin_interfaces/Time", M)),
    ("sequence<geometry_msgs/Pose>", Slot("geometry_msgs/Pose", M, -1)),
])
def test_ros2_field_types(text, slot):
    assert ros2.slot(text) == slot


# -- a run, against a source that stands in for ROS ------------------------------------------

class FakeSource:
    """Publishes /joint_states at 50 Hz of its simulated time, 10 times faster than the wall
    clock, its stamps from `start`; topics appear after `appear` s of wall time."""

    name = "ROS 1"

    def __init__(self, start=100.0, appear=0.0, sizes=2, ahead=0.0):
        self.t, self.start, self.sizes, self.ahead = start, start, sizes, ahead
        self.born = time.monotonic() + appear
        self.stop = threading.Event()
        self.closed = False

    def topics(self):
        return dict(TOPICS) if time.monotonic() >= self.born else {"/rosout": "rosgraph_msgs/Log"}

    def describe(self, kind):
        return TYPES[kind]

    def subscribe(self, topic, kind, on_message):
        def publish():
            while not self.stop.is_set():
                self.t += 0.02
                stamp = SimpleNamespace(secs=int(self.t), nsecs=0)
                on_message(SimpleNamespace(header=SimpleNamespace(stamp=stamp), t=self.t,
                                           position=[np.sin(self.t)] * self.sizes,
                                           velocity=[self.t - self.start] * self.sizes))
                time.sleep(0.002)
        threading.Thread(target=publish, daemon=True).start()

    def stamp(self, message):
        return message.t

    def now(self):
        return self.t + self.ahead

    def uses_sim_time(self):
        return True

    def close(self):
        self.stop.set()
        self.closed = True


def fake_ros(source):
    return SimpleNamespace(NAME="ROS 1", Source=lambda: source)


def test_a_run_plots_for_its_duration_of_ros_time_and_writes_png_and_csv(tmp_path, monkeypatch):
    source = FakeSource(appear=0.3)
    monkeypatch.setattr(plot_run, "choose", lambda ros, say: fake_ros(source))
    said = []
    png, table = tmp_path / "v.png", tmp_path / "v.csv"
    status = plot_run.run(plot_run.Options(["/joint_states/velocity[0]:position[1]"],
                                           output=png, csv=table, duration=1.0), say=said.append)
    assert status == 0 and source.closed, said
    assert said[0] == "sw2sim plot: waiting for /joint_states/velocity[0], " \
                      "/joint_states/position[1] to be published (ROS 1) ..."
    assert "2 series from /joint_states (ROS 1); waiting for the first message ..." in said[1]
    assert said[2] == "sw2sim plot: plotting for 1 s of simulated time; Ctrl-C ends it"
    rows = list(csv.DictReader(table.open()))
    speeds = [r for r in rows if r["series"] == "/joint_states/velocity[0]"]
    times = np.array([float(r["time"]) for r in speeds])
    # the plot's time is the source's, from the first sample, cut at the duration
    assert times[0] == 0 and 0.9 < times[-1] <= 1.0 + 1e-9
    assert np.allclose(np.diff(times), 0.02)
    first = float(speeds[0]["ros_time"])
    assert all(float(r["value"]) == pytest.approx(float(r["ros_time"]) - 100.0)
               for r in speeds) and first > 100.0
    assert {r["series"] for r in rows} == {"/joint_states/velocity[0]", "/joint_states/position[1]"}
    assert f"wrote {png} ({len(rows)} samples over" in said[-2]
    assert Image.open(png).size == (800, 450)


def test_the_duration_is_that_of_the_samples_when_the_clock_runs_ahead_of_them(tmp_path,
                                                                             monkeypatch):
    """Under a simulation far faster than real time the messages lag behind /clock: the
    plot still holds the duration's worth of them."""
    source = FakeSource(ahead=30.0)
    monkeypatch.setattr(plot_run, "choose", lambda ros, say: fake_ros(source))
    table = tmp_path / "v.csv"
    assert plot_run.run(plot_run.Options(["/joint_states/velocity[0]"], output=tmp_path / "v.png",
                                         csv=table, duration=1.0), say=print) == 0
    times = [float(r["time"]) for r in csv.DictReader(table.open())]
    assert 0.9 < max(times) <= 1.0 + 1e-9


def test_an_index_past_the_message_ends_the_run_with_the_fix(tmp_path, monkeypatch):
    source = FakeSource(sizes=2)
    monkeypatch.setattr(plot_run, "choose", lambda ros, say: fake_ros(source))
    said = []
    status = plot_run.run(plot_run.Options(["/joint_states/velocity[2]"], output=tmp_path / "x.png",
                                           duration=5.0), say=said.append)
    assert status == 2 and source.closed
    assert any("this message's velocity holds 2 values (index 0 to 1)" in s for s in said), said
    assert not (tmp_path / "x.png").exists()


def test_an_unpublished_topic_is_said_after_waiting(monkeypatch):
    source = FakeSource(appear=60)
    monkeypatch.setattr(plot_run, "choose", lambda ros, say: fake_ros(source))
    monkeypatch.setattr(plot_run, "TOPIC_WAIT", 0.3)
    said = []
    assert plot_run.run(plot_run.Options(["/joint_states/velocity[0]"], output=Path("x.png")),
                        say=said.append) == 2
    assert "no topic of that name is published" in said[-1] and "/rosout" in said[-1]


def test_ctrl_c_ends_the_run_and_still_writes_the_png(tmp_path, monkeypatch):
    source = FakeSource()
    monkeypatch.setattr(plot_run, "choose", lambda ros, say: fake_ros(source))
    said = []
    # (a Ctrl-C that came after the run ended must not end the test session)
    before = signal.signal(signal.SIGINT, lambda signum, frame: None)
    timer = threading.Timer(0.5, os.kill, (os.getpid(), signal.SIGINT))
    try:
        timer.start()
        status = plot_run.run(plot_run.Options(["/joint_states/position[0]"],
                                               output=tmp_path / "p.png"), say=said.append)
    finally:
        timer.join()
        signal.signal(signal.SIGINT, before)
    assert status == 0 and source.closed
    assert (tmp_path / "p.png").is_file() and f"wrote {tmp_path / 'p.png'}" in said[-1]


def test_without_a_display_the_png_is_named_after_the_plot(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    source = FakeSource()
    monkeypatch.setattr(plot_run, "choose", lambda ros, say: fake_ros(source))
    said = []
    assert plot_run.run(plot_run.Options(["/joint_states/velocity[0]"], duration=0.5,
                                         live=False), say=said.append) == 0
    assert said[0] == ("sw2sim plot: no display: the plot goes to "
                       "plot_joint_states_velocity_0.png when it ends")
    assert (tmp_path / "plot_joint_states_velocity_0.png").is_file()


# -- the picture -----------------------------------------------------------------------------

def test_the_png_draws_each_series_where_its_values_are(tmp_path):
    low, high = fields.Series("/a/low", "/a", "t", ()), fields.Series("/b/high", "/b", "t", ())
    recording = Recording([low, high])
    for k in range(201):
        recording.add("/a/low", 10 + k * 0.05, -1.0)
        recording.add("/b/high", 10 + k * 0.05, 1.0)
    whole, last = tmp_path / "whole.png", tmp_path / "last.png"
    save_png(recording, whole, None, "time (s)")
    pixels = np.asarray(Image.open(whole).convert("RGB")).astype(int)
    # matplotlib's first two colours, C0 (31, 119, 180) and C1 (255, 127, 14)
    blue = np.all(np.abs(pixels - (31, 119, 180)) < 40, axis=2)
    orange = np.all(np.abs(pixels - (255, 127, 14)) < 40, axis=2)
    rows_blue, cols_blue = np.nonzero(blue)
    rows_orange, cols_orange = np.nonzero(orange)
    # the low series is drawn below the high one, each across the axes' width
    assert np.median(rows_blue) > np.median(rows_orange) + 100
    assert np.ptp(cols_blue) > 500 and np.ptp(cols_orange) > 500
    # --window 2: the last 2 of the 10 seconds
    from sw2sim.plot.drawing import _limits
    assert _limits([[0.0, 10.0]], 2.0) == (8.0, 10.0)
    assert _limits([[0.0, 1.0]], 2.0) == (0.0, 2.0)   # the window's width before it fills
    save_png(recording, last, 2.0, "time (s)")
    assert last.is_file()


def test_the_command_line_refuses_what_it_cannot_write(tmp_path, capsys):
    assert cli.main(["plot", "/joint_states/velocity[0]", "-o", str(tmp_path / "x.jpg")]) == 2
    assert "give a file ending in .png" in capsys.readouterr().err
    assert cli.main(["plot", "/joint_states/velocity[0]", "-o",
                     str(tmp_path / "missing" / "x.png")]) == 2
    assert "does not exist; create it first" in capsys.readouterr().err
    with pytest.raises(SystemExit):
        cli.main(["plot", "/x", "--duration", "0"])
    assert "give a time above 0" in capsys.readouterr().err


def test_with_no_ros_it_names_what_is_missing(monkeypatch, capsys):
    monkeypatch.setattr(ros1, "problem", lambda: "no ROS 1 master answers at X")
    monkeypatch.setattr(ros2, "problem", lambda: "rclpy is not installed")
    assert cli.main(["plot", "/joint_states/velocity[0]", "-o", "x.png"]) == 2
    err = capsys.readouterr().err
    assert "no ROS to plot from. ROS 1: no ROS 1 master answers at X. ROS 2: rclpy is not " \
           "installed." in err
    assert cli.main(["plot", "/x/y", "--ros", "2", "-o", "x.png"]) == 2
    assert "--ros 2: rclpy is not installed" in capsys.readouterr().err
