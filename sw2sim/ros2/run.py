"""`sw2sim ros2 PACKAGE`: a ROS 2 package's robot under real rclpy, with MuJoCo in the
place of Gazebo Sim, gz_ros2_control and robot_state_publisher (sw2sim.ros2.node).

One process, the node itself, and the watcher of its shared-memory files (below). A ROS 1
export (a catkin package.xml, no config/controllers.yaml) is first ported into a temporary
folder with sw2sim.port, removed at the end. ROS 2 stays on this machine
(sw2sim.ros2.discovery), in the user's ROS_DOMAIN_ID or 0, printed for a second terminal to
match; should Fast DDS open a socket beyond 127.0.0.1 all the same, the process says so and
stops. The process stops on Ctrl-C (also where the shell started it with Ctrl-C ignored, in
the background of a script), SIGTERM, SIGHUP, after --duration seconds, and when its parent
process dies. Fast DDS's shared-memory files go with it however it ends: Fast DDS removes
them on the way out, and a watcher in a session of its own (sw2sim.ros2.shm) removes those
a SIGKILL leaves; each run also removes the ones killed runs left.
"""

from __future__ import annotations

import ctypes
import os
import shutil
import signal
import sys
import tempfile
import threading
import time
from pathlib import Path

from . import INSTALL, missing

PR_SET_PDEATHSIG = 1


def _die_with_parent() -> None:
    """SIGTERM when the parent process ends (Linux); elsewhere the loop watches getppid."""
    try:
        ctypes.CDLL(None, use_errno=True).prctl(PR_SET_PDEATHSIG, int(signal.SIGTERM), 0, 0, 0)
    except (OSError, AttributeError):
        pass


def _is_ros1(package) -> bool:
    manifest = package.root / "package.xml"
    text = manifest.read_text(encoding="utf-8", errors="replace") if manifest.is_file() else ""
    return ("<buildtool_depend>catkin" in text or package.robot.find("ros2_control") is None)


def installed(path: str) -> str:
    """The folder to read for what `sw2sim ros2` was given, where colcon built the package:
    a bare package name found under AMENT_PREFIX_PATH (after `source install/setup.bash`)
    is its share folder; a share folder that `colcon build --symlink-install` filled with
    links (package.xml among them) is the source folder they lead to, which holds the same
    files as the package's own. Anything else is returned as given."""
    given = Path(path)
    if not given.exists() and path and "/" not in path and os.sep not in path:
        for prefix in os.environ.get("AMENT_PREFIX_PATH", "").split(os.pathsep):
            share = Path(prefix) / "share" / path if prefix else None
            if share is not None and (share / "package.xml").is_file():
                given = share
                break
    manifest = given / "package.xml"
    if given.is_dir() and manifest.is_symlink() and given.parent.name == "share":
        source = manifest.resolve().parent
        if (source / "package.xml").is_file():
            return str(source)
    return str(given)


def _ported(package, say):
    """A ROS 2 port of a ROS 1 package in a temporary folder: (package, folder)."""
    try:
        from ..port import port
    except ImportError:
        say("sw2sim ros2: this is a ROS 1 package and `sw2sim port` (which makes the ROS 2 "
            "package) is not available in this version of sw2sim")
        return None, None
    from ..package import find_package
    scratch = Path(tempfile.mkdtemp(prefix="sw2sim-ros2-"))
    report = port(package, scratch / package.name)
    say(f"sw2sim ros2: {package.name} is a ROS 1 package: ported for this run into "
        f"{report.package_dir} ({len(report.choices)} choice(s); `sw2sim port` lists them)")
    return find_package(report.package_dir), scratch


