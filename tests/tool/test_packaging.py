"""What `pip install .` gives: a wheel with the tool only, whose declared dependencies are
exactly what it imports, and that works with nothing else installed.

The installed wheel is tried in a fresh virtual environment that sees only the declared
dependencies and what they need in turn (linked from this environment, so no download):
a dependency missing from pyproject.toml is missing there too, and the commands fail.
"""

from __future__ import annotations

import ast
import os
import re
import shutil
import subprocess
import sys
import tomllib
import zipfile
from functools import cache
from importlib import metadata
from pathlib import Path

import pytest
from packaging.requirements import Requirement

from repository import EXAMPLES, ROOT

PYPROJECT = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))
# ROS 1 comes from Debian, never from pip: the lessons' ROS nodes import these.
ROS_MODULES = {"rospy", "std_msgs", "sensor_msgs", "geometry_msgs", "gazebo_msgs", "std_srvs",
               "control_msgs", "trajectory_msgs", "rosgraph", "roslaunch", "tf2_msgs",
               "rosgraph_msgs", "controller_manager_msgs", "rostopic"}
# ROS 2 comes from the `ros2` extra (requirements-ros2.txt), imported only where it is used.
ROS2_MODULES = {"rclpy", "builtin_interfaces", "rosidl_runtime_py", "catkin_pkg",
                "ament_index_python", "lifecycle_msgs", "rcl_interfaces"}


def normalise(name: str) -> str:
    return re.sub(r"[-_.]+", "-", name).lower()


def declared(requirements: list[str]) -> set[str]:
    return {normalise(Requirement(r).name) for r in requirements}


def local_modules() -> set[str]:
    """Names this repository itself provides: its packages, and the scripts and helpers that
    import each other by file name (lesson scripts, test helpers)."""
    names = {p.stem for p in ROOT.rglob("*.py") if not _ignored(p)}
    return names | {"sw2sim", "course"}


def _ignored(path: Path) -> bool:
    parts = path.relative_to(ROOT).parts
    # (build/ is what `pip install .` leaves, .cache/ what make and the tools keep: copies)
    return parts[0] in (".venv", ".venv-ros2", "node_modules", "_site", ".git", "build",
                        ".cache") or "__pycache__" in parts


def imported_modules(*folders: str) -> set[str]:
    """Top-level names imported anywhere in the folders' Python files, without the
    standard library, this repository's own modules and ROS."""
    found: set[str] = set()
    for folder in folders:
        for file in (ROOT / folder).rglob("*.py"):
            if _ignored(file):
                continue
            for node in ast.walk(ast.parse(file.read_bytes(), str(file))):
                if isinstance(node, ast.Import):
                    found.update(alias.name.split(".")[0] for alias in node.names)
                elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
                    found.add(node.module.split(".")[0])
    return (found - set(sys.stdlib_module_names) - local_modules() - ROS_MODULES - ROS2_MODULES
            - {"__future__"})


@cache
def _providers() -> dict[str, list[str]]:
    return metadata.packages_distributions()


@cache
def distribution_of(module: str) -> str:
    """The installed distribution that provides a top-level module."""
    names = _providers().get(module, [])
    if not names:  # a lone extension module (manifold3d) is not in top_level.txt
        for dist in metadata.distributions():
            if any(f.parts and f.parts[0].split(".")[0] == module for f in dist.files or []):
                names = [dist.metadata["Name"]]
                break
    assert names, f"no installed distribution provides {module!r}"
    same = [n for n in names if normalise(n) == normalise(module)]
    return normalise((same or names)[0])


def distributions(modules: set[str]) -> set[str]:
    return {distribution_of(m) for m in modules}


def test_the_tools_dependencies_are_exactly_what_it_imports():
    needed = distributions(imported_modules("sw2sim"))
    listed = declared(PYPROJECT["project"]["dependencies"])
    assert needed == listed, (f"imported but not declared: {sorted(needed - listed)}; "
                              f"declared but not imported: {sorted(listed - needed)}")


def test_the_course_and_the_tests_declare_what_they_import_in_their_extras():
    tool = declared(PYPROJECT["project"]["dependencies"])
    extras = PYPROJECT["project"]["optional-dependencies"]
    course = declared(extras["course"])
    test = declared(extras["test"])
    missing = distributions(imported_modules("course", "examples")) - tool - course
    assert not missing, f"the course imports these; add them to the `course` extra: {sorted(missing)}"
    missing = distributions(imported_modules("tests", "tools")) - tool - course - test
    assert not missing, f"the tests import these; add them to the `test` extra: {sorted(missing)}"
    assert not (course & tool) and not (test & (tool | course)), "a package listed twice"


