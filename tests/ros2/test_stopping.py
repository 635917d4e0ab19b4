"""`sw2sim ros2` leaves nothing running: on Ctrl-C (also where it was started with Ctrl-C
ignored, as in the background of a script), SIGTERM, --duration and its parent's death.
Nor does it leave Fast DDS's shared-memory files, read from /proc while it runs: they go
on Ctrl-C and SIGTERM, and after a SIGKILL of its process group its watcher (in a session
of its own) removes them; it removes those that killed processes left when it starts, and
never those of a live process."""

from __future__ import annotations

import ctypes
import fcntl
import mmap
import os
import re
import secrets
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from repository import ROOT
from ros2_environment import PYTHON
from sw2sim.ros2 import shm

SHM = shm.DIRECTORY


def _wait_up(ros2, timeout=20.0):
    deadline = time.monotonic() + timeout
    while "controllers:" not in ros2.log("standin"):
        assert time.monotonic() < deadline, ros2.log("standin")
        time.sleep(0.1)


def shm_files(pid: int) -> set[Path]:
    """The Fast DDS files in /dev/shm the process has mapped or open, and the semaphores of
    its ports (which Fast DDS opens only while it opens or closes a port)."""
    found = set()
    for line in Path(f"/proc/{pid}/maps").read_text().splitlines():
        if f" {SHM}/" in line:
            found.add(Path(line[line.index(f" {SHM}/") + 1:]))
    for fd in Path(f"/proc/{pid}/fd").iterdir():
        try:
            target = Path(os.readlink(fd))
        except OSError:
            continue
        if target.parent == SHM:
            found.add(target)
    found = {f for f in found if f.name.startswith(shm.DOMAIN + "_")}
    ports = [f for f in found if re.fullmatch(rf"{shm.DOMAIN}_port\d+", f.name)]
    return found | {SHM / f"sem.{f.name}_mutex" for f in ports}


def watcher_of(pid: int) -> int | None:
    """The pid of the process watching `pid`'s shared-memory files."""
    for entry in Path("/proc").glob("[0-9]*"):
        try:
            words = (entry / "cmdline").read_bytes().split(b"\0")
        except OSError:
            continue
        for i, word in enumerate(words[:-1]):
            if word.endswith(b"sw2sim/ros2/shm.py") and words[i + 1] == str(pid).encode():
                return int(entry.name)
    return None


def running(pid: int) -> bool:
    try:
        state = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0]
    except (OSError, IndexError):
        return False
    return state not in ("Z", "X")


def ended_clean(files: set[Path], watcher: int | None) -> list[str]:
    """Once the run's watcher has ended: which of the run's files are still there."""
    deadline = time.monotonic() + 10
    while watcher is not None and running(watcher):
        assert time.monotonic() < deadline, f"the watcher {watcher} outlived its run"
        time.sleep(0.05)
    left = {f for f in files if f.exists()}
    return sorted(str(f) for f in left - used_by_others(left))


def used_by_others(files: set[Path]) -> set[Path]:
    """Those of `files` that another running process has mapped or open: a port such as
    fastrtps_port7000 is shared by every participant on the machine (tests run side by
    side), and is its last user's to remove."""
    used = set()
    for entry in Path("/proc").glob("[0-9]*"):
        if not files - used:
            break
        try:
            pid = int(entry.name)
            if pid != os.getpid() and running(pid):
                used |= shm_files(pid) & files
        except (OSError, ValueError):
            continue
    return used


@pytest.mark.parametrize("sig", [signal.SIGINT, signal.SIGTERM])
def test_a_signal_stops_it_promptly(ros2, ported_example_3, sig):
    previous = signal.signal(signal.SIGINT, signal.SIG_IGN)   # as a background job has it
    try:
        process = ros2.standin(ported_example_3)
    finally:
        signal.signal(signal.SIGINT, previous)
    _wait_up(ros2)
    files, watcher = shm_files(process.pid), watcher_of(process.pid)
    began = time.monotonic()
    process.send_signal(sig)
    assert process.wait(timeout=5) == 0
    assert time.monotonic() - began < 3
    assert not ros2.group_alive(process.pid)
    if shm.supported():
        assert files, "/proc shows no Fast DDS shared-memory file of the stand-in"
        assert not ended_clean(files, watcher)


