"""The fork server: pages forked from a process that has imported the libraries start and
import as a fresh interpreter would, and the plain subprocess stays available."""

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from course.snippets import format_failure, parse_page, run_page
from course.snippets import execute
from course.snippets.forkserver import AVAILABLE
from course.snippets.outputs import entries

from repository import ROOT

needs_fork = pytest.mark.skipif(not AVAILABLE, reason="no fork server on this system")


def page_file(folder: Path, *blocks: str) -> Path:
    path = folder / "page.md"
    path.write_text("".join(f"```python\n{block.strip()}\n```\n\n" for block in blocks))
    return path


def server_for(root: Path) -> execute.ForkServer | None:
    return execute._servers.get(execute._key(root, execute.child_env()))


def alive(pid: int) -> bool:
    try:
        with open(f"/proc/{pid}/stat") as f:
            return f.read().rsplit(")", 1)[1].split()[0] not in "ZX"
    except FileNotFoundError:
        return False


def gone(pid: int, within: float = 10.0) -> bool:
    deadline = time.monotonic() + within
    while alive(pid):
        if time.monotonic() > deadline:
            return False
        time.sleep(0.05)
    return True


@needs_fork
def test_forked_page_imports_as_a_fresh_interpreter(tmp_path):
    """After each import, sys.modules, os.environ and the warning filters are the same in
    a forked page as in a plain process: stashed modules come back with what they imported."""
    steps = ["pass", "import numpy", "import matplotlib.pyplot", "import mujoco", "import sw2sim", "import trimesh"]
    out = tmp_path / "out"
    for mode in ("forked", "plain"):
        blocks = [
            f"{step}\nimport json, os, sys, warnings\n"
            f"with open({str(out)!r} + '{mode}.{i}', 'w') as f:\n"
            "    json.dump({'modules': sorted(sys.modules), 'env': dict(os.environ),"
            " 'filters': [repr(w) for w in warnings.filters]}, f)"
            for i, step in enumerate(steps)
        ]
        (tmp_path / mode).mkdir()
        result = run_page(parse_page(page_file(tmp_path / mode, *blocks), ROOT), ROOT, fork=mode == "forked")
        assert result.ok, format_failure(result)
    for i, step in enumerate(steps):
        forked, plain = (json.loads(Path(f"{out}{mode}.{i}").read_text()) for mode in ("forked", "plain"))
        assert set(forked["modules"]) - set(plain["modules"]) == set(), step
        assert set(plain["modules"]) - set(forked["modules"]) == set(), step
        # the same but for each page's own temporary folder
        own = {name: (forked["env"].pop(name), plain["env"].pop(name))
               for name in execute.TEMP_VARIABLES}
        assert forked["env"] == plain["env"], step
        assert all(f.endswith("/tmp") and p.endswith("/tmp") and f != p
                   for f, p in own.values()), own
        assert forked["filters"] == plain["filters"], step
    assert "numpy" not in json.loads(Path(f"{out}forked.0").read_text())["modules"]


@needs_fork
def test_pages_are_forked_from_the_server(tmp_path):
    record = tmp_path / "record.json"
    page = parse_page(
        page_file(
            tmp_path,
            "import json, os, numpy\n"
            f"with open({str(record)!r}, 'a') as f:\n"
            "    print(json.dumps([os.getpid(), os.getppid(), os.getsid(0), numpy.random.randint(1 << 30)]), file=f)",
        ),
        ROOT,
    )
    before = server_for(ROOT).pages if server_for(ROOT) else 0
    for _ in range(2):
        assert run_page(page, ROOT, fork=True).ok
    server = server_for(ROOT)
    assert server.pages == before + 2
    first, second = (json.loads(line) for line in record.read_text().splitlines())
    assert first[1] == second[1] == server.pid  # forked by the server
    assert first[0] != second[0] and first[2] == first[0]  # a process and session of its own each
    assert first[3] != second[3]  # numpy's random state is not the server's


@pytest.mark.parametrize("fork", [True, False], ids=["forked", "plain"])
def test_process_group_is_killed_when_the_page_ends(tmp_path, fork):
    pid_file = tmp_path / "sleeper.pid"
    page = parse_page(
        page_file(
            tmp_path,
            "import subprocess\n"
            "sleeper = subprocess.Popen(['sleep', '60'])\n"
            f"open({str(pid_file)!r}, 'w').write(str(sleeper.pid))\n"
            "raise RuntimeError('failed with a process of its own still running')",
        ),
        ROOT,
    )
    result = run_page(page, ROOT, fork=fork)
    assert "RuntimeError: failed with a process" in result.failure.headline
    assert gone(int(pid_file.read_text()))