# A page's ```python block, with the attribute line after its closing fence if it has one.
PAGE_BLOCK = re.compile(r"^```python[ \t]*\n(?P<code>.*?)^```[ \t]*\n(?P<attributes>\{:[^\n]*\})?", re.M | re.S)


def page_imports() -> dict[str, set[str]]:
    """Top-level names the pages' runnable Python blocks import (not those marked
    data-skip or data-ros, nor include_code blocks: their files are under examples/), each
    with the pages that import it; without the standard library, this repository and ROS."""
    found: dict[str, set[str]] = {}
    for page in sorted((ROOT / "_pages").rglob("*.md")):
        for block in PAGE_BLOCK.finditer(page.read_text(encoding="utf-8")):
            attributes = block["attributes"] or ""
            if "data-skip" in attributes or "data-ros" in attributes or block["code"].lstrip().startswith("{%"):
                continue
            for node in ast.walk(ast.parse(block["code"])):
                names = ([alias.name for alias in node.names] if isinstance(node, ast.Import) else
                         [node.module] if isinstance(node, ast.ImportFrom) and node.level == 0 and node.module
                         else [])
                for name in names:
                    found.setdefault(name.split(".")[0], set()).add(page.relative_to(ROOT).as_posix())
    ignored = set(sys.stdlib_module_names) | local_modules() | ROS_MODULES | {"__future__"}
    return {name: pages for name, pages in found.items() if name not in ignored}


def test_the_course_extra_holds_what_the_lessons_import():
    """`pip install ".[course]"` is all a reader needs for the pages' Python, on any system."""
    modules = page_imports()
    assert {"mujoco", "numpy", "yourdfpy"} <= set(modules), f"the blocks were not found: {sorted(modules)}"
    extras = PYPROJECT["project"]["optional-dependencies"]
    covered = declared(PYPROJECT["project"]["dependencies"]) | declared(extras["course"])
    missing = {module: sorted(pages) for module, pages in modules.items() if distribution_of(module) not in covered}
    assert not missing, f"the pages import these; add them to the `course` extra: {missing}"


def test_every_declared_package_is_pinned_in_requirements_txt():
    pinned = {normalise(line.split("==")[0]) for line in
              (ROOT / "requirements.txt").read_text(encoding="utf-8").splitlines()
              if "==" in line and not line.startswith("#")}
    extras = PYPROJECT["project"]["optional-dependencies"]
    everything = declared(PYPROJECT["project"]["dependencies"] + extras["course"] + extras["test"])
    assert everything <= pinned, f"not pinned: {sorted(everything - pinned)}"


def test_the_ros2_extra_is_what_requirements_ros2_txt_pins():
    """`pip install ".[ros2]"` and `make setup` install the same ROS 2 set."""
    lines = (ROOT / "requirements-ros2.txt").read_text(encoding="utf-8").splitlines()
    pinned = {normalise(line.split("==")[0]) for line in lines
              if "==" in line and not line.startswith("#")}
    extra = declared(PYPROJECT["project"]["optional-dependencies"]["ros2"])
    assert pinned and extra == pinned, (sorted(extra - pinned), sorted(pinned - extra))


