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

# One Node process loads every model it is given ({name: {"files": {path: base64},
# "model": path, "ctrl": [...], "steps": n}}) and prints, for each, its sizes and its qpos
# after `steps` steps with `ctrl` held, or MuJoCo's error.
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
    const d = new mujoco.MjData(m);
    const { ctrl = [], steps = 0 } = cases[name];
    for (let i = 0; i < steps; i++) {
      ctrl.forEach((value, k) => { d.ctrl[k] = value; });
      mujoco.mj_step(m, d);
    }
    const option = m.opt;
    report[name] = { nq: m.nq, nu: m.nu, nbody: m.nbody, timestep: option.timestep,
      qpos: Array.from(d.qpos) };
    option.delete();
    d.delete();
    m.delete();
  } catch (error) {
    report[name] = { error: String(error.message ?? error) };
  }
}
console.log(JSON.stringify(report));
"""


def load_in_browser_mujoco(cases: dict) -> dict:
    import base64

    encoded = {name: {**case, "files": {path: base64.b64encode(data).decode() for path, data in
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


# What browser_form may change in the compiled model: the input signature, and each
# joint's force cap moved onto the one actuator that drives it.
BRIDGED = {"actuator_ctrlspec", "jnt_actfrcrange", "jnt_actfrclimited", "actuator_forcerange",
           "actuator_forcelimited"}
CAR_CONTROLS = [0.3, 0.3, 0.3, 8, 8, 8, 8]   # rad for the steering, rad/s for the wheels
STEPS = 200   # 0.2 s of 1 ms: the caps act from the first step


def test_browser_form_leaves_the_motion_in_python_as_it_was():
    """Practice 5's car as MuJoCo 4.0 writes it has position and velocity actuators with
    input="pos" / "vel", and effort limits as the joints' actuatorfrcrange: rewritten, 4.0
    compiles the same model but for those fields, and 1 s of the same controls (the
    steering's and the wheels' force caps acting) gives the same motion."""
    spec, _ = browser_models.LESSONS[5](5)
    written, urls = browser_models.model_xml(5, spec)
    assets = {path: (ROOT / url).read_bytes() for path, url in urls.items()}
    assert 'input="pos"' in written and 'input="vel"' in written
    bridged = browser_form(written)
    assert "input=" not in bridged and "actuatorfrcrange" not in bridged
    before = mujoco.MjModel.from_xml_string(written, assets)
    after = mujoco.MjModel.from_xml_string(bridged, assets)
    differ = [name for name in dir(before) if not name.startswith("_")
              and isinstance(getattr(before, name), np.ndarray)
              and not np.array_equal(getattr(before, name), getattr(after, name))]
    assert "actuator_ctrlspec" in differ and set(differ) <= BRIDGED, differ
    runs = []
    for model in (before, after):
        data = mujoco.MjData(model)
        data.ctrl[:] = CAR_CONTROLS
        for _ in range(1000):
            mujoco.mj_step(model, data)
        runs.append(data.qpos.copy())
    np.testing.assert_array_equal(runs[0], runs[1])


@needs_node
def test_the_browser_mujoco_loads_every_practice_and_convert_output(tmp_path):
    folder = tmp_path / "arm"
    convert(ROOT / "examples/example_3", folder)
    robot = next(p for p in folder.glob("*.xml") if p.name != "scene.xml")
    files = {p.relative_to(folder).as_posix(): p.read_bytes()
             for p in folder.rglob("*") if p.is_file()}
    cases = {f"practice{n}": practice_case(n) for n in browser_models.LESSONS}
    cases["converted"] = {"model": "scene.xml", "files": files}
    spec, _ = browser_models.LESSONS[5](5)
    written, urls = browser_models.model_xml(5, spec)   # as MuJoCo 4.0 writes it
    cases["raw"] = {"model": "model.xml", "files": {
        "model.xml": written.encode(), **{p: (ROOT / u).read_bytes() for p, u in urls.items()}}}
    report = load_in_browser_mujoco(cases)
    for practice in browser_models.LESSONS:
        spec, _ = browser_models.LESSONS[practice](practice)
        lesson = spec.compile()
        loaded = report[f"practice{practice}"]
        assert "error" not in loaded, loaded
        assert (loaded["nq"], loaded["nu"], loaded["nbody"], loaded["timestep"]) == (
            lesson.nq, lesson.nu, lesson.nbody, lesson.opt.timestep), practice
    assert "error" not in report["converted"], "sw2sim convert writes the browser's form"
    assert "input is only available" in report["raw"]["error"]


@needs_node
def test_the_browser_mujoco_steps_the_bridged_model_as_python_the_original():
    """Practice 5's car as the lesson builds it, its effort limits as the joints' force caps
    (input="pos" alone removed), moves otherwise in 3.14 than in 4.0; with browser_form's
    rewrite, as 4.0 moves the original. Over STEPS: later, the wheels' contacts with the
    floor amplify the last bits in which native and WebAssembly arithmetic may differ
    (test_simulate.py's CAR_PATH says more)."""
    spec, _ = browser_models.LESSONS[5](5)
    written, urls = browser_models.model_xml(5, spec)
    assert "actuatorfrcrange" in written
    files = {path: (ROOT / url).read_bytes() for path, url in urls.items()}
    run = {"model": "model.xml", "ctrl": CAR_CONTROLS, "steps": STEPS}
    report = load_in_browser_mujoco({
        "signature_only": {**run, "files": {
            **files, "model.xml": re.sub(r' input="(pos|vel)"', "", written).encode()}},
        "bridged": {**run, "files": {**files, "model.xml": browser_form(written).encode()}}})
    model = mujoco.MjModel.from_xml_string(written, files)
    data = mujoco.MjData(model)
    data.ctrl[:] = CAR_CONTROLS
    mujoco.mj_step(model, data, nstep=STEPS)
    np.testing.assert_allclose(report["bridged"]["qpos"], data.qpos, rtol=0, atol=1e-9)
    assert np.abs(np.array(report["signature_only"]["qpos"]) - data.qpos).max() > 1e-3
