"""Fork server: page processes forked from one that has already imported the heavy libraries.

Importing numpy, MuJoCo, Matplotlib, trimesh and SciPy takes a page process over a second,
most of a page's time. The server is started once, exactly like a page process (child.py
run as a file with `-c`, the page's environment, cwd the repository root; see child.py's
`--serve`), imports those libraries, then forks one process per page. The forked process:

- starts a session of its own (the page's process group, killed as a whole);
- takes the capture file as fds 1 and 2, the report pipe, the page's cwd and environment
  (the runner's `child_env()` at the time of the request);
- moves every module the server imported beyond what child.py itself has out of
  sys.modules into a stash, so the page starts with what a fresh interpreter has. A finder
  first on sys.meta_path hands a stashed module back when the page imports it, together
  with the stashed modules its import imported in turn and the environment variables and
  warning filters it set: `import numpy` is instant, and sys.modules, os.environ and the
  warning filters change as they would in a fresh interpreter;
- runs child.py's `main`, as a plain page process does.

The server reaps the page processes and reports each one's exit status (Popen's
convention: -N for signal N), since the runner is not their parent.

Protocol (AF_UNIX SOCK_SEQPACKET sockets, one message per send):
  server -> runner, control socket  b"ready", once the libraries are imported
  runner -> server, control socket  JSON {"job", "cwd", "env"}, with the fds
                                    [reply socket, report pipe, capture file]
  server -> runner, reply socket    JSON {"pid": n} once the page process has its session,
                                    JSON {"status": n} once it has ended
The server kills the page processes it still has and exits when the control socket closes.

Stdlib only: the server process loads this file with runpy (it must not import the course
package), and the runner imports it for `ForkServer`. That is also why it is
over 500 lines: the server, the page process's fresh-interpreter stash and the runner's
client are one file, since a file loaded by path cannot import siblings without putting
the course build on the page's sys.path.
"""

from __future__ import annotations

import builtins
import gc
import importlib.util
import json
import linecache
import os
import select
import signal
import socket
import sys
import traceback
import warnings
from collections.abc import Callable
from importlib.machinery import ModuleSpec
from pathlib import Path
from types import ModuleType
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    import subprocess

# fork() is unsafe on macOS once system frameworks are loaded; Windows has no fork at all.
AVAILABLE = (
    hasattr(os, "fork")
    and sys.platform != "darwin"
    and hasattr(socket, "SOCK_SEQPACKET")
    and hasattr(socket, "send_fds")
)
MESSAGE_SIZE = 1 << 18  # largest request: the job's path, the cwd and the environment


class ForkServerError(RuntimeError):
    """The server cannot start a page process."""


# ---------------------------------------------------------------------------------------
# Runner side


class ForkedProcess:
    """A page process the server forked: the part of Popen that run_page uses."""

    def __init__(self, pid: int, reply: socket.socket):
        self.pid = pid
        self.returncode: int | None = None
        self._reply = reply

    def wait(self) -> int | None:
        """Its exit status (-N: killed by signal N); None if the server stopped first."""
        if self._reply is not None:
            try:
                message = self._reply.recv(MESSAGE_SIZE)
            except OSError:
                message = b""
            self._reply.close()
            self._reply = None
            self.returncode = json.loads(message)["status"] if message else None
        return self.returncode


