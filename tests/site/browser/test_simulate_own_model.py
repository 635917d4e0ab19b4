""""Your own model" in the browser (_includes/own-model-simulator.html, assets/js/own-model.js):
a folder `sw2sim convert` wrote, dropped as a zip or as a folder, simulates in headless
Chromium as MuJoCo 4.0 simulates the same folder in Python, with a slider per joint; a
folder the browser cannot load, or a package not yet converted, gets a sentence naming the
file and the command to run; nothing is sent anywhere.
"""

import re
import shutil
import zipfile

import mujoco
import numpy as np
import pytest

import axe_audit
from repository import ROOT
from sw2sim.cli import main as cli
from sw2sim.convert import convert

PAGE = "/reference/your-own-model/"
READY_S = 30.0
SAME_MODEL = 1e-9   # m or rad: the same model in 3.14 and 4.0 (test_simulate.py says why)


def zipped(folder, archive):
    with zipfile.ZipFile(archive, "w", zipfile.ZIP_DEFLATED) as z:
        for path in sorted(folder.rglob("*")):
            if path.is_file():
                z.write(path, path.relative_to(folder.parent).as_posix())
    return archive


@pytest.fixture(scope="module")
def arm(tmp_path_factory):
    """Practice 3's package as `sw2sim convert` writes it: two position actuators."""
    folder = tmp_path_factory.mktemp("own") / "arm_mujoco"
    convert(ROOT / "examples/example_3", folder)
    return folder


def drop(page, path, kind="zip"):
    chooser = ".own-model input[accept]" if kind == "zip" else ".own-model input[webkitdirectory]"
    page.locator(chooser).set_input_files(path)
    page.wait_for_function(
        "() => ['ready', 'problem'].includes(document.querySelector('.own-model').dataset.state)",
        timeout=READY_S * 1000)


def status(page):
    return page.locator(".own-model-status").text_content()


def test_a_dropped_zip_simulates_as_python_does(site, browser_page, arm, tmp_path):
    archive = zipped(arm, tmp_path / "arm_mujoco.zip")
    found = {}
    methods = []

    def steps(page):
        page.on("request", lambda request: methods.append(request.method))
        drop(page, archive)
        page.evaluate("() => document.querySelector('.own-model').simulation.ready")
        page.get_by_role("button", name="Reset the simulation").click()
        slider = page.get_by_label("middle_arm_joint (position, rad)")
        found["range"] = (slider.get_attribute("min"), slider.get_attribute("max"))
        # the slider keeps to its 200 steps: the value it took is the control sent
        found["ctrl"] = float(slider.evaluate(
            "(input) => { input.value = 0.5; input.dispatchEvent(new Event('input')); "
            "return input.value; }"))
        page.evaluate("() => document.querySelector('.own-model').simulation.run(2)")
        found["qpos"] = page.evaluate("() => document.querySelector('.own-model').simulation.qpos()")
        found["sliders"] = page.locator(".own-model-joint").count()
        found["status"] = status(page)

    visit = browser_page.visit(PAGE, then=steps)
    assert not visit.problems(), visit.problems()
    assert set(methods) == {"GET"}, "the page sent something"
    assert found["sliders"] == 2 and "gravity on" in found["status"]
    assert [float(x) for x in found["range"]] == [-0.7854, 0.7854]
    model = mujoco.MjModel.from_xml_path(str(arm / "scene.xml"))
    data = mujoco.MjData(model)
    data.ctrl[:] = [found["ctrl"], 0.0]
    mujoco.mj_step(model, data, nstep=round(2 / model.opt.timestep))
    assert np.abs(np.array(found["qpos"]) - data.qpos).max() <= SAME_MODEL
    assert found["qpos"][0] == pytest.approx(found["ctrl"], abs=1e-3)


def test_a_dropped_folder_gets_a_slider_for_every_joint(site, browser_page, tmp_path):
    """Practice 1's wheels have no transmissions: each gets a velocity slider, as in
    `sw2sim view`."""
    folder = tmp_path / "wheels_mujoco"
    convert(ROOT / "examples/example_1", folder)

    def steps(page):
        drop(page, folder, kind="folder")
        page.evaluate("() => document.querySelector('.own-model').simulation.ready")

    visit = browser_page.visit(PAGE, then=steps)
    assert not visit.problems(), visit.problems()
    labels = browser_page.page.locator(".own-model-joint label").all_text_contents()
    assert labels == [f"{wheel}_joint (velocity, rad/s)" for wheel in
                      ("front_left", "front_right", "rear_left", "rear_right")]


