"""What the pages say the SolidWorks exporter does, as its C# source (github
ros/solidworks_urdf_exporter, releases 1.4.4 to 1.6.1) does it, and the numbers that follow
from the lessons' own models.

Each test fails on the wording the pages had before they were read against the source (the
old phrase is named in it), and passes on the corrected statement with its number, which is
computed here from the designs and example packages, not copied. The source itself is not
needed to run them; the file and method each statement rests on is named in the test.
"""

from __future__ import annotations

import json
import math

import mujoco
import numpy as np
import pytest
import sw2sim
from lxml import etree
from page_text import flat_page as flat

from course.exporter_format import EXPORTER_GREY, write_exported
from course.practices import ROOT, design


# ---- 1. both buttons rewrite every file but the meshes ---------------------------------------

def exported_files(practice: str, tmp_path) -> list[str]:
    """The files an export writes besides the meshes, as the course's copy of the exporter's
    format writes them (course/exporter_format.py:write_exported, after ExportHelper.cs:
    ExportRobot: the lesson's package without its hand edits and their saved copies)."""
    folder = tmp_path / practice
    written = write_exported(design(practice).robot(), folder)
    return sorted(p.relative_to(folder).as_posix() for p in written
                  if p.parent.name != "meshes")


def test_export_urdf_only_rewrites_everything_but_the_meshes(tmp_path):
    """AssemblyExportForm.cs: both buttons call FinishExport, which calls ExportRobot; the
    only thing exportSTL=false leaves out is SaveSTL. Every other file is written again."""
    # Each file the export writes, and how the page names it.
    named = {"CMakeLists.txt": "`CMakeLists.txt`",
             "config/joint_names_example_1.yaml": "`config/joint_names_example_1.yaml`",
             "launch/display.launch": "`display.launch`",
             "launch/gazebo.launch": "`gazebo.launch`",
             "package.xml": "`package.xml`",
             "urdf/example_1.csv": "its CSV",
             "urdf/example_1.urdf": "the URDF"}
    assert exported_files("practice_1", tmp_path) == sorted(named)
    text = flat("practice-1/02-exporting.md")
    assert "rewrites only the URDF" not in text
    sentence = text[text.index("*Export URDF Only...* skips only the meshes"):]
    sentence = sentence[:sentence.index("Choose a folder")]
    for file, words in named.items():
        assert words in sentence, file
    assert "overwrites whatever you have since edited by hand" in sentence

    reference = flat("reference/02-exporter.md")
    assert "writes the URDF without the meshes" not in reference
    assert "writes the same package except `meshes/`" in reference
    assert "Both buttons run the same export (`ExportRobot`)" in reference
    assert "overwrites your edits in them" in reference

    controllers = flat("practice-3/04-controllers.md")
    assert "writes that list again on every export, with either button" in controllers


# ---- 2. Automatically Generate turns Origin_global so that Z is up --------------------------

def exporter_rotation(rpy) -> np.ndarray:
    """MathOPS.cs GetRotation: Rz(yaw) · Ry(pitch) · Rx(roll)."""
    r, p, y = rpy
    rx = np.array([[1, 0, 0], [0, math.cos(r), -math.sin(r)], [0, math.sin(r), math.cos(r)]])
    ry = np.array([[math.cos(p), 0, math.sin(p)], [0, 1, 0], [-math.sin(p), 0, math.cos(p)]])
    rz = np.array([[math.cos(y), -math.sin(y), 0], [math.sin(y), math.cos(y), 0], [0, 0, 1]])
    return rz @ ry @ rx


def test_automatically_generate_puts_origin_globals_z_along_solidworks_up():
    """ExportHelperExtension.cs: CreateBaseRefOrigin(true) gives Origin_global the rpy
    (-pi/2, 0, 0) (the same in 1.4.4, 1.5.1, 1.6.0 and 1.6.1): its Z is SolidWorks' +Y, up,
    and its X the assembly's X. An automatic frame does not lay the model on its side."""
    turned = exporter_rotation((-math.pi / 2, 0.0, 0.0))
    assert turned[:, 2] == pytest.approx([0, 1, 0], abs=1e-12), "Z along SolidWorks' Y"
    assert turned[:, 0] == pytest.approx([1, 0, 0], abs=1e-12), "X the assembly's X"
    reference = flat("reference/02-exporter.md")
    assert "with the assembly's axes, and the model arrives lying on its side" not in reference
    assert "(`rpy` −π/2, 0, 0) so that its Z lies along SolidWorks' Y" in reference
    assert "A model built with Y up therefore arrives upright" in reference

    modelling = flat("practice-1/01-modelling.md")
    assert ("uses the assembly's own origin and your model arrives lying on its side"
            not in modelling)
    assert "the model would arrive in ROS and MuJoCo lying on its side" not in modelling
    assert "turned so that its Z is SolidWorks' Y: the model arrives upright" in modelling