class Planted:
    """Fast DDS files as processes leave them in /dev/shm: dead (a killed participant's
    segment and port, a port whose users all ended without removing it) and live (a
    segment and a port whose lock this process holds, a port it has mapped)."""

    def __init__(self):
        self.dead: list[str] = []
        self.live: list[str] = []
        self.held: list = []
        # Fast DDS's ports start at portBase - 400 = 7000 (unique flows, RTPSParticipantImpl)
        base = 1000 + secrets.randbelow(1000) * 4
        for state, segment in (("dead", secrets.token_hex(8)), ("live", secrets.token_hex(8))):
            name = f"{shm.DOMAIN}_{segment}"
            self.write(state, name, b"\0" * 4096)
            self.write(state, f"{name}_el", b"", lock=state == "live")
        for state, port in (("dead", base), ("live", base + 1)):
            name = f"{shm.DOMAIN}_port{port}"
            self.write(state, name, b"\0" * 4096)
            self.write(state, f"{name}_el", b"", lock=state == "live")
            self.semaphore(state, f"{name}_mutex")
        for state, port in (("dead", base + 2), ("live", base + 3)):   # no lock file
            name = f"{shm.DOMAIN}_port{port}"
            self.write(state, name, b"\0" * 4096, map_it=state == "live")
            self.semaphore(state, f"{name}_mutex")

    def write(self, state, name, data, lock=False, map_it=False):
        path = SHM / name
        path.write_bytes(data)
        getattr(self, state).append(name)
        if lock or map_it:
            handle = open(path, "r+b")
            if lock:
                fcntl.flock(handle, fcntl.LOCK_EX)
            else:
                self.held.append(mmap.mmap(handle.fileno(), 0))
            self.held.append(handle)

    def semaphore(self, state, name):
        libc = ctypes.CDLL(None, use_errno=True)
        libc.sem_open.restype = ctypes.c_void_p
        libc.sem_open.argtypes = [ctypes.c_char_p, ctypes.c_int, ctypes.c_uint, ctypes.c_uint]
        libc.sem_close.argtypes = [ctypes.c_void_p]
        sem = libc.sem_open(f"/{name}".encode(), os.O_CREAT, 0o644, 1)
        assert sem, os.strerror(ctypes.get_errno())
        libc.sem_close(sem)
        os.utime(SHM / f"sem.{name}", (time.time() - 60, time.time() - 60))
        getattr(self, state).append(f"sem.{name}")

    def there(self, names) -> list[str]:
        return [n for n in names if (SHM / n).exists()]

    def remove(self):
        for handle in reversed(self.held):
            handle.close()
        for name in self.dead + self.live:
            (SHM / name).unlink(missing_ok=True)


def test_a_sigkill_leaves_no_shared_memory_files(ros2, ported_example_3):
    if not shm.supported():
        pytest.skip("no /dev/shm: Fast DDS keeps its shared memory elsewhere")
    planted = Planted()
    try:
        process = ros2.standin(ported_example_3)
        _wait_up(ros2)
        assert not planted.there(planted.dead), "files dead processes left stayed"
        files, watcher = shm_files(process.pid), watcher_of(process.pid)
        assert files, "/proc shows no Fast DDS shared-memory file of the stand-in"
        assert watcher is not None, "no watcher"
        assert os.getsid(watcher) != os.getsid(process.pid)
        os.killpg(process.pid, signal.SIGKILL)   # the whole group, as `kill -9 -PGID`
        assert process.wait(timeout=5) == -signal.SIGKILL
        assert not ended_clean(files, watcher)
        assert planted.there(planted.live) == planted.live, "a live process's files went"
    finally:
        planted.remove()


def test_duration_ends_it(ros2, ported_example_3):
    process = ros2.start(str(PYTHON), "-m", "sw2sim", "ros2", str(ported_example_3),
                         "--realtime", "0", "--duration", "0.2", name="standin")
    assert process.wait(timeout=20) == 0


def test_it_ends_with_its_parent(ros2, ported_example_3):
    # a parent that starts it and is then killed without a chance to stop it
    parent = ros2.start(str(PYTHON), "-c",
                        "import subprocess, sys, time; "
                        f"p = subprocess.Popen([sys.executable, '-m', 'sw2sim', 'ros2', "
                        f"{str(ported_example_3)!r}, '--realtime', '0', '--duration', '60']); "
                        "print(p.pid, flush=True); time.sleep(60)", name="parent")
    deadline = time.monotonic() + 20
    while not (ros2.home / "parent.log").read_text().strip():
        assert time.monotonic() < deadline
        time.sleep(0.1)
    child = int((ros2.home / "parent.log").read_text().split()[0])
    while "controllers:" not in ros2.log("parent"):   # the child is up (it prints there)
        assert time.monotonic() < deadline, ros2.log("parent")
        time.sleep(0.1)
    parent.kill()
    parent.wait()
    deadline = time.monotonic() + 5
    while time.monotonic() < deadline:
        try:
            with open(f"/proc/{child}/stat") as stat:
                if stat.read().rsplit(")", 1)[1].split()[0] == "Z":
                    break
        except FileNotFoundError:
            break
        time.sleep(0.1)
    else:
        raise AssertionError("sw2sim ros2 outlived its parent")


def test_without_rclpy_it_says_what_to_install_on_one_line(tmp_path, monkeypatch):
    import sw2sim.ros2.run as run_module
    monkeypatch.setattr(run_module, "missing", lambda: run_module.INSTALL)
    said = []
    assert run_module.run("examples/example_3", say=said.append) == 2
    assert len(said) == 1 and "\n" not in said[0]
    assert 'pip install "sw2sim[ros2]"' in said[0] and "make setup" in said[0]


def test_a_python_without_rclpy_is_told_so():
    """The tests' own environment has no rclpy (ROS 2 lives in .venv-ros2): there, the
    command says on one line what to install, and exits 2."""
    import importlib.util
    if importlib.util.find_spec("rclpy") is not None:
        pytest.skip("this Python has rclpy")
    done = subprocess.run([sys.executable, "-m", "sw2sim", "ros2", "examples/example_3",
                           "--duration", "1"], cwd=ROOT, capture_output=True, text=True,
                          timeout=60)
    assert done.returncode == 2, done.stdout + done.stderr
    said = (done.stdout + done.stderr).strip().splitlines()
    assert len(said) == 1 and 'pip install "sw2sim[ros2]"' in said[0], said
