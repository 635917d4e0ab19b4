"""Print how long the expensive parts of `make test` take on this machine.

    .venv/bin/python tools/benchmark.py                 # models, drawings, pages, figures
    .venv/bin/python tools/benchmark.py pages tests     # only these sections

Sections: `models` (load, compile, step rate of each example), `drawings` (each part and
assembly drawing), `pages` (each lesson page in a fresh process, as
tests/course/test_pages.py runs them), `figures` (each figure made as `make media` makes
it, and whether the tests would make it again: they do only when the manifest cannot vouch
for the committed file), `tests` (each test file in a pytest of its own), `commands` (each
`sw2sim` command in a fresh process, as a user types it: `check` three times on every
example package and on packages of every shape tools/check_packages.py writes, COLLADA,
OBJ, text STL, 40 links, 200,000 triangles, with the median and the worst, first as a
user's `pip install .` runs it (in a venv of its own, ~/.cache/sw2sim/benchmark-user-venv),
then in the project's .venv; `convert`, `render`), `runner` (every lesson page through the
page runner, its processes plain and then forked from the fork server, side by side with
`jupyter nbconvert --execute` over the same pages' notebooks; not in the default set),
`load` (`check` on the same packages as a user installs it, first alone, then with 4
other jobs each keeping a core busy, as a class's CI runs many checks at once; not in the
default set), `ros` (the whole test suite as `make test` runs it, with and without tests/ros, in pairs:
what the ROS tests add; not in the default set, it takes some ten minutes), `ros2` (the
same for tests/ros2 and tests/tool/port, the ROS 2 tests), `browser` (each practice's
Simulate mode in headless Chromium on the built site: download, time to the first simulated
frame, real-time factor; not in the default set), `ctrl-c` (each lesson node that runs until
Ctrl-C, stopped 50 times with SIGINT beside `sw2sim ros2` and two busy processes, counting
the stops that printed a traceback or ended with another status than 0: they must be none;
not in the default set, some five minutes).

Figures, not assertions: compare them before and after a change (2-core machines are the
target). Each line shows CPU seconds as well as wall-clock seconds: on a busy machine the
wall clock says more about the other processes than about this code. Nothing here is run
by the tests.
"""

import json
import os
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

# The environment before `import sw2sim` below chooses a GL platform for this process
# (MUJOCO_GL, PYOPENGL_PLATFORM): test runs get this one, as under `make test`, so that
# each of their processes makes its own choice.
ORIGINAL_ENVIRONMENT = dict(os.environ)

# The course build is found by folder: run as tools/benchmark.py, this file's folder is on
# sys.path instead of the repository.
sys.path.insert(1, str(Path(__file__).resolve().parent.parent))

import sw2sim  # noqa: E402
import mujoco
from course.drawing import assembly_drawing_svg, part_drawing_svg
from course.media import all_figures, cores, is_current, read_manifest
from course.practices import PRACTICES, ROOT, design, package_dir
from course.snippets import find_pages, format_failure, parse_page, run_page
from course.snippets import execute as snippets

DEFAULT = ("models", "drawings", "pages", "figures")


def cpu_seconds() -> float:
    """CPU time of this process (all its threads) and of the children it has waited for."""
    own = resource.getrusage(resource.RUSAGE_SELF)
    children = resource.getrusage(resource.RUSAGE_CHILDREN)
    return own.ru_utime + own.ru_stime + children.ru_utime + children.ru_stime


class Section:
    """Timed lines under a heading, and their total."""

    def __init__(self, title: str):
        self.cpu = self.wall = 0.0
        print(f"== {title}")
        print(f"{'':60} {'cpu':>7}   {'wall':>7}")

    def timed(self, label: str, fn, *args, note: str = "", **kwargs):
        cpu, wall = cpu_seconds(), time.perf_counter()
        result = fn(*args, **kwargs)
        cpu, wall = cpu_seconds() - cpu, time.perf_counter() - wall
        self.cpu += cpu
        self.wall += wall
        print(f"{label:60} {cpu:7.2f} s {wall:7.2f} s  {note}".rstrip(), flush=True)
        return result

    def total(self) -> None:
        print(f"{'total':60} {self.cpu:7.2f} s {self.wall:7.2f} s\n")