def test_practice_1s_parallel_frames_give_zero_rpy_and_axes_along_y():
    """The reason the page now gives for Z-up frames: with every frame parallel to
    Origin_global, every joint's rpy is 0 0 0 and every wheel turns about y."""
    urdf = etree.parse(str(ROOT / "examples/example_1/urdf/example_1.urdf"))
    joints = urdf.xpath("//joint")
    assert joints and all(j.find("origin").get("rpy") == "0 0 0" for j in joints)
    wheels = [j for j in joints if j.get("type") == "continuous"]
    assert len(wheels) == 4 and all(j.find("axis").get("xyz") == "0 1 0" for j in wheels)
    assert "every joint's `rpy` is 0 0 0 and every wheel turns about y" in flat(
        "practice-1/01-modelling.md")


# ---- 3. k_velocity caps the push at every speed ----------------------------------------------

def test_k_velocity_caps_practice_3s_push_at_rest():
    """joint_limits_interface.h (ros_control noetic-devel), EffortJointSoftLimitsHandle: the
    effort is held below -k_velocity * (v - v_max) at every speed, so at rest the middle joint
    gets k_velocity * velocity, none at the velocity limit, and a brake above it. The
    stand-in's copy of the rule (sw2sim.ros.hardware) gives the same numbers."""
    from sw2sim.package import find_package
    from sw2sim.ros import hardware
    arm = design("practice_3")
    k_velocity, velocity = arm.K_VELOCITY["middle_arm_joint"], arm.VELOCITY
    cap = k_velocity * velocity
    assert cap == 20.0 and cap < arm.EFFORT
    handle = hardware.handles(find_package(ROOT / "examples/example_3"))["middle_arm_joint"]

    def applied(speed: float) -> float:
        law = hardware.effort((arm.EFFORT, 0.0, 0.0), handle, 0.0, speed)
        return hardware.value(law, 0.0, speed)

    assert applied(0.0) == pytest.approx(cap)
    assert applied(velocity) == pytest.approx(0.0)
    assert applied(1.25 * velocity) < 0
    reference = flat("reference/02-exporter.md")
    assert "when the joint moves faster than its velocity limit" not in reference
    assert "push with up to 1000 N·m" not in reference
    assert (f"{k_velocity:g} × {velocity:g} rad/s = {cap:g} N·m at most" in reference
            and "That rule acts at every speed" in reference)
    assert f"an effort limit of {arm.EFFORT:g} N·m" in reference


# ---- 4. the knuckles are as light for Gazebo's explicit d term as the centre joint ----------

GAZEBO_STEP = 0.001   # s, Gazebo's default physics step


def test_practice_5s_knuckles_are_too_light_for_an_explicit_d_term():
    """The page's rule: Gazebo's explicit force is stable while d * step < 2 * inertia. The
    inertia about each joint, from the model (the knuckle carries its wheel)."""
    car = design("practice_5")
    model = sw2sim.load_package(ROOT / "examples/example_5", fixed_base=False).compile()
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    full = np.zeros((model.nv, model.nv))
    mujoco.mj_fullM(model, data, full)

    def inertia(joint: str) -> float:   # g·m²
        dof = model.joint(joint).dofadr[0]
        return full[dof, dof] * 1e6 / 1e3

    text = flat("reference/08-ros-without-gazebo.md")
    assert "Practice 5's steering joint is such a case" not in text
    cases = ((car.STEERING_JOINT, car.STEERING_GAINS, "the centre joint, with d = {d:g} "
              "N·m·s/rad, needs an inertia over {needed:.2f} g·m² and has {has:.2f} g·m²"),
             (car.KNUCKLES["left"], car.KNUCKLE_GAINS, "each knuckle, with d = {d:g} N·m·s/rad, "
              "needs over {needed:.1f} g·m² and has {has:.2f} g·m², its wheel included"))
    for joint, gains, phrase in cases:
        needed = gains["d"] * GAZEBO_STEP / 2 * 1e3
        has = inertia(joint)
        assert has < needed, (joint, has, needed)
        assert phrase.format(d=gains["d"], needed=needed, has=has) in text, joint
    assert inertia(car.KNUCKLES["right"]) == pytest.approx(inertia(car.KNUCKLES["left"]))
    assert "All three of Practice 5's steering joints are such cases" in text


# ---- 5. the exporter changes the sign of the products of inertia -----------------------------

def test_the_products_of_inertia_are_copied_with_their_signs_changed():
    """Inertia.cs SetMomentMatrix: Ixy = -array[1], Ixz = -array[2], Iyz = -array[5]; the
    moments as they are."""
    from sw2sim.check import all_rules
    fix = all_rules()["inertia-not-positive-definite"].fix
    data = json.loads((ROOT / "_data/check_rules.json").read_text(encoding="utf-8"))
    listed = {r["id"]: r for g in data["groups"] for r in g["rules"]}
    for words in (fix, listed["inertia-not-positive-definite"]["fix"]):
        assert "(the Lxx ... Lzz values)" not in words
        assert "ixy = -Lxy, ixz = -Lxz, iyz = -Lyz" in words
    reference = flat("reference/02-exporter.md")
    assert "`ixy` = −Lxy, `ixz` = −Lxz, `iyz` = −Lyz" in reference
    assert "copied as shown, they are wrong" in reference


