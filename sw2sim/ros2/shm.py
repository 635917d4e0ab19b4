"""Fast DDS's shared-memory files: finding those no live process holds, and removing them.

Fast DDS 2.14 (ROS 2 Jazzy) keeps these in /dev/shm while a participant runs:

- its segment, `fastrtps_<16 hex digits>`, with the lock file `fastrtps_<id>_el`, which
  the owner locks (flock) before it creates the segment and holds until it has removed it;
- a port for each locator it listens on, `fastrtps_port<N>`, with its reader's lock file
  (`_el`, exclusive, or `_sl`, shared) and the named semaphore that guards opening it
  (`sem.fastrtps_port<N>_mutex`).

A participant that ends removes them. A process killed with SIGKILL cannot, and then
about 0.6 MB stays per participant. Fast DDS's own rule for such leftovers is the one used
here: a file is dead when its lock file exists and nobody holds the lock. So decide
SharedMemGlobal::Port::is_zombie
(https://github.com/eProsima/Fast-DDS/blob/v2.14.5/src/cpp/rtps/transport/shared_mem/SharedMemGlobal.hpp#L936-L979),
the watchdog of the segments a process has opened
(https://github.com/eProsima/Fast-DDS/blob/v2.14.5/src/cpp/rtps/transport/shared_mem/SharedMemManager.hpp#L1249-L1262)
and the `fastdds shm clean` tool
(https://github.com/eProsima/Fast-DDS/blob/v2.14.5/tools/fastdds/shm/clean.py#L86-L116).
A segment's lock is taken before the segment is made
(https://github.com/eProsima/Fast-DDS/blob/v2.14.5/src/cpp/rtps/transport/shared_mem/SharedMemManager.hpp#L530-L558),
and a lock whose file went while it was being taken is taken again on a new file
(https://github.com/eProsima/Fast-DDS/blob/v2.14.5/src/cpp/utils/shared_memory/RobustExclusiveLock.hpp#L211-L253).
This module applies the rule more carefully than the tool does:

- a segment's lock is held while the segment and the lock file are removed, so that a
  process creating a segment of that name fails to lock it and picks another name (as
  Fast DDS does on a collision);
- a port is examined holding its semaphore, the mutex under which Fast DDS opens, locks
  and removes ports, so that no process is opening it meanwhile;
- a port left without a lock file (its reader ended normally while a writer had been
  killed, so the port's count of users never reached zero) is removed only when no process
  that could write to it has it mapped or open (read from /proc).

`sweep()` removes what is dead, once. `watch()` starts a small process in a session of
its own that waits for the calling process to end, however it ends (SIGKILL of the
process or of its whole process group included), and then sweeps. Run as a script
(`python shm.py PID FD`), this file is that process: it imports the standard library only.
"""

from __future__ import annotations

import ctypes
import fcntl
import os
import re
import subprocess
import sys
import time
from pathlib import Path

DIRECTORY = Path("/dev/shm")
DOMAIN = "fastrtps"   # SharedMemTransport's domain name in Fast DDS 2.x
SEGMENT = re.compile(rf"{DOMAIN}_([0-9a-f]{{16}})(?:_el|_sl)?$")
PORT = re.compile(rf"(?:sem\.)?{DOMAIN}_port(\d+)(?:_el|_sl|_mutex)?$")
WAIT_GONE = 10.0   # s the watcher waits for the ended process to release its files
# s: a port's semaphore without the port is a leftover only when older than this (Fast
# DDS's open_port_internal makes the semaphore a moment before the port)
LONE_SEMAPHORE_AGE = 5.0


def supported() -> bool:
    return sys.platform.startswith("linux") and DIRECTORY.is_dir()


def sweep(directory: Path = DIRECTORY) -> list[str]:
    """Remove the dead Fast DDS files in `directory`; the names of those removed."""
    try:
        names = os.listdir(directory)
    except OSError:
        return []
    segments = sorted({m.group(1) for n in names if (m := SEGMENT.match(n))})
    ports = sorted({int(m.group(1)) for n in names if (m := PORT.match(n))})
    removed = []
    for segment in segments:
        removed += _sweep_segment(directory, segment)
    mapped = None
    for port in ports:
        done, mapped = _sweep_port(directory, port, mapped)
        removed += done
    return removed


def _unlink(directory: Path, names) -> list[str]:
    done = []
    for name in names:
        try:
            os.unlink(directory / name)
            done.append(name)
        except FileNotFoundError:
            pass
        except OSError:   # another user's file in the sticky /dev/shm
            pass
    return done


def _lock(path: Path) -> int | None:
    """The file's descriptor with an exclusive lock held; None when someone holds a lock
    on it (or it cannot be opened: it is not ours to judge)."""
    try:
        fd = os.open(path, os.O_RDONLY)
    except OSError:
        return None
    try:
        fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
    except OSError:
        os.close(fd)
        return None
    return fd


def _sweep_segment(directory: Path, segment: str) -> list[str]:
    base = f"{DOMAIN}_{segment}"
    files = [base, f"{base}_el", f"{base}_sl"]
    locks = [n for n in files[1:] if (directory / n).exists()]
    held = []
    try:
        for name in locks:
            fd = _lock(directory / name)
            if fd is None:
                return []   # its owner lives
            held.append(fd)
        # Locked by nobody, or no lock file at all: the owner locks before it creates the
        # segment and removes the segment before it unlocks, so no owner is alive.
        return _unlink(directory, files)
    finally:
        for fd in held:
            os.close(fd)


