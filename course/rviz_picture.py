"""RViz's view of an example package: its own launch/display.launch, run unchanged on a
virtual screen (Xvfb), and the 3D view cut out of a picture of that screen.

Debian 12 ships rviz and joint_state_publisher, and joint_state_publisher_gui 1.15.1,
which stops as it opens (`TypeError: setValue(self, a0: int): argument 1 has unexpected
type 'float'`: its sliders are given floats, which the PyQt5 of Debian 12 refuses).
`sw2sim ros` stands in for it with a window of sliders (sw2sim/ros/sliders.py), but here a
window would lie over the screen the picture is cut from. So a package of that name goes
ahead of any other, whose node is Debian's joint_state_publisher: the same /joint_states,
every joint at zero, without a window.

Everything started here runs in process groups of its own and is stopped when the picture
is taken or anything fails.
"""

from __future__ import annotations

import os
import random
import select
import shutil
import socket
import subprocess
import tempfile
import time
import xmlrpc.client
from contextlib import ExitStack, contextmanager
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from sw2sim.ros.run import stop

from . import ROOT
from .rviz_config import BACKGROUND, WINDOW

# Programs the picture needs, with the Debian packages that have them.
PROGRAMS = {"roscore": "python3-roslaunch", "roslaunch": "python3-roslaunch", "rviz": "rviz",
            "Xvfb": "xvfb"}
JOINT_STATE_PUBLISHER = Path("/usr/lib/joint_state_publisher/joint_state_publisher")
SCREEN = (WINDOW["Width"], WINDOW["Height"])
START_TIMEOUT = 15.0     # s for Xvfb to open its display and roscore to answer
ROBOT_TIMEOUT = 40.0     # s for the robot to show (several figures may be made at once)
SETTLED = 3              # grabs in a row with the same 3D view


def missing() -> str | None:
    """Why RViz's picture cannot be taken here, or None when it can."""
    from PIL import features
    if not features.check("xcb"):
        return "this Pillow cannot read an X screen (built without XCB)"
    absent = [deb for program, deb in PROGRAMS.items() if not shutil.which(program)]
    if not JOINT_STATE_PUBLISHER.is_file():
        absent.append("joint-state-publisher")
    if not absent:
        return None
    return (f"not installed: {', '.join(dict.fromkeys(absent))} (`make setup` installs them "
            "where Debian ships ROS 1)")


@dataclass
class Screen:
    display: str                  # ":N"
    process: subprocess.Popen     # Xvfb


def _start_xvfb(number: int, size: tuple[int, int]) -> tuple[subprocess.Popen, int] | None:
    """Xvfb on display `number` once it answers, and the pipe it told so on (to be kept
    open while it runs: Xvfb writes to it again, and a closed pipe stops it); None if it
    cannot have that display. -noreset: it goes on as it is when its last client leaves."""
    read, write = os.pipe()
    process = subprocess.Popen(
        ["Xvfb", f":{number}", "-displayfd", str(write), "-noreset", "-screen", "0",
         f"{size[0]}x{size[1]}x24", "-nolisten", "tcp"], pass_fds=(write,),
        stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
        start_new_session=True)
    os.close(write)
    # Xvfb writes the display's number once it listens, and closes the pipe when it gives
    # up (another server has that display).
    ready = select.select([read], [], [], START_TIMEOUT)[0] and os.read(read, 16).strip()
    if ready == str(number).encode():
        return process, read
    os.close(read)
    stop(process)
    return None


@contextmanager
def xvfb(size: tuple[int, int] = SCREEN):
    """A virtual screen, stopped (its process group) at the end, also on an error.

    Its display number is drawn at random from a range other X servers seldom use, not
    the first free one (Xvfb's own choice): two screens started at once then do not reach
    for the same number, and none is started over one being stopped."""
    rng = random.Random()
    for number in rng.sample(range(200, 5000), 20):
        if Path(f"/tmp/.X{number}-lock").exists():
            continue
        started = _start_xvfb(number, size)
        if started is not None:
            break
    else:
        raise RuntimeError("Xvfb did not start on any of 20 display numbers")
    process, pipe = started
    try:
        yield Screen(f":{number}", process)
    finally:
        stop(process)
        os.close(pipe)