def run(path: str, duration: float | None = None, realtime: float = 1.0, view: bool = False,
        say=print) -> int:
    reason = missing()
    if reason:
        say(f"sw2sim ros2: {reason}")
        return 2
    from ..package import LoadError, find_package
    try:
        package = find_package(installed(path))
    except LoadError as exc:
        say(f"sw2sim ros2: {exc}")
        return 2
    from . import messages
    try:
        messages.ensure(say=say)
    except messages.MessagesError as exc:
        say(f"sw2sim ros2: {exc}")
        return 2
    env = messages.environment()
    if env.get("LD_LIBRARY_PATH") != os.environ.get("LD_LIBRARY_PATH"):
        # The message libraries sit in a cache folder: the loader reads LD_LIBRARY_PATH
        # only when a process starts.
        os.execve(sys.executable, sys.orig_argv, env)
    scratch = None
    stop = threading.Event()
    previous = {}

    def request_stop(signum, frame):
        stop.set()

    for sig in (signal.SIGINT, signal.SIGTERM, signal.SIGHUP):
        previous[sig] = signal.signal(sig, request_stop)
    _die_with_parent()
    parent = os.getppid()
    try:
        if _is_ros1(package):
            package, scratch = _ported(package, say)
            if package is None:
                return 2
        from . import config, discovery
        try:
            setup = config.read(package)
        except Exception as exc:  # noqa: BLE001  (YAML and XML fail in many ways)
            say(f"sw2sim ros2: {package.root}: {exc}")
            return 2
        if not setup.joints:
            say(f"sw2sim ros2: {package.urdf} has no <ros2_control> block with joints: "
                "nothing for the controllers to drive (`sw2sim port` writes one)")
        domain = discovery.domain_id()
        os.environ.update(discovery.environment(domain))
        for variable in ("ROS_LOCALHOST_ONLY", "ROS_STATIC_PEERS"):
            os.environ.pop(variable, None)
        from . import shm
        if shm.supported():
            shm.sweep()    # what killed runs left in /dev/shm
            shm.watch()    # what this one leaves, however it ends
        return _serve(package, setup, domain, duration, realtime, view, stop, parent, say)
    finally:
        for sig, handler in previous.items():
            signal.signal(sig, handler)
        if scratch is not None:
            shutil.rmtree(scratch, ignore_errors=True)


def _serve(package, setup, domain, duration, realtime, view, stop, parent, say) -> int:
    import rclpy
    from rclpy.executors import SingleThreadedExecutor
    from rclpy.signals import SignalHandlerOptions

    from ..archive import shown
    from . import discovery
    from .node import Simulation
    context = rclpy.Context()
    rclpy.init(context=context, signal_handler_options=SignalHandlerOptions.NO)
    node = executor = spinner = window = sim = None
    try:
        node = rclpy.create_node("sw2sim", context=context)
        outside = discovery.beyond_loopback()
        if outside:
            say(f"sw2sim ros2: Fast DDS opened sockets beyond 127.0.0.1 "
                f"({', '.join(outside)}): it did not apply the profile "
                f"{discovery.profile_file()} (its messages above say why); stopped, to keep "
                "ROS 2 on this machine")
            return 2
        try:
            sim = Simulation(package, setup, node, say=say)
        except Exception as exc:  # noqa: BLE001  (the model cannot be loaded)
            say(f"sw2sim ros2: {' '.join(str(exc).split())} (`sw2sim check` on the package "
                "lists every problem, each with its fix)")
            return 2
        say(f"sw2sim ros2: {shown(package.root) or package.root} on ROS_DOMAIN_ID={domain} "
            "(this machine only: every socket on 127.0.0.1), MuJoCo standing in "
            "for Gazebo Sim, gz_ros2_control and robot_state_publisher")
        say(f"sw2sim ros2: in the terminals of your nodes: export ROS_DOMAIN_ID={domain} "
            "ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST")
        sim.start()
        executor = SingleThreadedExecutor(context=context)
        for each in (node, *sim.extra_nodes):   # the controller manager's node too
            executor.add_node(each)
        spinner = threading.Thread(target=_spin, args=(executor, stop), daemon=True)
        spinner.start()
        if view:
            from ..ros.viewer import Window   # shows any object with lock, model, data
            window = Window(sim)
        started = time.monotonic()
        end = None if duration is None else started + duration
        sim_start = sim.time
        checked = started
        while not stop.is_set():
            now = time.monotonic()
            if end is not None and now >= end:
                break
            if now - checked > 0.5:
                checked = now
                if os.getppid() != parent:   # the parent died (where prctl is missing)
                    break
            if window is not None:
                window.update()
            sim.step()
            if realtime > 0:
                ahead = (sim.time - sim_start) / realtime - (time.monotonic() - started)
                if ahead > 0.002:
                    time.sleep(min(ahead, 0.05))
        return 0
    finally:
        stop.set()
        if window is not None:
            window.close()
        if executor is not None:
            executor.shutdown(timeout_sec=1.0)
        if spinner is not None:
            spinner.join(timeout=2.0)
        for each in getattr(sim, "extra_nodes", []):
            each.destroy_node()
        if node is not None:
            node.destroy_node()
        if context.ok():
            rclpy.shutdown(context=context)


def _spin(executor, stop) -> None:
    while not stop.is_set():
        try:
            executor.spin_once(timeout_sec=0.05)
        except Exception:  # noqa: BLE001  (shutting down)
            if stop.is_set():
                return
            raise


__all__ = ["run", "INSTALL"]