class ForkServer:
    """A server process, started with `command(control_fd)` in `cwd` with `env`."""

    def __init__(self, command: Callable[[int], list[str]], cwd: Path, env: dict[str, str]):
        # Imported here, not at the top: the server process loads this file too, and the
        # modules it imports before recording its imports come back to pages less exactly.
        import subprocess
        import tempfile
        import threading

        self.owner = os.getpid()
        self.pages = 0  # page processes forked so far
        self._lock = threading.Lock()
        self._ready: bool | None = None  # None until the server has said it is ready, or died
        self._control, theirs = socket.socketpair(socket.AF_UNIX, socket.SOCK_SEQPACKET)
        self._log = tempfile.TemporaryFile()  # the server's own output: import warnings, errors
        try:
            self._proc = subprocess.Popen(
                command(theirs.fileno()),
                cwd=cwd,
                env=env,
                stdin=subprocess.DEVNULL,
                stdout=self._log,
                stderr=subprocess.STDOUT,
                pass_fds=(theirs.fileno(),),
            )
        except BaseException:
            self._control.close()
            self._log.close()
            raise
        finally:
            theirs.close()

    @property
    def pid(self) -> int:
        return self._proc.pid

    def wait_ready(self, timeout: float) -> bool:
        """Wait until the server has imported the libraries; False if it died or is too slow."""
        with self._lock:
            if self._ready is None:
                ready, _, _ = select.select([self._control], [], [], timeout)
                try:
                    message = self._control.recv(64) if ready else b""
                except OSError:
                    message = b""
                self._ready = message == b"ready"
                if not self._ready:
                    self.close()
            return self._ready

    def start(self, job: Path, cwd: Path, env: dict[str, str], report_fd: int, sink_fd: int) -> ForkedProcess:
        """Fork a page process that runs `job` with `report_fd` and `sink_fd` (child.py's)."""
        mine, theirs = socket.socketpair(socket.AF_UNIX, socket.SOCK_SEQPACKET)
        try:
            request = json.dumps({"job": str(job), "cwd": str(cwd), "env": env}).encode()
            with self._lock:
                if not self._ready:
                    raise ForkServerError("the fork server is not running")
                socket.send_fds(self._control, [request], [theirs.fileno(), report_fd, sink_fd])
                self.pages += 1
            theirs.close()
            mine.settimeout(60.0)
            message = mine.recv(MESSAGE_SIZE)
            mine.settimeout(None)
            if not message:
                raise ForkServerError("the fork server stopped")
            return ForkedProcess(json.loads(message)["pid"], mine)
        except OSError as exc:
            mine.close()
            raise ForkServerError(f"the fork server did not answer: {exc}") from exc
        finally:
            theirs.close()

    def output(self) -> str:
        """What the server printed (why it failed, if it did)."""
        try:
            self._log.seek(0)
            return self._log.read().decode("utf-8", errors="replace")
        except (OSError, ValueError):
            return ""

    def close(self) -> None:
        """Stop the server (it kills the page processes it still has) and reap it."""
        import subprocess

        if self.owner != os.getpid():
            return  # a forked copy of the runner: the server belongs to the original
        if self._control.fileno() != -1:
            self._control.close()  # the server sees the end of the control socket and exits
        try:
            # Still importing: it reads nothing until it is done, so stop it right away.
            self._proc.wait(timeout=10.0 if self._ready else 0.0)
        except subprocess.TimeoutExpired:
            self._proc.kill()
            self._proc.wait()
        self._ready = False

    def __enter__(self) -> ForkServer:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()


# ---------------------------------------------------------------------------------------
# Server side (runs in the server process, loaded by child.py --serve)


def serve(run_page: Callable[[list[str]], None], keep: set[str], control_fd: int, preload: list[str]) -> None:
    """Import `preload`, then fork a page process running `run_page` for each request.

    `keep`: the modules of a plain page process (a fresh interpreter, runpy and child.py's
    imports); everything else in sys.modules is stashed in the page processes.
    """
    control = socket.socket(fileno=control_fd)
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # Ctrl-C is for the runner; it closes us
    state = _Preloaded(keep, preload)
    gc.collect()
    gc.freeze()  # the page processes' collections skip (and do not copy) the libraries' objects

    wake_r, wake_w = os.pipe()
    os.set_blocking(wake_w, False)
    signal.set_wakeup_fd(wake_w)
    signal.signal(signal.SIGCHLD, lambda signum, frame: None)  # wakes select through wake_r
    children: dict[int, socket.socket] = {}  # page process -> the reply socket of its runner
    try:
        control.send(b"ready")
        while True:
            ready, _, _ = select.select([control, wake_r], [], [])
            if wake_r in ready:
                os.read(wake_r, 4096)
                _reap(children)
            if control in ready:
                try:
                    message, fds, _, _ = socket.recv_fds(control, MESSAGE_SIZE, 3)
                except OSError:
                    break
                if not message:
                    break  # the runner is done
                if len(fds) != 3:
                    for fd in fds:
                        os.close(fd)
                    continue
                _fork_page(json.loads(message), fds, run_page, state, control, (wake_r, wake_w), children)
    except BaseException:  # noqa: BLE001 - into the server's log, which the runner shows
        traceback.print_exc()
    finally:
        for pid in children:
            try:
                os.killpg(pid, signal.SIGKILL)
            except OSError:
                pass
            try:
                os.waitpid(pid, 0)
            except ChildProcessError:
                pass
        os._exit(0)  # no teardown of the libraries (GL, threads): nothing to save