class _Semaphore:
    """A port's POSIX named semaphore (boost's named_mutex on Linux), through the C library;
    opened only where it exists."""

    def __init__(self, name: str):
        self.name = f"/{name}".encode()
        libc = ctypes.CDLL(None, use_errno=True)
        libc.sem_open.restype = ctypes.c_void_p
        libc.sem_open.argtypes = [ctypes.c_char_p, ctypes.c_int]
        for call in ("sem_trywait", "sem_post", "sem_close"):
            getattr(libc, call).argtypes = [ctypes.c_void_p]
        libc.sem_unlink.argtypes = [ctypes.c_char_p]
        self.libc = libc
        self.sem = libc.sem_open(self.name, 0)
        if not self.sem:   # SEM_FAILED
            raise OSError(ctypes.get_errno(), os.strerror(ctypes.get_errno()))
        self.held = False

    def try_acquire(self) -> bool:
        self.held = self.libc.sem_trywait(self.sem) == 0
        return self.held

    def close(self, remove: bool = False) -> None:
        if self.held:
            if remove:   # as Fast DDS removes a port's mutex: while holding it
                self.libc.sem_unlink(self.name)
            self.libc.sem_post(self.sem)
        self.libc.sem_close(self.sem)


def _sweep_port(directory: Path, port: int, mapped):
    """(names removed, the mapped files once read) for one port."""
    base = f"{DOMAIN}_port{port}"
    files = [base, f"{base}_el", f"{base}_sl"]
    mutex = None
    if (directory / f"sem.{base}_mutex").exists():
        try:
            mutex = _Semaphore(f"{base}_mutex")
        except OSError:
            return [], mapped
        if not mutex.try_acquire():   # a process is opening or closing the port
            mutex.close()
            return [], mapped
    held = []
    dead = False
    try:
        present = [n for n in files if (directory / n).exists()]
        locks = [n for n in present if n != base]
        for name in locks:
            fd = _lock(directory / name)
            if fd is None:
                return [], mapped   # its reader lives
            held.append(fd)
        if base in present and not locks:
            if mapped is None:
                mapped = _mapped_files()
            if str(directory / base) in mapped:
                return [], mapped   # a writer still has it
        if not present and not _older(directory / f"sem.{base}_mutex", LONE_SEMAPHORE_AGE):
            return [], mapped   # a process may have just created it, to open the port
        dead = True
        return _unlink(directory, files) + ([f"sem.{base}_mutex"] if mutex else []), mapped
    finally:
        for fd in held:
            os.close(fd)
        if mutex is not None:
            mutex.close(remove=dead)


def _older(path: Path, seconds: float) -> bool:
    try:
        return time.time() - path.stat().st_mtime > seconds
    except OSError:
        return False


def _mapped_files() -> set[str]:
    """Every /dev/shm file a process this one may inspect has mapped or open. A process
    of another user cannot write to this user's ports, and its /proc is closed to us."""
    found = set()
    for entry in Path("/proc").glob("[0-9]*"):
        try:
            for line in (entry / "maps").read_text(errors="replace").splitlines():
                where = line.find(f" {DIRECTORY}/")
                if where >= 0:
                    found.add(line[where + 1:].removesuffix(" (deleted)"))
            for fd in (entry / "fd").iterdir():
                try:
                    target = os.readlink(fd)
                except OSError:
                    continue
                if target.startswith(f"{DIRECTORY}/"):
                    found.add(target)
        except OSError:
            continue
    return found


# -- the watcher ---------------------------------------------------------------------------

def watch() -> subprocess.Popen | None:
    """Start the process that sweeps once this one has ended; None where there is no
    /dev/shm. The pipe's writing end stays open in this process (and in none other) until
    it ends, which the watcher reads as the end."""
    if not supported():
        return None
    reading, writing = os.pipe()   # neither end is inherited by later children
    try:
        return subprocess.Popen([sys.executable, "-I", "-S", str(Path(__file__).resolve()),
                                 str(os.getpid()), str(reading)], pass_fds=(reading,),
                                stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                                stderr=subprocess.DEVNULL, start_new_session=True)
    except OSError:
        os.close(writing)
        return None
    finally:
        os.close(reading)


def _start_time(pid: int) -> str | None:
    try:
        fields = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
    except (OSError, IndexError):
        return None
    return None if fields[0] in ("Z", "X") else fields[19]


def _main(pid: int, fd: int) -> int:
    started = _start_time(pid)
    try:
        while os.read(fd, 4096):   # until the pipe's one writer, the watched process, ends
            pass
    except OSError:
        pass
    os.close(fd)
    # The pipe closes as the process ends; its locks and mappings go with the rest of its
    # files. Wait until it is a zombie or gone (or its number is another process's).
    deadline = time.monotonic() + WAIT_GONE
    while (started is not None and _start_time(pid) == started
           and time.monotonic() < deadline):
        time.sleep(0.01)
    sweep()
    return 0


if __name__ == "__main__":
    sys.exit(_main(int(sys.argv[1]), int(sys.argv[2])))