def models() -> None:
    section = Section("models")
    for practice in PRACTICES:
        pkg = package_dir(practice)
        spec = section.timed(f"load_package {pkg.name}", sw2sim.load_package, pkg)
        model = section.timed(f"compile {pkg.name}", spec.compile)
        data = mujoco.MjData(model)
        steps = 5000
        start = time.perf_counter()
        mujoco.mj_step(model, data, nstep=steps)
        rate = steps / (time.perf_counter() - start)
        real_time = rate * model.opt.timestep
        print(f"{'step rate ' + pkg.name:60} {rate:7.0f} steps/s ({real_time:.0f}x real time)")
    section.total()


def drawings() -> None:
    section = Section("drawings (tests/course/test_drawing.py and the practices' tests draw these)")
    for practice in PRACTICES:
        module = design(practice)
        for part in module.parts():
            section.timed(f"{practice} part {part.name}", part_drawing_svg, part)
        section.timed(f"{practice} assembly", assembly_drawing_svg, module.robot())
    section.total()


def pages() -> None:
    section = Section("pages (each in a fresh process; the tests run a few at once)")
    for page_path in find_pages(ROOT):
        page = parse_page(page_path, ROOT)
        result = section.timed(str(page_path.relative_to(ROOT)), run_page, page, ROOT)
        if not result.ok:
            print("   failed")
    section.total()


def figures() -> None:
    section = Section("figures (made in this process; 'remade' = the tests would make it again)")
    manifest = read_manifest()
    tmp = Path("/tmp/sw2sim-benchmark")
    tmp.mkdir(exist_ok=True)
    for fig in all_figures():
        note = "" if is_current(fig, manifest) else "remade"
        section.timed(fig.output, fig.make, tmp / fig.path.name, note=note)
    section.total()


def make_test_environment() -> dict[str, str]:
    """The environment `make test` runs pytest in (Makefile): this process's before it
    chose a GL platform, compiled modules kept in .cache/pycache."""
    env = dict(ORIGINAL_ENVIRONMENT)
    env.pop("PYTHONDONTWRITEBYTECODE", None)
    env.setdefault("PYTHONPYCACHEPREFIX", str(ROOT / ".cache" / "pycache"))
    return env