def _reap(children: dict[int, socket.socket]) -> None:
    """Report the status of every page process that has ended."""
    while True:
        try:
            pid, status = os.waitpid(-1, os.WNOHANG)
        except ChildProcessError:
            return
        if pid == 0:
            return
        reply = children.pop(pid, None)
        if reply is not None:
            try:
                reply.send(json.dumps({"status": os.waitstatus_to_exitcode(status)}).encode())
            except OSError:
                pass  # the runner gave up on it
            reply.close()


def _fork_page(
    request: dict[str, Any],
    fds: list[int],
    run_page: Callable[[list[str]], None],
    state: _Preloaded,
    control: socket.socket,
    wake: tuple[int, int],
    children: dict[int, socket.socket],
) -> None:
    reply_fd, report_fd, sink_fd = fds
    reply = socket.socket(fileno=reply_fd)
    ready_r, ready_w = os.pipe()
    for stream in (sys.stdout, sys.stderr):
        stream.flush()
    pid = os.fork()
    if pid == 0:  # the page process
        status = 1  # as a Python process ending on an uncaught exception
        try:
            os.setsid()
            os.close(ready_w)  # the server may now give the runner our pid: killpg(pid) works
            os.close(ready_r)
            # Only the server's own descriptors: the libraries keep theirs, as after an import.
            for sock in (control, reply, *children.values()):
                os.close(sock.detach())
            signal.set_wakeup_fd(-1)
            for fd in wake:
                os.close(fd)
            os.dup2(sink_fd, 1)
            os.dup2(sink_fd, 2)
            if sink_fd > 2:
                os.close(sink_fd)
            state.become_page(request)
            run_page(["child.py", request["job"], str(report_fd)])  # ends with os._exit(0)
            status = 0
        except SystemExit as exc:
            status = exc.code if isinstance(exc.code, int) else 1
        except BaseException:  # noqa: BLE001 - report anything, as the interpreter would
            traceback.print_exc()
        finally:
            os._exit(status)
    os.close(ready_w)
    os.close(report_fd)
    os.close(sink_fd)
    os.read(ready_r, 1)  # end of file once the page process has its session (or has died)
    os.close(ready_r)
    children[pid] = reply
    try:
        reply.send(json.dumps({"pid": pid}).encode())
    except OSError:
        pass


class _Preloaded:
    """The imported libraries, and what a page process needs to hand them out again."""

    def __init__(self, keep: set[str], preload: list[str]):
        self.path = list(sys.path)
        self.filters = list(warnings.filters)
        early = [name for name in sys.modules if name not in keep]  # this server's own imports
        recorder = _Recorder()
        with recorder:
            for name in preload:
                try:
                    __import__(name)
                except Exception as exc:  # noqa: BLE001 - a missing library is just not preloaded
                    print(f"fork server: cannot import {name}: {exc!r}", file=sys.stderr)
        sys.path[:] = self.path
        self.edges = recorder.edges
        self.effects = recorder.effects
        self.modules = {name: module for name, module in sys.modules.items() if name not in keep and module is not None}
        for name in early:
            if name in self.modules:
                self.edges.setdefault(name, set()).update(_references(self.modules[name]))

    def become_page(self, request: dict[str, Any]) -> None:
        """In the forked process: the page's cwd, environment, fresh sys.modules, and so on."""
        signal.signal(signal.SIGCHLD, signal.SIG_DFL)
        signal.signal(signal.SIGINT, signal.default_int_handler)
        os.chdir(request["cwd"])
        env: dict[str, str] = request["env"]
        os.environ.clear()
        os.environ.update(env)
        import tempfile
        tempfile.tempdir = None   # found again, from this page's TMPDIR, at its first use
        sys.path[:] = self.path
        warnings.filters[:] = self.filters
        _filters_mutated()
        random = self.modules.get("numpy.random")
        if random is not None:
            random.seed()  # fresh entropy, as a fresh import has, not the server's state
        importlib.invalidate_caches()  # drops the finder of '', now another directory
        linecache.clearcache()
        # The stashed modules leave sys.modules, and the attributes of kept packages
        # (`importlib.metadata`) that a fresh interpreter would not have yet.
        for name, module in self.modules.items():
            sys.modules.pop(name, None)
            parent, _, child = name.rpartition(".")
            if parent and parent not in self.modules and getattr(sys.modules.get(parent), child, None) is module:
                delattr(sys.modules[parent], child)
        sys.meta_path.insert(0, _Stash(dict(self.modules), self.edges, self.effects, env))
        if os.environ.get("PYTHONFAULTHANDLER"):
            import faulthandler

            faulthandler.enable()  # on the new fd 2