@pytest.fixture(scope="module")
def wheel(tmp_path_factory) -> Path:
    """The wheel `pip install .` builds, made offline with the pinned setuptools."""
    out = tmp_path_factory.mktemp("wheel")
    # Built from a copy of what the sdist holds, so that setuptools' build/ folder stays
    # out of the repository.
    source = tmp_path_factory.mktemp("source")
    for name in ("pyproject.toml", "README.md", "LICENSE"):
        shutil.copy(ROOT / name, source / name)
    shutil.copytree(ROOT / "sw2sim", source / "sw2sim",
                    ignore=shutil.ignore_patterns("__pycache__"))
    done = subprocess.run([sys.executable, "-m", "pip", "wheel", "--no-deps", "--no-build-isolation",
                           "--disable-pip-version-check", "-q", "-w", str(out), str(source)],
                          capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    (built,) = out.glob("sw2sim-*.whl")
    return built


def test_the_wheel_holds_the_tool_and_nothing_of_the_course(wheel):
    names = zipfile.ZipFile(wheel).namelist()
    tops = {n.split("/")[0] for n in names}
    assert tops == {"sw2sim", next(t for t in tops if t.endswith(".dist-info"))}, tops
    shipped = {n for n in names if n.endswith(".py")}
    assert shipped == {p.relative_to(ROOT).as_posix() for p in (ROOT / "sw2sim").rglob("*.py")}
    for name in shipped:
        tree = ast.parse(zipfile.ZipFile(wheel).read(name))
        for node in ast.walk(tree):
            if isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
                assert node.module.split(".")[0] != "course", f"{name} imports the course build"
            if isinstance(node, ast.Import):
                assert all(a.name.split(".")[0] != "course" for a in node.names), name


def _closure(requirements: list[str]) -> list[metadata.Distribution]:
    """The installed distributions the requirements need, with what those need in turn."""
    seen: dict[str, metadata.Distribution] = {}
    todo = [Requirement(r) for r in requirements]
    while todo:
        req = todo.pop()
        if req.marker is not None and not req.marker.evaluate({"extra": ""}):
            continue
        name = normalise(req.name)
        if name in seen:
            continue
        seen[name] = dist = metadata.distribution(req.name)
        todo.extend(Requirement(r) for r in dist.requires or [])
    return list(seen.values())


@pytest.fixture(scope="module")
def fresh_venv(wheel, tmp_path_factory) -> Path:
    """A new virtual environment holding the wheel and nothing else; its bin/ folder."""
    root = tmp_path_factory.mktemp("fresh")
    subprocess.run([sys.executable, "-m", "venv", "--without-pip", str(root / "venv")], check=True)
    python = root / "venv" / "bin" / "python"
    subprocess.run([sys.executable, "-m", "pip", "--python", str(python), "install", "-q",
                    "--disable-pip-version-check", "--no-deps", "--no-index", str(wheel)],
                   check=True, capture_output=True)
    return python.parent


def _dependencies(farm: Path, requirements: list[str]) -> Path:
    """A folder linking to exactly the installed files of `requirements` and their own
    dependencies, for the fresh environment's path."""
    farm.mkdir()
    for dist in _closure(requirements):
        site = Path(dist.locate_file(""))
        for top in {f.parts[0] for f in dist.files or [] if f.parts and f.parts[0] != ".."}:
            if (site / top).exists() and not (farm / top).exists() and not top.endswith(".pth"):
                (farm / top).symlink_to(site / top)
    return farm


def _sw2sim(bin_dir: Path, dependencies: Path, cwd: Path, *args: str) -> subprocess.CompletedProcess:
    # As a new shell would have it, but for the dependencies: the installed tool chooses its
    # own GL platform.
    env = {k: v for k, v in os.environ.items()
           if not k.startswith(("PYTHON", "VIRTUAL_ENV")) and k != "MUJOCO_GL"}
    env["PATH"] = f"{bin_dir}{os.pathsep}{env.get('PATH', '')}"
    env["PYTHONPATH"] = str(dependencies)
    return subprocess.run([str(bin_dir / args[0]), *args[1:]], cwd=cwd, env=env,
                          capture_output=True, text=True, timeout=300)


def test_pip_install_gives_a_working_check_convert_and_render(fresh_venv, tmp_path):
    dependencies = _dependencies(tmp_path / "dependencies", PYPROJECT["project"]["dependencies"])
    package = EXAMPLES / "example_3"
    done = _sw2sim(fresh_venv, dependencies, tmp_path, "sw2sim", "check", str(package))
    assert done.returncode == 0, done.stdout + done.stderr
    done = _sw2sim(fresh_venv, dependencies, tmp_path, "sw2sim", "convert", str(package), "-o", "model")
    assert done.returncode == 0, done.stdout + done.stderr
    assert (tmp_path / "model" / "scene.xml").is_file()
    done = _sw2sim(fresh_venv, dependencies, tmp_path, "sw2sim", "render", str(package), "-o", "picture.png")
    assert done.returncode == 0, done.stdout + done.stderr
    assert (tmp_path / "picture.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    # Nothing of the course came along.
    where = _sw2sim(fresh_venv, dependencies, tmp_path, "python", "-c", "import course")
    assert where.returncode != 0 and "No module named 'course'" in where.stderr


def test_the_fresh_install_check_fails_when_a_dependency_is_left_out(fresh_venv, tmp_path):
    # The same check with PyYAML left out: convert reads the controllers' YAML and must fail.
    # (xacro goes too: it needs PyYAML itself, and would bring it back.)
    without = [r for r in PYPROJECT["project"]["dependencies"]
               if normalise(Requirement(r).name) not in ("pyyaml", "xacro")]
    dependencies = _dependencies(tmp_path / "dependencies", without)
    done = _sw2sim(fresh_venv, dependencies, tmp_path, "sw2sim", "convert", str(EXAMPLES / "example_3"),
                   "-o", "model")
    assert done.returncode != 0 and "yaml" in (done.stdout + done.stderr)