def joint_state_publisher_gui(prefix: Path) -> Path:
    """A catkin prefix holding the package joint_state_publisher_gui, whose node is Debian's
    joint_state_publisher. With `prefix` first on CMAKE_PREFIX_PATH (roslaunch looks for a
    node's program there before Debian's /usr) and `prefix`/share on ROS_PACKAGE_PATH, it
    stands in for Debian's GUI, installed or not."""
    share = prefix / "share" / "joint_state_publisher_gui"
    node = prefix / "lib" / "joint_state_publisher_gui" / "joint_state_publisher_gui"
    share.mkdir(parents=True, exist_ok=True)
    node.parent.mkdir(parents=True, exist_ok=True)
    (prefix / ".catkin").write_text("")
    (share / "package.xml").write_text(
        '<?xml version="1.0"?>\n<package format="2">\n  <name>joint_state_publisher_gui</name>\n'
        "  <version>1.15.1</version>\n  <description>joint_state_publisher without its sliders"
        "</description>\n  <maintainer email=\"none@example.org\">none</maintainer>\n"
        "  <license>BSD</license>\n  <exec_depend>joint_state_publisher</exec_depend>\n"
        "</package>\n")
    node.write_text(f'#!/bin/sh\nexec {JOINT_STATE_PUBLISHER} "$@"\n')
    node.chmod(0o755)
    return prefix


def environment(env: dict[str, str], package: Path, display: str, prefix: Path,
                home: Path) -> dict[str, str]:
    """`env` (a ROS master's) with what display.launch needs here: the screen, the package
    and the stand-in on the paths, and a home of its own for RViz's settings."""
    runtime = home / "runtime"
    runtime.mkdir(parents=True, exist_ok=True)
    runtime.chmod(0o700)
    return {**env, "DISPLAY": display, "HOME": str(home), "XDG_RUNTIME_DIR": str(runtime),
            "ROS_PACKAGE_PATH": os.pathsep.join([str(package.parent), str(prefix / "share"),
                                                 "/usr/share"]),
            "CMAKE_PREFIX_PATH": str(prefix),
            # Debian's nodes start with /usr/bin/env python3: theirs, with rospy
            "PATH": os.pathsep.join(["/usr/bin", env.get("PATH", "")])}


def grab(display: str) -> np.ndarray:
    """The whole screen, (height, width, 3) uint8."""
    from PIL import ImageGrab
    return np.asarray(ImageGrab.grab(xdisplay=display).convert("RGB"))


def view_box(screen: np.ndarray) -> tuple[int, int, int, int] | None:
    """(top, bottom, left, right) of RViz's 3D view: the rows and columns mostly of its
    background colour. None while there is none."""
    background = np.all(screen == BACKGROUND, axis=2)
    rows = np.flatnonzero(background.mean(axis=1) > 0.3)
    cols = np.flatnonzero(background.mean(axis=0) > 0.3)
    if len(rows) < 50 or len(cols) < 50:
        return None
    return int(rows[0]), int(rows[-1]) + 1, int(cols[0]), int(cols[-1]) + 1


def robot_pixels(view: np.ndarray, reach: int = 2) -> np.ndarray:
    """Where the 3D view shows the robot: pixels not of the background whose neighbours
    up to `reach` pixels away are not either. The grid's lines are one pixel wide, so
    none of their pixels is; the robot's faces, whatever their colour, are."""
    drawn = np.abs(view.astype(int) - BACKGROUND).max(axis=2) > 6
    solid = drawn.copy()
    height, width = drawn.shape
    for dy in range(-reach, reach + 1):
        for dx in range(-reach, reach + 1):
            shifted = np.zeros_like(drawn)
            shifted[max(dy, 0):height + min(dy, 0), max(dx, 0):width + min(dx, 0)] = \
                drawn[max(-dy, 0):height + min(-dy, 0), max(-dx, 0):width + min(-dx, 0)]
            solid &= shifted
    return solid


def unplaced_pixels(view: np.ndarray) -> np.ndarray:
    """Where the 3D view shows RViz's error material: a link RViz has no transform for
    (nothing publishes its joint's state) is drawn white, at the fixed frame's origin."""
    pixels = view.astype(int)
    return (pixels.min(axis=2) > 200) & (pixels.max(axis=2) - pixels.min(axis=2) < 16)


