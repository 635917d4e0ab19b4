"""What the pages say about MuJoCo and an exported package, checked by running MuJoCo: its
viewer, its contacts between a locked base and its wheels, and what holds a model in place.
"""

from __future__ import annotations

import re
import subprocess
import sys

import pytest
import mujoco
import sw2sim
from sw2sim.actuators import add_actuators
from sw2sim.convert import convert
from page_text import flat_page as flat

from course.practices import ROOT

PAGES = ROOT / "_pages"


# ---- MuJoCo's viewer and an exported package ------------------------------------------------

def fresh_python(code: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT)


def test_import_mujoco_alone_does_not_load_the_viewer():
    run = fresh_python("import mujoco\nmujoco.viewer")
    assert run.returncode != 0 and "AttributeError" in run.stderr
    assert fresh_python("import mujoco.viewer\nmujoco.viewer.launch").returncode == 0
    text = (PAGES / "practice-1/04-testing-and-modifying.md").read_text(encoding="utf-8")
    launch = text.index("mujoco.viewer.launch(model)")
    assert "import mujoco.viewer" in text[:launch] and "AttributeError" in text[:launch]


def test_the_viewers_command_line_takes_an_mjcf_file():
    run = subprocess.run([sys.executable, "-m", "mujoco.viewer", "--help"], capture_output=True,
                         text=True, timeout=60)
    assert run.returncode == 0 and "--mjcf" in run.stdout
    assert "python -m mujoco.viewer --mjcf=" in (PAGES / "practice-1/04-testing-and-modifying.md").read_text()


def test_mujoco_cannot_open_an_exported_urdf_but_can_open_the_converted_folder(tmp_path):
    urdf = ROOT / "examples/example_1/urdf/example_1.urdf"
    with pytest.raises(ValueError, match="Error opening file"):
        mujoco.MjModel.from_xml_path(str(urdf))
    convert(ROOT / "examples/example_1", tmp_path / "example_1_mujoco")
    model = mujoco.MjModel.from_xml_path(str(tmp_path / "example_1_mujoco/scene.xml"))
    assert model.njnt == 4
    text = flat("practice-1/04-testing-and-modifying.md")
    assert "drag the URDF onto it" not in text and '"Error opening file"' in text
    assert "sw2sim convert examples/example_1 -o example_1_mujoco" in text
    assert "--mjcf=example_1_mujoco/scene.xml" in text


def test_sw2sim_view_gives_each_wheel_a_speed_slider():
    spec = sw2sim.load_package(ROOT / "examples/example_1")
    actuators, _ = add_actuators(spec, ROOT / "examples/example_1", sliders=True)
    assert len(actuators) == 4 and {a.kind for a in actuators} == {"velocity"}
    assert "gives each wheel a slider in the *Control* section" in flat("practice-1/04-testing-and-modifying.md")


# ---- contacts between a locked base and its wheels ------------------------------------------

CONTACT_SECTION = "why-a-locked-base-does-not-touch-its-wheels"


def contacts(base_joint: str, options: str = "") -> int:
    """Contacts between a box and a disc overlapping it on a hinge, the box held or free."""
    xml = f"""<mujoco><option>{options}</option><worldbody>
      <body name="base">{base_joint}<geom type="box" size=".1 .1 .02"/>
        <body name="wheel"><joint type="hinge" axis="0 1 0"/>
          <geom type="cylinder" size=".05 .05" pos="0 0 .03"/></body>
      </body></worldbody></mujoco>"""
    model = mujoco.MjModel.from_xml_string(xml)
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    return data.ncon


def test_mujoco_filters_parent_contacts_except_for_a_body_welded_to_the_world():
    assert contacts("<freejoint/>") == 0, "a free parent: filtered"
    assert contacts("<freejoint/>", '<flag filterparent="disable"/>') > 0
    assert contacts("") > 0, "a parent welded to the world counts as the world: not filtered"