@pytest.mark.parametrize("case", ["older convert", "not converted"])
def test_what_the_browser_cannot_load_is_named_with_the_fix(site, browser_page, arm, tmp_path,
                                                            case):
    if case == "older convert":   # as convert wrote the robot before the browser's form
        folder = tmp_path / "old_mujoco"
        folder.mkdir()
        for path in arm.rglob("*"):
            if path.is_file():
                target = folder / path.relative_to(arm)
                target.parent.mkdir(parents=True, exist_ok=True)
                target.write_bytes(path.read_bytes())
        robot = folder / "example_3.xml"
        robot.write_text(re.sub(r'<general ', '<general input="pos" ', robot.read_text()))
        archive, named = zipped(folder, tmp_path / "old.zip"), "old_mujoco/example_3.xml"
        command = "sw2sim convert YOUR_PACKAGE -o FOLDER --force"
    else:
        archive = zipped(ROOT / "examples/example_1", tmp_path / "example_1.zip")
        named, command = "example_1/urdf/example_1.urdf", "sw2sim convert example_1 -o example_1_mujoco"

    visit = browser_page.visit(PAGE, then=lambda page: drop(page, archive))
    assert not visit.problems(), visit.problems()
    said = status(browser_page.page)
    assert named in said and command in said, said
    assert browser_page.page.locator(".own-model-problem").count() == 1


def test_the_dropped_model_view_is_accessible(site, browser_page, arm, tmp_path):
    """The drop box, its choosers, the view, the buttons and the labelled sliders pass axe."""
    archive = zipped(arm, tmp_path / "arm_mujoco.zip")
    axe_url = site.node_module_url(axe_audit.AXE)

    def drop_and_audit(page):
        drop(page, archive)
        page.add_script_tag(url=axe_url)
        axe_audit.start(page, PAGE, context={"include": [[".own-model"]]})

    visit = browser_page.visit(PAGE, then=drop_and_audit)
    violations = axe_audit.serious(axe_audit.collect(browser_page.page))
    assert not visit.problems(), visit.problems()
    assert not violations, violations


def test_a_converted_raw_export_simulates(site, browser_page, tmp_path):
    """The raw export of Your own model (examples/Arm_Assembly), with the page's one fix
    (the empty mesh replaced) and convert's repairs: a free base, two joints without limits
    or actuators. It stands on the floor under gravity as in MuJoCo 4.0, its two joints get a
    velocity slider each."""
    package = tmp_path / "Arm_Assembly"
    shutil.copytree(ROOT / "examples/Arm_Assembly", package)
    shutil.copy(ROOT / "examples/example_3/meshes/end_arm_link.STL",
                package / "meshes/end_arm_link.STL")
    folder = tmp_path / "arm_repaired"
    assert cli(["convert", str(package), "-o", str(folder)]) == 0
    found = {}

    def steps(page):
        drop(page, folder, kind="folder")
        page.evaluate("() => document.querySelector('.own-model').simulation.ready")
        page.get_by_role("button", name="Reset the simulation").click()
        page.evaluate("() => document.querySelector('.own-model').simulation.run(1)")
        found["qpos"] = page.evaluate("() => document.querySelector('.own-model').simulation.qpos()")

    visit = browser_page.visit(PAGE, then=steps)
    assert not visit.problems(), visit.problems()
    labels = browser_page.page.locator(".own-model-joint label").all_text_contents()
    assert labels == ["middle_arm_joint (velocity, rad/s)", "end_arm_joint (velocity, rad/s)"]
    model = mujoco.MjModel.from_xml_path(str(folder / "scene.xml"))
    data = mujoco.MjData(model)
    mujoco.mj_step(model, data, nstep=round(1 / model.opt.timestep))
    qpos = np.array(found["qpos"])
    assert np.isfinite(qpos).all() and len(qpos) == model.nq
    assert qpos[2] == pytest.approx(data.qpos[2], abs=1e-4), "the base's height on the floor"
