"""Every example package: exporter layout, valid URDF, meshes that match their inertials, a clean model."""

import shutil
import subprocess
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest
import trimesh
import yourdfpy

import sw2sim
import mujoco
from course.practices import PRACTICES, ROOT, design, package_dir

PACKAGES = [package_dir(p) for p in PRACTICES]
IDS = [p.name for p in PACKAGES]


def exporter_files(pkg: Path) -> list[str]:
    name = pkg.name
    return ["CMakeLists.txt", "package.xml", f"config/joint_names_{name}.yaml", "launch/display.launch",
            "launch/gazebo.launch", f"urdf/{name}.urdf", f"urdf/{name}.csv"]


@pytest.mark.parametrize("pkg", PACKAGES, ids=IDS)
def test_package_has_the_exporter_layout(pkg):
    missing = [f for f in exporter_files(pkg) if not (pkg / f).is_file()]
    assert not missing, f"{pkg.name} lacks {missing}"
    urdf = ET.parse(pkg / "urdf" / f"{pkg.name}.urdf").getroot()
    for link in urdf.iter("link"):
        if link.find("visual") is not None:
            assert (pkg / "meshes" / f"{link.get('name')}.STL").is_file()
    manifest = ET.parse(pkg / "package.xml").getroot()
    assert manifest.get("format") == "2" and manifest.findtext("name") == pkg.name


@pytest.mark.parametrize("practice", PRACTICES)
def test_package_is_what_the_design_writes(practice, tmp_path):
    """Nobody edited the generated files by hand: regenerating gives the same bytes."""
    written = design(practice).write(tmp_path)
    for path in written:
        rel = path.relative_to(tmp_path)
        committed = ROOT / "examples" / rel
        assert committed.read_bytes() == path.read_bytes(), (
            f"examples/{rel} differs from its design; run `python -m course.practices`")


@pytest.mark.skipif(shutil.which("check_urdf") is None, reason="check_urdf missing: run make setup")
@pytest.mark.parametrize("pkg", PACKAGES, ids=IDS)
def test_check_urdf_accepts_it(pkg):
    result = subprocess.run(["check_urdf", str(pkg / "urdf" / f"{pkg.name}.urdf")],
                            capture_output=True, text=True)
    assert result.returncode == 0, result.stdout + result.stderr
    assert "Successfully Parsed XML" in result.stdout


@pytest.mark.parametrize("pkg", PACKAGES, ids=IDS)
def test_yourdfpy_finds_every_mesh(pkg):
    robot = yourdfpy.URDF.load(str(pkg / "urdf" / f"{pkg.name}.urdf"))
    with_mesh = [lk for lk in robot.robot.links if lk.visuals]
    assert len(with_mesh) > 0
    assert len(robot.scene.geometry) == len(with_mesh), "a mesh was not found"


@pytest.mark.parametrize("pkg", PACKAGES, ids=IDS)
def test_inertials_equal_the_meshes_mass_properties(pkg):
    """Each URDF inertial matches its STL at the design's density, within 1 %."""
    robot = yourdfpy.URDF.load(str(pkg / "urdf" / f"{pkg.name}.urdf"), load_meshes=False)
    density = design(f"practice_{pkg.name.split('_')[-1]}").ALUMINIUM.density
    for link in robot.robot.links:
        if link.inertial is None:
            continue
        mesh = trimesh.load(pkg / "meshes" / f"{link.name}.STL")
        assert mesh.is_watertight, link.name
        mesh.density = density
        assert link.inertial.mass == pytest.approx(mesh.mass, rel=0.01), link.name
        assert link.inertial.origin[:3, 3] == pytest.approx(mesh.center_mass, abs=1e-4), link.name
        scale = np.abs(mesh.moment_inertia).max()
        assert np.allclose(link.inertial.inertia, mesh.moment_inertia, rtol=0.01, atol=0.01 * scale), link.name


@pytest.mark.parametrize("pkg", PACKAGES, ids=IDS)
@pytest.mark.parametrize("fixed_base", [True, False])
def test_model_compiles_and_steps_without_warnings(pkg, fixed_base):
    model = sw2sim.load_package(pkg, fixed_base=fixed_base).compile()
    data = mujoco.MjData(model)
    moving = (mujoco.mjtJoint.mjJNT_HINGE, mujoco.mjtJoint.mjJNT_SLIDE)
    dofs = [model.jnt_dofadr[j] for j in range(model.njnt) if model.jnt_type[j] in moving]
    rng = np.random.default_rng(0)
    for _ in range(1000):  # 2 s of small random pushes on every joint
        data.qfrc_applied[dofs] = rng.uniform(-0.5, 0.5, len(dofs))
        mujoco.mj_step(model, data)
    assert np.all(np.isfinite(data.qpos))
    warnings = {mujoco.mjtWarning(i).name: int(data.warning[i].number) for i in range(len(data.warning))
                if data.warning[i].number}
    assert not warnings, warnings