# ---- 6. the colour comes from the part ------------------------------------------------------

def test_the_colour_is_the_parts_own_and_the_grey_is_solidworks_default():
    """ExportHelperExtension.cs ComputeVisualCollisionProperties: rgba from the first
    component's MaterialPropertyValues (alpha = 1 - transparency)."""
    grey = " ".join(f"{c:.3f}" for c in EXPORTER_GREY[:3]) + " 1"
    practice = flat("practice-1/04-testing-and-modifying.md")
    assert "Every link of an export gets the same pale blue-grey" not in practice
    assert "The exporter copies each link's colour from SolidWorks" in practice
    assert f'`rgba="{grey}"`' in practice
    reference = flat("reference/02-exporter.md")
    assert "The exporter's default is a pale blue-grey" not in reference
    assert f"SolidWorks' default part colour is a pale blue-grey, `{grey}`" in reference


# ---- 7. the mates are read only for a joint left on automatic ------------------------------

def test_the_home_pose_mates_are_not_read_for_a_named_joint():
    """ExportHelperExtension.cs CreateJoint: EstimateGlobalJointFromComponents (which reads
    the freedom the mates leave) runs only when the coordinate system, the axis or the joint
    type is left on Automatically Generate / Automatically Detect."""
    practice_1 = flat("practice-1/01-modelling.md")
    assert ("which reads the freedom the mates leave, would take it for a fixed joint"
            not in practice_1)
    assert ("only when its coordinate system, its axis or its type is left on automatic"
            in practice_1)
    practice_4 = flat("practice-4/01-modelling.md")
    assert "or the exporter will see no freedom to move" not in practice_4
    assert "are chosen in the exporter's link tree, not left on automatic" in practice_4


# ---- 8. the name typed in the save dialog names everything ---------------------------------

@pytest.mark.parametrize("example", ["example_1", "example_3", "Arm_Assembly"])
def test_one_typed_name_names_the_package_the_robot_and_the_files(example):
    """ExportHelper.cs ExportRobot: URDFRobot.Name = PackageName, and the URDF, CSV and YAML
    are named after it; AssemblyExportForm.cs: PackageName is what the save dialog returns,
    which it only pre-fills with the assembly's title."""
    folder = ROOT / "examples" / example
    name = etree.parse(str(folder / "package.xml")).findtext("name")
    assert name == example
    assert etree.parse(str(folder / "urdf" / f"{name}.urdf")).getroot().get("name") == name
    assert (folder / "urdf" / f"{name}.csv").is_file()
    assert (folder / "config" / f"joint_names_{name}.yaml").is_file()


def test_the_pages_and_the_checker_say_the_save_dialog_names_the_package():
    from sw2sim.check import all_rules
    reference = flat("reference/02-exporter.md")
    assert "The exporter names the robot after the assembly" not in reference
    assert "the assembly's own name is used only to fill in the box" in reference
    own = flat("reference/03-your-own-model.md")
    assert "rename the assembly file in SolidWorks to `arm_assembly`" not in own
    assert "export again and type `arm_assembly` in the save dialog" in own
    rules = all_rules()
    data = json.loads((ROOT / "_data/check_rules.json").read_text(encoding="utf-8"))
    listed = {r["id"]: r for g in data["groups"] for r in g["rules"]}
    for rule in ("package-name-invalid", "package-name-style"):
        for words in (rules[rule].cause + rules[rule].fix,
                      listed[rule]["cause"] + listed[rule]["fix"]):
            assert "names the package after the SolidWorks assembly" not in words
            assert "Rename the assembly" not in words
            assert "save dialog" in words


# ---- 9. package.xml has format="2" from 1.5.1 on -------------------------------------------

def test_only_the_1_4_releases_omit_format_2():
    """PackageXMLWriter.cs writes the format attribute in 1.5.1 (and after), not in 1.4.4."""
    own = flat("reference/03-your-own-model.md")
    assert "what exporter versions up to 1.5 wrote" not in own
    assert "what the exporter's 1.4 releases wrote; 1.5.1 and later write it" in own


# ---- 10. Practice 4's block needs at least 2.69 s for its travel ---------------------------

def test_the_block_needs_at_least_its_travel_over_its_speed_limit():
    block = design("practice_4")
    least = block.TRAVEL / 1000 / block.VELOCITY
    assert least == pytest.approx(2.69)
    text = flat("practice-4/03-modifying-the-urdf.md")
    assert "needs 1.5 s to cross the bar" not in text
    assert (f"at its {block.VELOCITY:g} m/s limit the block needs at least {least:.2f} s to "
            f"cross its {least * block.VELOCITY:.2f} m of travel (about 3.3 s" in text)
