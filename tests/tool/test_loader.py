"""load_package: what it fixes in an exported package, and how it reports a broken one."""

import shutil

import numpy as np
import pytest

import sw2sim
import mujoco
from sw2sim import LoadError
from repository import ROOT

EXAMPLE = ROOT / "examples" / "example_1"


@pytest.fixture
def package(tmp_path):
    """A private copy of the Practice 1 package, free to break."""
    dst = tmp_path / "example_1"
    shutil.copytree(EXAMPLE, dst, ignore=shutil.ignore_patterns("scripts"))
    return dst


def urdf_of(pkg):
    return pkg / "urdf" / "example_1.urdf"


def test_loads_from_the_folder_or_the_urdf():
    a = sw2sim.load_package(EXAMPLE).compile()
    b = sw2sim.load_package(EXAMPLE / "urdf" / "example_1.urdf").compile()
    assert a.nbody == b.nbody == 6 and a.njnt == b.njnt == 4


def test_visual_meshes_are_kept_and_do_not_collide():
    model = sw2sim.load_package(EXAMPLE).compile()
    visual = model.geom_group == 1
    assert visual.sum() == 5
    assert np.all(model.geom_contype[visual] == 0) and np.all(model.geom_conaffinity[visual] == 0)


def test_fixed_base_children_do_not_collide_with_it():
    model = sw2sim.load_package(EXAMPLE).compile()
    base = model.body("base_link").id
    pairs = {tuple(sorted((model.exclude_signature[i] >> 16, model.exclude_signature[i] & 0xFFFF)))
             for i in range(model.nexclude)}
    for name in ["front_left_wheel", "front_right_wheel", "rear_left_wheel", "rear_right_wheel"]:
        assert tuple(sorted((base, model.body(name).id))) in pairs


def test_without_the_exclusions_a_wheel_would_stick():
    """The reason the loader excludes contacts: the wheel's hull overlaps the axle stub."""
    spec = sw2sim.load_package(EXAMPLE)
    for exclude in list(spec.excludes):
        spec.delete(exclude)
    model = spec.compile()
    data = mujoco.MjData(model)
    for _ in range(500):
        data.qfrc_applied[:] = 1.0
        mujoco.mj_step(model, data)
    assert data.ncon > 0 and abs(data.qvel[0]) < 1.0


def test_free_base_gets_a_free_joint_and_rests_on_the_floor():
    model = sw2sim.load_package(EXAMPLE, fixed_base=False).compile()
    assert model.jnt_type[0] == mujoco.mjtJoint.mjJNT_FREE and model.nq == 7 + 4
    data = mujoco.MjData(model)
    for _ in range(1000):
        mujoco.mj_step(model, data)
    assert data.body("base_link").xpos[2] == pytest.approx(0.1, abs=0.005)  # on its 0.1 m wheels


def test_scene_has_floor_light_and_camera():
    model = sw2sim.load_package(EXAMPLE).compile()
    assert model.geom("floor").type[0] == mujoco.mjtGeom.mjGEOM_PLANE
    assert model.nlight >= 1 and model.camera("overview") is not None


def test_missing_package_names_the_path(tmp_path):
    with pytest.raises(LoadError, match="no such file or folder"):
        sw2sim.load_package(tmp_path / "nothing")


def test_missing_mesh_names_file_line_and_fix(package):
    (package / "meshes" / "rear_left_wheel.STL").unlink()
    with pytest.raises(LoadError) as err:
        sw2sim.load_package(package)
    text = str(err.value)
    line = next(i for i, l in enumerate(urdf_of(package).read_text().splitlines(), 1)
                if "rear_left_wheel.STL" in l)
    assert text.startswith(f"{urdf_of(package).resolve()}:{line}:")
    assert "rear_left_wheel.STL" in text and "export again" in text


def test_malformed_xml_names_the_line(package):
    lines = urdf_of(package).read_text().splitlines()
    broken = next(i for i, line in enumerate(lines) if line.endswith('izz="0.045673030684173" />'))
    lines[broken] = lines[broken].replace(" />", " >")   # <inertia ...> never closed
    urdf_of(package).write_text("\n".join(lines))
    with pytest.raises(LoadError, match=r"example_1\.urdf:\d+: not well-formed XML") as err:
        sw2sim.load_package(package)
    assert broken + 1 <= err.value.line <= broken + 3


def test_mesh_path_cannot_leave_the_package(package):
    text = urdf_of(package).read_text().replace(
        "package://example_1/meshes/base_link.STL", "package://example_1/../../secret.STL", 1)
    urdf_of(package).write_text(text)
    with pytest.raises(LoadError, match="outside the package"):
        sw2sim.load_package(package)


def test_wrong_package_name_is_explained(package):
    text = urdf_of(package).read_text().replace("package://example_1/", "package://Example_1/")
    urdf_of(package).write_text(text)
    with pytest.raises(LoadError, match="names package 'Example_1'"):
        sw2sim.load_package(package)


def test_entities_are_not_expanded(package):
    text = urdf_of(package).read_text().replace(
        "<robot", '<!DOCTYPE robot [<!ENTITY x SYSTEM "file:///etc/passwd">]>\n<robot', 1)
    text = text.replace('name="example_1">', 'name="&x;">', 1)
    urdf_of(package).write_text(text.split("\n", 1)[1] if text.startswith("<?xml") else text)
    try:
        spec = sw2sim.load_package(package)
    except LoadError:
        return  # refused: fine
    assert "root:" not in spec.modelname