class _Recorder:
    """While the server imports: what each module's import brought along, and the
    environment variables and warning filters it set.

    An import statement run while module M is being imported belongs to M's import, even
    one in a function of another module that M's code calls (a fresh interpreter would run
    it there too): `edges[M]` holds every module that such statements named, and every
    module that got loaded while M was. Effects go to the innermost module being imported.
    """

    def __init__(self) -> None:
        self.edges: dict[str, set[str]] = {}
        self.effects: dict[str, tuple[int, dict[str, str | None], list[Any]]] = {}  # (order, ...)
        self._loading: list[_Loading] = []  # imports under way, innermost last
        self._import = builtins.__import__

    def __enter__(self) -> _Recorder:
        builtins.__import__ = self._recording_import
        return self

    def __exit__(self, *exc: object) -> None:
        builtins.__import__ = self._import

    def _recording_import(self, name: str, globals: Any = None, locals: Any = None, fromlist: Any = (), level: int = 0) -> Any:
        try:
            target = _absolute(name, globals, level)
        except Exception:  # noqa: BLE001 - let the import system say what is wrong
            return self._import(name, globals, locals, fromlist, level)
        wanted = [target, *(f"{target}.{item}" for item in fromlist or () if item != "*")]
        new = [m for m in wanted if m not in sys.modules]  # or attributes, not modules at all
        loading = _Loading(new) if new else None
        if loading is not None:
            self._loading.append(loading)
        try:
            module = self._import(name, globals, locals, fromlist, level)
        finally:
            if loading is not None:
                self._loading.pop()
        if loading is not None:
            self._done(loading)
        if self._loading:
            self._loading[-1].named.update(m for m in wanted if m in sys.modules)
        return module

    def _done(self, loading: _Loading) -> None:
        loaded = [m for m in loading.wanted if m in sys.modules]
        if not loaded:  # names in a fromlist that are attributes: nothing of its own
            if self._loading:
                self._loading[-1].named.update(loading.named)
            return
        owner = loaded[0]
        new = list(sys.modules)[loading.start:]
        brought = set(new) | loading.named
        # Packages loaded on the way to `owner` ran within this import, unseen: theirs too.
        parts = owner.split(".")
        for package in (owner, *(p for p in (".".join(parts[:i]) for i in range(1, len(parts))) if p in new)):
            self.edges.setdefault(package, set()).update(brought - {package})
        if loading.env == _environ_copy() and loading.filters == {id(f) for f in warnings.filters}:
            return  # the common case, and cheap to tell
        env_before = {os.fsdecode(k): os.fsdecode(v) for k, v in loading.env.items()}
        env: dict[str, str | None] = {k: v for k, v in os.environ.items() if env_before.get(k) != v}
        env.update({k: None for k in env_before if k not in os.environ})
        filters = [f for f in warnings.filters if id(f) not in loading.filters]
        claimed_env = {item for effect in self.effects.values() for item in effect[1].items()}
        claimed_filters = {id(f) for effect in self.effects.values() for f in effect[2]}
        env = {k: v for k, v in env.items() if (k, v) not in claimed_env}
        filters = [f for f in filters if id(f) not in claimed_filters]
        if env or filters:
            self.effects[owner] = (len(self.effects), env, filters)


