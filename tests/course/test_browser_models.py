"""The models of the site's Simulate mode: built as the Python lessons build them, in a form
both MuJoCo versions read, and loaded by the browser's version (under Node)."""

import json
import re
import shutil
import subprocess

import mujoco
import numpy as np
import pytest

from course import browser_models
from course.practices import ROOT
from sw2sim.browser_model import BROWSER_MUJOCO, PYTHON_MUJOCO, browser_form
from sw2sim.convert import convert

NODE = shutil.which("node")
BROWSER_PACKAGE = ROOT / "node_modules/@mujoco/mujoco"
needs_node = pytest.mark.skipif(
    NODE is None or not (BROWSER_PACKAGE / "mujoco.wasm").is_file(),
    reason="Node.js or node_modules/@mujoco/mujoco is missing (make setup installs them)")

# One Node process loads every model it is given ({name: {"files": {path: text or base64},
# "model": path}}) and prints, for each, its sizes or MuJoCo's error.
LOADER = r"""
import loadMujoco from "@mujoco/mujoco";
import fs from "node:fs";
const mujoco = await loadMujoco();
const cases = JSON.parse(fs.readFileSync(0, "utf8"));
const report = {};
for (const [name, { files, model }] of Object.entries(cases)) {
  const root = `/${name}`;
  for (const [path, bytes] of Object.entries(files)) {
    const full = `${root}/${path}`;
    const parts = full.split("/").slice(1, -1);
    for (let i = 1; i <= parts.length; i++) {
      const dir = "/" + parts.slice(0, i).join("/");
      if (!mujoco.FS.analyzePath(dir).exists) mujoco.FS.mkdir(dir);
    }
    mujoco.FS.writeFile(full, Buffer.from(bytes, "base64"));
  }
  try {
    const m = mujoco.MjModel.from_xml_path(`${root}/${model}`);
    report[name] = { nq: m.nq, nu: m.nu, nbody: m.nbody, timestep: m.opt.timestep };
    m.delete();
  } catch (error) {
    report[name] = { error: String(error.message ?? error) };
  }
}
console.log(JSON.stringify(report));
"""


def load_in_browser_mujoco(cases: dict) -> dict:
    import base64

    encoded = {name: {"model": case["model"],
                      "files": {path: base64.b64encode(data).decode() for path, data in
                                case["files"].items()}}
               for name, case in cases.items()}
    run = subprocess.run([NODE, "--input-type=module", "-e", LOADER], cwd=ROOT,
                         input=json.dumps(encoded), capture_output=True, text=True, timeout=60)
    assert run.returncode == 0, run.stderr
    return json.loads(run.stdout)


def practice_case(practice: int) -> dict:
    built = json.loads(browser_models.output(practice).read_text())
    files = {"model.xml": built["model"].encode()}
    for path, url in built["files"].items():
        files[path] = (ROOT / url).read_bytes()
    return {"model": "model.xml", "files": files}


def test_both_mujoco_versions_are_the_pinned_ones():
    requirements = (ROOT / "requirements.txt").read_text()
    assert re.search(rf"^mujoco=={re.escape(PYTHON_MUJOCO)}$", requirements, re.M)
    assert mujoco.__version__ == PYTHON_MUJOCO
    package = json.loads((ROOT / "package.json").read_text())
    assert package["dependencies"]["@mujoco/mujoco"] == BROWSER_MUJOCO
    lock = json.loads((ROOT / "package-lock.json").read_text())
    assert lock["packages"]["node_modules/@mujoco/mujoco"]["version"] == BROWSER_MUJOCO


def test_the_browser_models_are_up_to_date():
    assert browser_models.main(["--check"]) == 0, "run: .venv/bin/python -m course.browser_models"


@pytest.mark.parametrize("practice", sorted(browser_models.LESSONS))
def test_a_browser_model_is_the_lessons_model(practice):
    """The same bodies, joints, actuators and time step as the lesson's own model."""
    built = json.loads(browser_models.output(practice).read_text())
    assets = {path: (ROOT / url).read_bytes() for path, url in built["files"].items()}
    page = mujoco.MjModel.from_xml_string(built["model"], assets)
    spec, _ = browser_models.LESSONS[practice](practice)
    lesson = spec.compile()
    for size in ("nq", "nv", "nu", "nbody", "ngeom", "njnt"):
        assert getattr(page, size) == getattr(lesson, size), size
    assert page.opt.timestep == lesson.opt.timestep
    for field in ("body_mass", "body_inertia", "jnt_range", "dof_damping", "dof_frictionloss",
                  "actuator_ctrlrange", "actuator_gear"):
        np.testing.assert_allclose(getattr(page, field), getattr(lesson, field), rtol=1e-5,
                                   err_msg=field)


def test_browser_form_changes_only_the_input_signature(tmp_path):
    """Practice 5 as `sw2sim convert` writes it has position and velocity actuators with
    input="pos" / "vel": without it, 4.0 compiles the same model, all but
    actuator_ctrlspec, and 2 s of the same controls give the same motion."""
    folder = tmp_path / "car"
    convert(ROOT / "examples/example_5", folder)
    robot = next(p for p in folder.glob("*.xml") if p.name != "scene.xml")
    written = robot.read_text()
    assert 'input="pos"' in written and 'input="vel"' in written
    bridged = browser_form(written)
    assert "input=" not in bridged
    before = mujoco.MjModel.from_xml_path(str(folder / "scene.xml"))
    robot.write_text(bridged)
    after = mujoco.MjModel.from_xml_path(str(folder / "scene.xml"))
    differ = [name for name in dir(before) if not name.startswith("_")
              and isinstance(getattr(before, name), np.ndarray)
              and not np.array_equal(getattr(before, name), getattr(after, name))]
    assert differ == ["actuator_ctrlspec"]
    runs = []
    for model in (before, after):
        data = mujoco.MjData(model)
        data.ctrl[:] = np.linspace(0.2, 0.9, model.nu)
        for _ in range(1000):
            mujoco.mj_step(model, data)
        runs.append(data.qpos.copy())
    np.testing.assert_array_equal(runs[0], runs[1])


@needs_node
def test_the_browser_mujoco_loads_every_practice_and_needs_the_bridge(tmp_path):
    folder = tmp_path / "arm"
    convert(ROOT / "examples/example_3", folder)
    robot = next(p for p in folder.glob("*.xml") if p.name != "scene.xml")
    files = {p.relative_to(folder).as_posix(): p.read_bytes()
             for p in folder.rglob("*") if p.is_file()}
    cases = {f"practice{n}": practice_case(n) for n in browser_models.LESSONS}
    cases["converted"] = {"model": "scene.xml", "files": files}
    cases["bridged"] = {"model": "scene.xml", "files": {
        **files, robot.name: browser_form(robot.read_text()).encode()}}
    report = load_in_browser_mujoco(cases)
    for practice in browser_models.LESSONS:
        spec, _ = browser_models.LESSONS[practice](practice)
        lesson = spec.compile()
        assert report[f"practice{practice}"] == {
            "nq": lesson.nq, "nu": lesson.nu, "nbody": lesson.nbody,
            "timestep": lesson.opt.timestep}, practice
    assert "input is only available" in report["converted"]["error"]
    assert report["bridged"]["nu"] == 2