def tests() -> None:
    section = Section("test files (each in a pytest of its own)")
    for path in sorted((ROOT / "tests").rglob("test_*.py")):
        command = [sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", str(path)]
        done = section.timed(str(path.relative_to(ROOT)), subprocess.run, command, cwd=ROOT,
                             capture_output=True, text=True, env=make_test_environment())
        if done.returncode != 0:
            print(f"   exit status {done.returncode}")
    section.total()


ROS_ROUNDS = 2   # pairs of whole runs: the figure varies by several seconds from run to run


def _share_of(folders: list[str], what: str) -> None:
    """What the tests in `folders` add to `make test`: the whole suite as `make test` runs
    it (a worker per core, in its environment), with and without them, in pairs that take
    turns going first."""
    jobs = str(cores())   # the Makefile's TEST_JOBS (auto)
    section = Section(f"{what}' share of `make test` (pytest -n {jobs} --dist loadscope)")
    command = [sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", "-n", jobs,
               "--dist", "loadscope"]
    added = []
    folder = " and ".join(folders)
    runs = [(f"without {folder}", [f"--ignore={f}" for f in folders]), (f"with {folder}", [])]
    for round_ in range(1, ROS_ROUNDS + 1):
        walls = {}
        # each kind of run goes first in every other round: a run right after another
        # may find the machine slower
        for label, extra in (runs if round_ % 2 else runs[::-1]):
            start = time.perf_counter()
            done = section.timed(f"round {round_}: {label}", subprocess.run, [*command, *extra],
                                 cwd=ROOT, capture_output=True, text=True,
                                 env=make_test_environment())
            walls[label] = time.perf_counter() - start
            if done.returncode != 0:
                print(f"   exit status {done.returncode}: {done.stdout.strip().splitlines()[-1:]}")
        added.append(walls[f"with {folder}"] - walls[f"without {folder}"])
        print(f"{f'round {round_}: added by {folder}':60} {'':9} {added[-1]:7.2f} s", flush=True)
    print(f"{f'added by {folder}, mean of the rounds':60} {'':9} {sum(added) / len(added):7.2f} s\n")


def ros() -> None:
    """What the ROS 1 tests add to `make test`."""
    _share_of(["tests/ros"], "the ROS 1 tests")


def ros2() -> None:
    """What the ROS 2 tests add to `make test`: tests/ros2 (the stand-in, the pages' rclpy
    nodes) and tests/tool/port (the ported packages, built with colcon)."""
    _share_of(["tests/ros2", "tests/tool/port"], "the ROS 2 tests")


CTRL_C_STOPS = 50


def ctrl_c() -> None:
    """Each lesson node that runs until Ctrl-C (tests/ros2/ctrl_c.py), in its ported package
    against `sw2sim ros2`, stopped CTRL_C_STOPS times with SIGINT at a random moment of its
    loop, while two processes keep both cores busy."""
    import random
    import signal
    sys.path[:0] = [str(ROOT / "tests"), str(ROOT / "tests" / "ros2")]
    import ctrl_c as stops
    import ros2_domains
    from course.snippets.ros2 import node_blocks
    from sw2sim.port import port
    from sw2sim.ros2.discovery import environment
    python = ROOT / ".venv-ros2" / "bin" / "python"
    if not python.exists():
        print("== ctrl-c: no .venv-ros2 (make setup)\n")
        return
    section = Section(f"ctrl-c: each lesson node stopped {CTRL_C_STOPS} times, 2 busy processes")
    blocks = node_blocks(ROOT)
    wheels = "front_left_joint,front_right_joint,rear_left_joint,rear_right_joint"
    busy = [subprocess.Popen([sys.executable, "-c", "while True: pass"]) for _ in range(2)]
    rng = random.Random(1)
    failed = 0
    try:
        with tempfile.TemporaryDirectory() as top:
            for package, file in stops.NODES:
                folder = Path(top) / package
                port(ROOT / "examples" / package, folder,
                     effort_joints=[wheels] if package == "example_1" else ())
                node = folder / file
                node.parent.mkdir(parents=True, exist_ok=True)
                node.write_text(blocks[f"{package}/{file}"].code, encoding="utf-8")
                command = [str(python), str(node), "--ros-args", "-p", "use_sim_time:=true"]
                domain = ros2_domains.claim()
                env = environment(domain.id, {**ORIGINAL_ENVIRONMENT, "PYTHONUNBUFFERED": "1",
                                              "ROS_HOME": str(Path(top) / "ros")})
                standin = subprocess.Popen([str(python), "-m", "sw2sim", "ros2", str(folder),
                                            "--realtime", "1"], env=env, start_new_session=True,
                                           stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
                faults = []
                try:
                    section.timed(f"{package}/{file}", lambda: faults.extend(
                        f for f in (stops.stop_once(command, env, folder, rng)
                                    for _ in range(CTRL_C_STOPS)) if f))
                finally:
                    os.killpg(standin.pid, signal.SIGINT)
                    standin.wait(timeout=20)
                    domain.release()
                print(f"    {len(faults)} of {CTRL_C_STOPS} stops printed a traceback or ended "
                      "with another status than 0", flush=True)
                for fault in faults[:3]:
                    print("    " + fault[-1500:].replace("\n", "\n    "))
                failed += len(faults)
    finally:
        for process in busy:
            process.kill()
            process.wait()
    section.total()
    print(f"{'stops with a fault, all nodes':60} {failed}\n")


def _sw2sim(*args: str, python: str = sys.executable) -> subprocess.CompletedProcess:
    """One `sw2sim` command in a fresh Python, as typed in a terminal after an install: in
    the environment this process was given before `import sw2sim` above chose a GL platform
    for it, with Python's compiled modules kept (make_test_environment)."""
    return subprocess.run([python, "-m", "sw2sim", *args], cwd=ROOT,
                          capture_output=True, text=True, env=make_test_environment())


# A virtual environment with nothing but the tool, as the README's `python -m pip install .`
# makes it for a user. The project's .venv holds far more (the course's libraries, Jupyter,
# ROS's path file, a hundred distributions that MuJoCo's import looks through for plugins),
# and is installed in editable mode. It lies outside the repository, whose tests read every
# Python file in it; pip's build/ folder is removed after each install.
USER_VENV = Path.home() / ".cache" / "sw2sim" / "benchmark-user-venv"


def user_install() -> str:
    """The Python of USER_VENV, with the tool as it is now installed into it (made on first
    use; the tool itself installed again on every run)."""
    python = USER_VENV / "bin" / "python"
    quiet = {"cwd": ROOT, "check": True, "capture_output": True}
    if not python.is_file():
        subprocess.run([sys.executable, "-m", "venv", str(USER_VENV)], **quiet)
    subprocess.run([str(python), "-m", "pip", "install", "-q", "."], **quiet)
    subprocess.run([str(python), "-m", "pip", "install", "-q", "--no-deps", "--force-reinstall",
                    "."], **quiet)
    shutil.rmtree(ROOT / "build", ignore_errors=True)
    return str(python)


CHECK_ROUNDS = 3   # runs of `check` per package: the machine may be busy during any one


def _timed_checks(packages: dict[str, Path], python: str, where: str) -> None:
    """`sw2sim check` on each package CHECK_ROUNDS times, with `python`: per package its CPU
    and wall seconds (median of the runs, and the slowest wall), then the median and the
    worst over all packages. The check's targets: 0.5 s median, 2 s worst."""
    print(f"{'check ' + where + ' (median of ' + str(CHECK_ROUNDS) + ' runs)':60} {'cpu':>7}   "
          f"{'wall':>7}   {'slowest':>7}   findings")
    _sw2sim("check", str(next(iter(packages.values()))), python=python)   # compiles, untimed
    medians, worst = [], []
    for label, package in packages.items():
        runs = []
        for _ in range(CHECK_ROUNDS):
            cpu, wall = cpu_seconds(), time.perf_counter()
            done = _sw2sim("check", "--json", str(package), python=python)
            runs.append((cpu_seconds() - cpu, time.perf_counter() - wall))
        cpus, walls = sorted(r[0] for r in runs), sorted(r[1] for r in runs)
        cpu, wall = cpus[len(cpus) // 2], walls[len(walls) // 2]
        medians.append((cpu, wall))
        worst.append((cpus[-1], walls[-1]))
        try:
            rules = sorted({f["rule"] for f in json.loads(done.stdout)["findings"]})
            said = f"exit {done.returncode}: {', '.join(rules) or 'none'}"
        except (ValueError, KeyError):
            said = f"exit {done.returncode}: {done.stderr.strip()[-120:]}"
        print(f"{'check ' + label:60} {cpu:7.2f} s {wall:7.2f} s {walls[-1]:7.2f} s  {said}",
              flush=True)
    print(f"{'check, median over the ' + str(len(medians)) + ' packages':60} "
          f"{statistics.median(c for c, _ in medians):7.2f} s "
          f"{statistics.median(w for _, w in medians):7.2f} s")
    print(f"{'check, the most any run took':60} {max(c for c, _ in worst):7.2f} s "
          f"{max(w for _, w in worst):7.2f} s\n")


# The load a class's CI puts beside one check: this many other jobs, each keeping a core busy.
OTHER_JOBS = 4


class busy:
    """`jobs` processes that each keep a core busy while the block runs (Python loops of their
    own, started and stopped here by their process ids)."""

    def __init__(self, jobs: int):
        self.jobs, self.processes = jobs, []

    def __enter__(self):
        for _ in range(self.jobs):
            self.processes.append(subprocess.Popen([sys.executable, "-c", "while True: pass"]))
        return self

    def __exit__(self, *exc):
        for process in self.processes:
            process.kill()
        for process in self.processes:
            process.wait()


def load() -> None:
    """`sw2sim check` on every package shape while OTHER_JOBS other jobs run: the targets
    (0.5 s median, 2 s at most) hold on a machine a class's CI keeps busy."""
    from check_packages import all_shapes   # tools/, beside this file; writes with trimesh
    Section(f"sw2sim check with {OTHER_JOBS} other jobs running (targets: 0.5 s median, "
            "2 s worst)")
    with tempfile.TemporaryDirectory() as scratch:
        packages = {str(package_dir(p).relative_to(ROOT)): package_dir(p) for p in PRACTICES}
        packages.update(all_shapes(Path(scratch) / "shapes"))
        python = user_install()
        _timed_checks(packages, python, "as a user installs it, unloaded")
        with busy(OTHER_JOBS):
            _timed_checks(packages, python, f"as a user installs it, {OTHER_JOBS} other jobs")


def commands() -> None:
    from check_packages import all_shapes   # tools/, beside this file; writes with trimesh
    section = Section("sw2sim commands (each in a fresh process; check's target: 0.5 s "
                      "median, 2 s worst)")
    with tempfile.TemporaryDirectory() as scratch:
        scratch = Path(scratch)
        packages = {str(package_dir(p).relative_to(ROOT)): package_dir(p) for p in PRACTICES}
        packages.update(all_shapes(scratch / "shapes"))
        start = time.perf_counter()
        python = user_install()
        where = f"~/{USER_VENV.relative_to(Path.home())}"
        print(f"{'(pip install . into ' + where + ', untimed)':60} "
              f"{'':9} {time.perf_counter() - start:7.2f} s")
        _timed_checks(packages, python, "as a user installs it")
        _timed_checks(packages, sys.executable, "in the project's .venv")
        pkg = package_dir(PRACTICES[-1])
        section.timed(f"convert {pkg.relative_to(ROOT)}", _sw2sim, "convert", str(pkg), "-o",
                      str(scratch / "converted"))
        section.timed(f"render {pkg.relative_to(ROOT)}", _sw2sim, "render", str(pkg), "-o",
                      str(scratch / "picture.png"))
    section.total()


def runner() -> None:
    """The page runner against nbconvert, on the same machine and the same pages.

    (a) every lesson page that has a notebook, one after the other, each in a process of its
    own as run_page makes it: first plain subprocesses (the runner before the fork server),
    then with the fork server (started by the first page, which runs plain meanwhile, and
    stopped at the end: both inside the timing, and its CPU counted once it is reaped);
    (b) ONE `jupyter nbconvert --to notebook --execute` command over all their notebooks
    (nbconvert starts a fresh kernel per notebook, in notebooks/, so that the notebooks'
    first cell finds the repository). A notebook that fails is reported, and it and its
    page are left out of both sides (nbconvert is then timed again without them).
    """
    notebook_dir = ROOT / "notebooks"
    notebooks = {}  # page -> notebook
    for path in sorted(notebook_dir.glob("*.ipynb")):
        page = json.loads(path.read_text(encoding="utf-8"))["metadata"].get("sw2sim", {}).get("page")
        if page and (ROOT / page).is_file():
            notebooks[page] = path
        else:
            print(f"   {path.relative_to(ROOT)}: no lesson page of its own, left out")
    jupyter = Path(sys.executable).with_name("jupyter")

    def nbconvert(paths: list[Path]) -> tuple[subprocess.CompletedProcess[str], Path]:
        out = Path(tempfile.mkdtemp(prefix="benchmark-nbconvert-"))
        command = [str(jupyter), "nbconvert", "--to", "notebook", "--execute", "--allow-errors",
                   "--output-dir", str(out), *(p.name for p in paths)]
        return subprocess.run(command, cwd=notebook_dir, capture_output=True, text=True), out

    def failed_notebooks(done: subprocess.CompletedProcess[str], out: Path, paths: list[Path]) -> dict[Path, str]:
        failed = {}
        for path in paths:
            result = out / path.name
            if not result.is_file():
                failed[path] = f"no output (nbconvert exit status {done.returncode}): {done.stderr.strip()[-300:]}"
                continue
            cells = json.loads(result.read_text(encoding="utf-8"))["cells"]
            errors = [o for c in cells if c["cell_type"] == "code" for o in c.get("outputs", ())
                      if o.get("output_type") == "error"]
            if errors:
                failed[path] = f"{errors[0]['ename']}: {errors[0]['evalue']}"[:300]
        return failed

    section = Section(f"runner vs nbconvert ({len(notebooks)} pages and their notebooks)")
    paths = list(notebooks.values())
    done, out = section.timed(f"nbconvert --execute, one command, {len(paths)} notebooks", nbconvert, paths)
    failed = failed_notebooks(done, out, paths)
    for path, why in failed.items():
        print(f"   failed, left out of both sides: {path.relative_to(ROOT)}: {why}")
    nb_cpu, nb_wall = section.cpu, section.wall
    if failed:
        paths = [p for p in paths if p not in failed]
        notebooks = {page: nb for page, nb in notebooks.items() if nb in paths}
        section.cpu = section.wall = 0.0
        done, out = section.timed(f"nbconvert --execute again, {len(paths)} notebooks", nbconvert, paths)
        nb_cpu, nb_wall = section.cpu, section.wall

    def run_all(fork: bool | None) -> int:
        failures = 0
        for page_path in notebooks:
            result = run_page(parse_page(ROOT / page_path, ROOT), ROOT, fork=fork)
            if not result.ok:
                failures += 1
                print(f"   page failed: {format_failure(result).splitlines()[0]}")
        if fork is not False:
            snippets.shutdown()  # reaps the server: its CPU and its pages' reach this process
        return failures

    measured = {}
    for label, fork in (("plain subprocesses (before)", False), ("fork server (after)", None)):
        section.cpu = section.wall = 0.0
        section.timed(f"runner, {len(notebooks)} pages, {label}", run_all, fork)
        measured[label] = (section.cpu, section.wall)
    print()
    for label, (cpu, wall) in measured.items():
        print(f"{'nbconvert / runner with ' + label:60} {nb_cpu / cpu:6.1f}x   {nb_wall / wall:6.1f}x  (cpu, wall)")
    print()


def browser() -> None:
    """Each practice's Simulate mode in headless Chromium, on the built site (_site, or
    $SW2SIM_SITE): the bytes it downloads after the press, raw and gzipped (level 6, as the
    tests' server compresses text), the time from the press to the first simulated frame,
    and the real-time factor of stepping 10 s at once."""
    import gzip

    from playwright.sync_api import sync_playwright

    sys.path.insert(0, str(ROOT / "tests/site/browser"))
    from site_server import SiteServer

    site = Path(os.environ.get("SW2SIM_SITE") or ROOT / "_site")
    pages = {n: f"practice-{n}/modelling/" for n in range(1, 6)
             if (site / f"media/practice-{n}/simulate.json").is_file()}
    server = SiteServer(site, ROOT / "node_modules")
    args = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage"]
    viewer = "document.querySelector('.model-viewer')"
    try:
        with sync_playwright() as playwright:
            chromium = playwright.chromium.launch(executable_path="/usr/bin/chromium", args=args)
            for practice, path in pages.items():
                page = chromium.new_page()
                page.goto(server.base_url + path)
                page.get_by_role("button", name="Turn the model in 3D").click()
                page.get_by_role("button", name="Simulate").wait_for()
                fetched = []
                page.on("requestfinished", lambda request: fetched.append(request.url))
                start = time.perf_counter()
                page.get_by_role("button", name="Simulate").click()
                page.wait_for_function(f"() => {viewer}.simulation")
                page.evaluate(f"() => {viewer}.simulation.ready")
                ready = time.perf_counter() - start
                speed = page.evaluate(f"() => {viewer}.simulation.run(10)")
                files = [site / url.removeprefix(server.base_url) for url in fetched]
                raw = sum(f.stat().st_size for f in files if f.is_file())
                packed = sum(len(gzip.compress(f.read_bytes(), 6)) for f in files if f.is_file())
                print(f"{'Simulate practice ' + str(practice):60} {ready:5.2f} s to the first frame, "
                      f"{speed:5.1f}x real time, {len(files)} files {raw / 1e6:.2f} MB "
                      f"({packed / 1e6:.2f} MB gzipped)")
                page.close()
            chromium.close()
    finally:
        server.close()


SECTIONS = {"commands": commands, "models": models, "drawings": drawings, "pages": pages, "figures": figures,
            "tests": tests, "runner": runner, "ros": ros, "ros2": ros2, "load": load,
            "browser": browser, "ctrl-c": ctrl_c}


def main(argv: list[str]) -> int:
    chosen = argv or list(DEFAULT)
    unknown = [name for name in chosen if name not in SECTIONS]
    if unknown:
        print(f"unknown sections {unknown}; choose from {', '.join(SECTIONS)}", file=sys.stderr)
        return 2
    load, n = os.getloadavg()[0], cores()
    print(f"load average {load:.1f} on {n} cores"
          + ("  (busy: trust the cpu column, not the wall clock)" if load > 0.5 * n else ""))
    for name in chosen:
        SECTIONS[name]()
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