@pytest.mark.parametrize("fork", [True, False], ids=["forked", "plain"])
def test_what_a_page_puts_in_its_temporary_folder_goes_with_it(tmp_path, fork):
    """Each page gets a temporary folder of its own (the pages make scratch copies with
    tempfile.mkdtemp, and sw2sim unpacks zips there), removed when the page is done; a
    path inside it prints as one inside /tmp."""
    seen = tmp_path / "seen.txt"
    code = ("import tempfile\n"
            "scratch = tempfile.mkdtemp(prefix='page-scratch-')\n"
            f"open({str(seen)!r}, 'w').write(scratch)\n"
            "print(scratch)")
    results = [run_page(parse_page(page_file(tmp_path, code), ROOT), ROOT, fork=fork)
               for _ in range(2)]
    assert all(r.ok for r in results), [r.failure for r in results]
    scratch = Path(seen.read_text())
    assert str(scratch.parent) == results[-1].temp, "in the page's own folder"
    assert not scratch.exists(), "removed with the page"
    assert results[0].temp != results[1].temp, "a folder of its own for each page"
    [printed] = entries(results[-1].page, results[-1], ROOT)
    assert printed["output"].startswith("/tmp/page-scratch-")


def test_environment_variable_forces_a_plain_process(tmp_path, monkeypatch):
    monkeypatch.setenv(execute.FORK_VARIABLE, "0")
    record = tmp_path / "parent"
    page = parse_page(page_file(tmp_path, f"import os\nopen({str(record)!r}, 'w').write(str(os.getppid()))"), tmp_path)
    for _ in range(2):  # the second page would use a server if one had been started
        assert run_page(page, tmp_path).ok
        assert record.read_text() == str(os.getpid())
    assert server_for(tmp_path) is None


@needs_fork
def test_plain_process_when_the_server_cannot_start(tmp_path, monkeypatch, capsys):
    monkeypatch.setattr(execute, "server_command", lambda fd: [sys.executable, "-c", "print('no server here')"])
    page = parse_page(page_file(tmp_path, "import os\nx = 1"), tmp_path)
    assert run_page(page, tmp_path, fork=True).ok
    err = capsys.readouterr().err
    assert "fork server unusable, pages run in plain processes" in err and "no server here" in err
    assert run_page(page, tmp_path, fork=True).ok  # no second try, no second message
    assert capsys.readouterr().err == ""


OWNER = """
import os, sys, time
from pathlib import Path
from course.snippets import parse_page, run_page
from course.snippets.execute import _servers
page = parse_page(Path(sys.argv[1]), Path(sys.argv[2]))
assert run_page(page, Path(sys.argv[2]), fork=True).ok
print(next(iter(_servers.values())).pid, flush=True)
if sys.argv[3] == "hang":
    run_page(parse_page(Path(sys.argv[4]), Path(sys.argv[2])), Path(sys.argv[2]), fork=True)
"""


@needs_fork
@pytest.mark.parametrize("how", ["exits", "is killed"])
def test_no_process_left_when_the_owner_is_done(tmp_path, how):
    """The server stops when the runner's process exits, or dies: it kills its page processes."""
    quick = page_file(tmp_path, "x = 1")
    hung = tmp_path / "hung.md"
    pid_file = tmp_path / "page.pid"
    hung.write_text(f"```python\nimport os, time\nopen({str(pid_file)!r}, 'w').write(str(os.getpid()))\ntime.sleep(60)\n```\n")
    command = [sys.executable, "-c", OWNER, str(quick), str(tmp_path), "hang" if how == "is killed" else "exit", str(hung)]
    # the killed owner leaves its page's folder behind: in the test's folder, not /tmp
    scratch = tmp_path / "tmp"
    scratch.mkdir()
    env = {**os.environ, "TMPDIR": str(scratch)}
    owner = subprocess.Popen(command, cwd=ROOT, stdout=subprocess.PIPE, text=True, env=env)
    try:
        server = int(owner.stdout.readline())
        if how == "is killed":
            deadline = time.monotonic() + 60
            while not pid_file.exists() or not pid_file.read_text():
                assert time.monotonic() < deadline and owner.poll() is None
                time.sleep(0.05)
            page = int(pid_file.read_text())
            assert alive(page)
            owner.send_signal(signal.SIGKILL)
            assert gone(page)
        assert owner.wait(timeout=60) == (0 if how == "exits" else -signal.SIGKILL)
        assert gone(server)
    finally:
        owner.kill()
        owner.wait()