def test_practice_1_explains_the_exclusions_and_its_numbers_hold():

    def push_one_wheel(spec):
        model = spec.compile()
        data = mujoco.MjData(model)
        mujoco.mj_forward(model, data)
        base = model.body("base_link").id
        touching = sum(base in (model.geom_bodyid[c.geom1], model.geom_bodyid[c.geom2])
                       for c in data.contact[:data.ncon])
        dof = model.joint("front_left_joint").dofadr[0]
        while data.time < 1.0:
            data.qfrc_applied[dof] = 1.0
            mujoco.mj_step(model, data)
        return touching, data.qvel[dof]

    package = ROOT / "examples/example_1"
    assert not sw2sim.load_package(package, fixed_base=False).excludes
    spec = sw2sim.load_package(package)
    assert len(spec.excludes) == 4
    touching, free = push_one_wheel(spec)
    for exclude in list(spec.excludes):
        spec.delete(exclude)
    held, stuck = push_one_wheel(spec)
    text = flat("practice-1/04-testing-and-modifying.md")
    assert touching == 0 and f"spins up freely, to {free:.1f} rad/s" in text
    assert f"touches its wheels in {held} places" in text and abs(stuck) < 1
    assert "### Why a locked base does not touch its wheels" in text and "`filterparent`" in text


def test_practice_4_points_at_the_explanation():
    assert f"(/practice-1/testing-and-modifying/#{CONTACT_SECTION})" in flat("practice-4/03-modifying-the-urdf.md")


# ---- what holds a model in place in MuJoCo: fixed_base, not the world link ------------------

def raw_mujoco(urdf_text: str):
    """MuJoCo's own URDF reader, mesh paths made absolute and nothing else changed."""
    meshes = (ROOT / "examples/example_1").as_posix() + "/"
    return mujoco.MjSpec.from_string(urdf_text.replace("package://example_1/", meshes)).compile()


def test_mujoco_holds_a_jointless_root_with_or_without_a_world_link():
    text = (ROOT / "examples/example_1/urdf/example_1.urdf").read_text()
    assert re.search(r'<link\s+name="world"', text)
    without = re.sub(r'<link\s+name="world"\s*/>', "", text)
    without = re.sub(r'<joint\s+name="world_joint".*?</joint>', "", without, flags=re.S)
    for urdf in (text, without):
        model = raw_mujoco(urdf)
        assert mujoco.mjtJoint.mjJNT_FREE not in list(model.jnt_type), "no free joint"
        wheel = model.body("front_left_wheel").id
        assert model.body_weldid[model.body_parentid[wheel]] == 0, "the base is part of the world"


def test_fixed_base_decides_in_load_package_and_the_world_link_in_the_commands(tmp_path):
    free = mujoco.mjtJoint.mjJNT_FREE
    with_world, without_world = ROOT / "examples/example_1", ROOT / "examples/example_5"
    assert free in list(sw2sim.load_package(with_world, fixed_base=False).compile().jnt_type)
    assert free not in list(sw2sim.load_package(without_world).compile().jnt_type)
    assert convert(with_world, tmp_path / "one").fixed
    assert not convert(without_world, tmp_path / "five").fixed
    five = mujoco.MjModel.from_xml_path(str(tmp_path / "five/scene.xml"))
    assert five.jnt_type[0] == free
    glossary = flat("reference/06-glossary.md")
    entry = glossary[glossary.index("### World link"):]
    assert "in Gazebo and in MuJoCo" not in entry
    assert "whether or not there is a world link" in entry and "fixed_base=False" in entry
    assert "free it when the URDF has no world link" in entry


def test_without_sw2sim_the_fixed_base_grips_its_wheels():
    """"A model you ... load without sw2sim needs the same exclusions whenever its base is fixed"."""
    model = raw_mujoco((ROOT / "examples/example_1/urdf/example_1.urdf").read_text())
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    wheels = {model.body(f"{end}_{side}_wheel").id for end in ("front", "rear") for side in ("left", "right")}
    pairs = {(model.geom_bodyid[c.geom1], model.geom_bodyid[c.geom2]) for c in data.contact[:data.ncon]}
    assert {b for pair in pairs for b in pair} == wheels | {0}, "every wheel touches the world"
    assert "load without `sw2sim`, needs the same exclusions" in flat("practice-1/04-testing-and-modifying.md")