def wait_for_robot(display: str, alive, timeout: float = ROBOT_TIMEOUT,
                   interval: float = 0.25) -> np.ndarray:
    """The 3D view once the robot is in it, every link placed, and the picture has stopped
    changing. `alive()` says whether the launch still runs."""
    deadline = time.monotonic() + timeout
    last, same = None, 0
    while time.monotonic() < deadline:
        if not alive():
            raise RuntimeError("display.launch ended before RViz showed the robot")
        screen = grab(display)
        box = view_box(screen)
        if box is not None:
            view = screen[box[0]:box[1], box[2]:box[3]]
            if robot_pixels(view).mean() > 0.002 and unplaced_pixels(view).mean() < 0.0005:
                same = same + 1 if last is not None and np.array_equal(view, last) else 0
                if same >= SETTLED - 1:
                    return view
            last = view
        time.sleep(interval)
    raise RuntimeError(f"RViz did not show the robot with every link placed in {timeout:.0f} s")


def trimmed(view: np.ndarray, margin: float = 0.08) -> np.ndarray:
    """The view without the empty rows and columns around the robot, but `margin` (of the
    view's larger side) of them: a long, thin robot does not come out as a thin line in
    a square of floor."""
    robot = robot_pixels(view)
    rows, cols = np.flatnonzero(robot.any(axis=1)), np.flatnonzero(robot.any(axis=0))
    pad = round(margin * max(view.shape[:2]))
    return view[max(rows[0] - pad, 0):rows[-1] + pad + 1, max(cols[0] - pad, 0):cols[-1] + pad + 1]


def _wait_for_master(uri: str) -> None:
    deadline = time.monotonic() + START_TIMEOUT
    while time.monotonic() < deadline:
        try:
            xmlrpc.client.ServerProxy(uri).getSystemState("/rviz_picture")
            return
        except OSError:
            time.sleep(0.1)
    raise RuntimeError(f"roscore did not answer on {uri}")


def _free_port() -> int:
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def picture(package: Path) -> np.ndarray:
    """RViz's 3D view of `package` as its display.launch shows it: a master of its own on a
    free loopback port, a virtual screen, the launch file; all stopped at the end."""
    with ExitStack() as stack:
        home = Path(stack.enter_context(tempfile.TemporaryDirectory(prefix="rviz-")))
        display = stack.enter_context(xvfb()).display
        port = _free_port()
        uri = f"http://127.0.0.1:{port}"
        ros = {**os.environ, "ROS_MASTER_URI": uri, "ROS_IP": "127.0.0.1",
               "ROS_HOSTNAME": "127.0.0.1", "ROS_HOME": str(home / "ros"),
               "ROS_LOG_DIR": str(home / "ros" / "log")}
        env = environment(ros, package, display, joint_state_publisher_gui(home / "stand-in"),
                          home)
        log = open(home / "launch.log", "wb")
        stack.callback(log.close)
        started = []
        stack.callback(lambda: [stop(p) for p in reversed(started)])
        for command in (["roscore", "-p", str(port)],
                        ["roslaunch", "--wait", package.name, "display.launch"]):
            started.append(subprocess.Popen(command, env=env, stdout=log, stderr=subprocess.STDOUT,
                                            stdin=subprocess.DEVNULL, start_new_session=True))
            if command[0] == "roscore":
                _wait_for_master(uri)
        try:
            view = wait_for_robot(display, lambda: started[-1].poll() is None)
            log.flush()
            if "process has died" in (home / "launch.log").read_text(errors="replace"):
                raise RuntimeError("a node of display.launch stopped")
            return view
        except RuntimeError as exc:
            log.flush()
            raise RuntimeError(f"{package.name}: {exc}\n"
                               + (home / "launch.log").read_text(errors="replace")[-3000:])


def rviz_picture(package: str):
    """A figure maker: RViz's 3D view of the example package `package` (a folder from the
    repository's root), trimmed to the robot. Where RViz cannot run, the figure is kept
    as it is."""
    def make(path: Path) -> None:
        from PIL import Image
        from .media import Unavailable
        reason = missing()
        if reason:
            raise Unavailable(f"RViz: {reason}")
        Image.fromarray(trimmed(picture(ROOT / package))).save(path, optimize=True)
    make.__qualname__ = "rviz_picture"
    return make