class _Loading:
    """An import under way while the server preloads."""

    def __init__(self, wanted: list[str]):
        self.wanted = wanted
        self.start = len(sys.modules)  # sys.modules keeps insertion order: what is new comes after
        self.named: set[str] = set()  # modules named by the import statements run meanwhile
        self.env = _environ_copy()
        self.filters = {id(f) for f in warnings.filters}


def _references(module: ModuleType) -> set[str]:
    """The modules a module's globals come from: the edges of one imported before recording."""
    found = set()
    for value in list(vars(module).values()):
        if isinstance(value, ModuleType):
            found.add(value.__name__)
        else:
            home = getattr(value, "__module__", None) if callable(value) else None
            if isinstance(home, str):
                found.add(home)
    found.discard(module.__name__)
    return found


def _environ_copy() -> dict[Any, Any]:
    """os.environ as stored (bytes on POSIX): copied without decoding every variable."""
    data = getattr(os.environ, "_data", None)
    return dict(os.environ) if data is None else data.copy()


def _absolute(name: str, globals: Any, level: int) -> str:
    if level == 0:
        return name
    package = globals.get("__package__")
    if not package:
        package = globals["__name__"] if "__path__" in globals else globals["__name__"].rpartition(".")[0]
    return importlib.util.resolve_name("." * level + name, package)


def _filters_mutated() -> None:
    mutated = getattr(warnings, "_filters_mutated", None)
    if mutated is not None:
        mutated()


class _Stash:
    """First finder on sys.meta_path in a page process: hands back the server's modules.

    Importing a stashed module puts it back in sys.modules as it is (never run again: one
    copy of each module, as C extensions need), together with the stashed modules that its
    import imported, and replays the environment variables and warning filters they set.
    """

    def __init__(
        self,
        modules: dict[str, ModuleType],
        edges: dict[str, set[str]],
        effects: dict[str, tuple[int, dict[str, str | None], list[Any]]],
        env: dict[str, str],
    ):
        self.modules = modules  # not handed back yet
        self.edges = edges
        self.effects = effects
        self.env = env  # the page's environment at its start
        self._loading: dict[int, tuple[str, Any, Any]] = {}

    def find_spec(self, name: str, path: Any = None, target: Any = None) -> ModuleSpec | None:
        module = self.modules.get(name)
        if module is None:
            return None
        original = getattr(module, "__spec__", None)
        return ModuleSpec(
            name, self, origin=getattr(original, "origin", None), is_package=hasattr(module, "__path__")
        )

    def create_module(self, spec: ModuleSpec) -> ModuleType:
        module = self.modules[spec.name]
        # The import system sets __spec__ (and a missing __loader__): put back the originals.
        self._loading[id(module)] = (spec.name, getattr(module, "__spec__", None), getattr(module, "__loader__", None))
        return module

    def exec_module(self, module: ModuleType) -> None:
        name, spec, loader = self._loading.pop(id(module))
        for attribute, value in (("__spec__", spec), ("__loader__", loader)):
            try:
                setattr(module, attribute, value)
            except AttributeError:
                pass
        self._hand_back(name)

    def _hand_back(self, name: str) -> None:
        """Put back `name` (the import system does) and what its import imported (we do)."""
        todo, back = [name], []
        while todo:
            current = todo.pop()
            module = self.modules.pop(current, None)
            if module is None:
                continue  # handed back already, or never stashed
            back.append(current)
            parent, _, child = current.rpartition(".")
            if current != name:
                sys.modules[current] = module
                holder = sys.modules.get(parent)
                if holder is not None and not hasattr(holder, child):
                    setattr(holder, child, module)
            todo.extend(self.edges.get(current, ()))
            if parent:
                todo.append(parent)
        # In the order the server's imports had them: later filters go in front.
        for _, env, filters in sorted(self.effects[m] for m in back if m in self.effects):
            self._replay(env, filters)

    def _replay(self, env: dict[str, str | None], filters: list[Any]) -> None:
        for key, value in env.items():
            if os.environ.get(key) == self.env.get(key):  # unless the page set it itself
                if value is None:
                    os.environ.pop(key, None)
                else:
                    os.environ[key] = value
        if filters:
            warnings.filters[:0] = [f for f in filters if f not in warnings.filters]
            _filters_mutated()
