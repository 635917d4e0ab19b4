"""`sw2sim convert` repairs what has one right answer, reports each repair, and leaves the
user's package as it was; `--strict` repairs nothing.

The packages are written as the exporter writes them (exporter_packages.py) or copied from
the examples, then given one fault each, as packages people really export have them.
"""

from __future__ import annotations

import hashlib
import re
import shutil
from pathlib import Path

import mujoco
import numpy as np
import pytest
import trimesh
from hypothesis import given, settings
from hypothesis import strategies as st

from sw2sim.check import Options, check, check_package
from sw2sim.check.repairs import balanced
from sw2sim.cli import main
from exporter_packages import FOUR_WHEELER_NESTED, ORIGINAL_3_DOF_ARM, REAL_EXPORTS, write_export
from packages import copy_example, edit, edit_re, line_of, urdf_of

FAST = dict(deadline=None, derandomize=True, database=None, max_examples=12)


def snapshot(folder: Path) -> dict[str, str]:
    """Every file under `folder` and the hash of its bytes."""
    return {p.relative_to(folder).as_posix(): hashlib.sha256(p.read_bytes()).hexdigest()
            for p in sorted(folder.rglob("*")) if p.is_file()}


def convert(package: Path, out: Path, *flags: str, capsys=None) -> tuple[int, str]:
    status = main(["convert", str(package), "-o", str(out), *flags])
    said = capsys.readouterr() if capsys else None
    return status, (said.out + said.err if said else "")


def compiled(out: Path) -> mujoco.MjModel:
    return mujoco.MjModel.from_xml_path(str(out / "scene.xml"))


def repairs_in_readme(out: Path) -> str:
    text = (out / "README.md").read_text()
    assert "## Repairs" in text, text
    return text.split("## Repairs", 1)[1].split("\n## ", 1)[0]


def _mimic_of_missing_joint(folder: Path) -> Path:
    package, urdf = _arm(folder)
    edit_re(urdf, r'(name="end_arm_joint".*?)(</joint>)',
            r'\1<mimic joint="midle_arm_joint" multiplier="1" />\n  \2')
    return package


# -- the exporter's default limits ----------------------------------------------------------

def test_a_1_4_export_with_default_limits_converts_with_its_joints_free(tmp_path, capsys):
    package = write_export(ORIGINAL_3_DOF_ARM, tmp_path)
    before = snapshot(package)
    status, said = convert(package, tmp_path / "out", capsys=capsys)
    assert status == 0, said
    assert snapshot(package) == before
    defaults = [f for f in check(package, stability=False).findings
                if f.rule == "limit-exporter-default"]
    assert len(defaults) == 2
    model = compiled(tmp_path / "out")
    for finding in defaults:
        joint = re.search(r'joint "([^"]+)"', finding.message).group(1)
        j = model.joint(joint).id
        assert not model.jnt_limited[j]                       # turns freely
        assert joint not in {model.joint(model.actuator_trnid[a, 0]).name
                             for a in range(model.nu)}          # and is not driven
    section = repairs_in_readme(tmp_path / "out")
    assert section.count("[limit-exporter-default]") == 2
    assert "turns freely" in section and "--lock-default-limits" in section
    # The line each repair names is the line of the <limit> in the user's URDF.
    urdf = urdf_of(package)
    lines = [int(n) for n in re.findall(r"\.urdf:(\d+)`\*\* \[limit-exporter-default\]", section)]
    assert lines == [f.line for f in defaults]
    assert all("<limit" in urdf.read_text().splitlines()[n - 1] for n in lines)
    assert "error (ROS packaging only) [package-format-missing]" in said


def test_locking_default_limits_makes_those_joints_fixed(tmp_path, capsys):
    package = write_export(ORIGINAL_3_DOF_ARM, tmp_path)
    status, said = convert(package, tmp_path / "out", "--lock-default-limits", capsys=capsys)
    assert status == 0, said
    model = compiled(tmp_path / "out")
    report = check(package, stability=False)
    locked = [re.search(r'joint "([^"]+)"', f.message).group(1) for f in report.findings
              if f.rule == "limit-exporter-default"]
    names = {model.joint(j).name for j in range(model.njnt)}
    assert locked and not set(locked) & names
    assert "locked at its home pose" in repairs_in_readme(tmp_path / "out")


def test_strict_repairs_nothing_and_writes_nothing(tmp_path, capsys):
    package = write_export(ORIGINAL_3_DOF_ARM, tmp_path)
    status, said = convert(package, tmp_path / "out", "--strict", capsys=capsys)
    assert status == 1
    assert "Convert repairs it" not in said
    assert not (tmp_path / "out").exists() or not any((tmp_path / "out").iterdir())


def test_check_says_what_convert_would_repair(tmp_path):
    report = check(write_export(ORIGINAL_3_DOF_ARM, tmp_path), stability=False)
    assert report.status == 1                      # the package still has errors
    assert report.repaired and not report.simulation_stoppers
    assert "Convert repairs it:" in report.format()
    assert '"repair":' in report.to_json()


# -- mesh paths ------------------------------------------------------------------------------

def _arm(tmp_path) -> tuple[Path, Path]:
    package = copy_example(3, tmp_path)
    return package, urdf_of(package)


@pytest.mark.parametrize("written", [
    "package://example_3/meshes/BASE_LINK.stl",          # capitals differ
    "package://example_3/meshes\\base_link.STL",         # a backslash
    "package://example_3/base_link.STL",                 # a folder left out (ROS 2 install)
    "file:///C:/Users/student/Desktop/example_3/meshes/base_link.STL",   # the PC's own path
    "package://Example3/meshes/base_link.STL",           # another package name
])
def test_a_mesh_path_that_means_one_file_is_repaired(tmp_path, capsys, written):
    package, urdf = _arm(tmp_path)
    edit(urdf, "package://example_3/meshes/base_link.STL", written, count=2)
    before = snapshot(package)
    report = check(package, stability=False)
    problem = [f for f in report.findings if f.repair and "base_link" in f.repair + f.message]
    assert problem, report.format()
    assert problem[0].line == line_of(urdf, written.replace("\\", "\\"))
    assert not report.simulation_stoppers, report.format()
    status, said = convert(package, tmp_path / "out", capsys=capsys)
    assert status == 0, said
    assert snapshot(package) == before
    model = compiled(tmp_path / "out")
    assert model.nmesh == 3                      # base, middle and end arm, all found
    assert "meshes/base_link.STL" in repairs_in_readme(tmp_path / "out")


def test_a_mesh_path_that_could_mean_two_files_names_both_and_is_not_repaired(tmp_path, capsys):
    package, urdf = _arm(tmp_path)
    (package / "meshes" / "old").mkdir()
    shutil.copy(package / "meshes" / "base_link.STL", package / "meshes" / "old" / "BASE_LINK.stl")
    edit(urdf, "package://example_3/meshes/base_link.STL", "package://example_3/base_link.stl",
         count=2)
    report = check(package, stability=False)
    [finding] = [f for f in report.findings if f.rule == "mesh-not-found"]
    assert finding.repair is None
    assert "meshes/base_link.STL" in finding.message and "meshes/old/BASE_LINK.stl" in finding.message
    status, _ = convert(package, tmp_path / "out", capsys=capsys)
    assert status == 1


def test_the_file_that_matches_in_capitals_too_is_the_one_meant_and_said_so(tmp_path, capsys):
    """A Windows path (a backslash) to base_link.STL, with a lower-case copy beside it, as
    packages edited on Windows and then on Linux hold: the exact name is the file meant."""
    from sw2sim.mesh_paths import matches
    package, urdf = _arm(tmp_path)
    shutil.copy(package / "meshes" / "base_link.STL", package / "meshes" / "base_link.stl")
    edit(urdf, "package://example_3/meshes/base_link.STL",
         "package://example_3/meshes\\base_link.STL", count=2)
    files = [Path("meshes/base_link.STL"), Path("meshes/base_link.stl")]
    assert matches(files, "package://example_3/meshes\\base_link.STL") == [files[0]]
    assert matches(files, "package://example_3/meshes/Base_Link.stl") == files
    report = check(package, stability=False)
    [finding] = [f for f in report.findings if f.rule == "mesh-not-found"]
    assert "names no single file" not in finding.message
    assert finding.repair == ("the mesh is read from meshes/base_link.STL, the file whose name "
                              "matches the path's exactly, capitals too (beside it, "
                              "meshes/base_link.stl differs in capitals only)")
    status, said = convert(package, tmp_path / "out", capsys=capsys)
    assert status == 0, said


def test_a_mesh_path_that_means_no_file_names_the_closest(tmp_path):
    package, urdf = _arm(tmp_path)
    edit(urdf, "package://example_3/meshes/base_link.STL", "package://example_3/meshes/base_lnk.STL",
         count=2)
    [finding] = [f for f in check(package, stability=False).findings if f.rule == "mesh-not-found"]
    assert finding.repair is None
    assert "the closest files are meshes/base_link.STL" in finding.message


# -- effort, velocity, inertia ------------------------------------------------------------

def test_zero_effort_gives_no_force_limit(tmp_path, capsys):
    package, urdf = _arm(tmp_path)
    edit(urdf, 'effort="1000"', 'effort="0"', count=2)
    status, said = convert(package, tmp_path / "out", capsys=capsys)
    assert status == 0, said
    model = compiled(tmp_path / "out")
    assert model.nu and not model.actuator_forcelimited.any() and not model.jnt_actfrclimited.any()
    assert repairs_in_readme(tmp_path / "out").count("[effort-not-positive]") == 2


def _break_triangle(urdf: Path, shortfall: float) -> None:
    """Give the middle arm link a diagonal inertia whose izz exceeds ixx + iyy by `shortfall`
    of itself."""
    c = 0.02
    a = b = c * (1 - shortfall) / 2
    edit_re(urdf, r'(name="middle_arm_link">.*?<inertia\s+)ixx="[^"]*"\s+ixy="[^"]*"\s+ixz="[^"]*"'
            r'\s+iyy="[^"]*"\s+iyz="[^"]*"\s+izz="[^"]*"',
            rf'\1ixx="{a!r}" ixy="0" ixz="0" iyy="{b!r}" iyz="0" izz="{c!r}"')


def test_an_inertia_short_by_rounding_is_balanced(tmp_path, capsys):
    package, urdf = _arm(tmp_path)
    _break_triangle(urdf, 2e-5)
    [finding] = [f for f in check(package, stability=False).findings if f.rule == "inertia-triangle"]
    assert finding.repair and "rounding" in finding.repair
    status, said = convert(package, tmp_path / "out", capsys=capsys)
    assert status == 0, said
    model = compiled(tmp_path / "out")
    a, b, c = sorted(model.body_inertia[model.body("middle_arm_link").id])
    assert a + b >= c and c == pytest.approx(0.02, rel=1e-9)


def test_an_inertia_short_by_more_than_rounding_stops_convert(tmp_path, capsys):
    package, urdf = _arm(tmp_path)
    _break_triangle(urdf, 0.2)
    [finding] = [f for f in check(package, stability=False).findings if f.rule == "inertia-triangle"]
    assert finding.repair is None
    assert convert(package, tmp_path / "out", capsys=capsys)[0] == 1


def test_mujoco_refuses_a_shortfall_the_check_used_to_let_pass(tmp_path):
    package, urdf = _arm(tmp_path)
    _break_triangle(urdf, 1e-11)
    report = check(package, stability=False)
    assert "inertia-triangle" in report.rules()


@given(st.floats(1e-14, 1e-3), st.floats(0.0, 3.1), st.floats(0.0, 3.1))
@settings(**FAST)
def test_balancing_satisfies_the_triangle_and_keeps_the_axes(shortfall, yaw, pitch):
    c = 1.0
    moments = np.array([(1 - shortfall) * 0.3, (1 - shortfall) * 0.7, c])
    turn = trimesh.transformations.euler_matrix(0, pitch, yaw)[:3, :3]
    tensor = turn @ np.diag(moments) @ turn.T
    fixed = balanced(tensor)
    a, b, c2 = np.linalg.eigvalsh(fixed)
    assert a + b >= c2
    assert c2 == pytest.approx(c, rel=1e-12)
    assert np.allclose(np.linalg.eigh(fixed)[1][:, 2] ** 2, turn[:, 2] ** 2, atol=1e-6)


# -- masses ------------------------------------------------------------------------------------

def _ten_grams(tmp_path) -> Path:
    """The four-wheeler as exported, weighing 10 g in all, with meshes that are not closed."""
    package = write_export(FOUR_WHEELER_NESTED, tmp_path)
    urdf = urdf_of(package)
    total = sum(float(v) for v in re.findall(r'<mass\s+value="([^"]+)"', urdf.read_text()))
    text = re.sub(r'(<mass\s+value=")([^"]+)"',
                  lambda m: f'{m.group(1)}{float(m.group(2)) * 0.01 / total!r}"', urdf.read_text())
    urdf.write_text(text)
    for stl in (package / "meshes").glob("*.STL"):
        mesh = trimesh.load(stl)
        mesh.update_faces(np.arange(len(mesh.faces)) != 0)   # one triangle gone: not closed
        mesh.export(stl)
    return package


def test_a_ten_gram_robot_is_flagged_on_every_link_though_its_meshes_are_open(tmp_path):
    package = _ten_grams(tmp_path)
    report = check(package, stability=False)
    flagged = [f for f in report.findings if f.rule == "density-implausible"]
    assert len(flagged) == len(FOUR_WHEELER_NESTED.links), report.format()
    assert all("convex hull" in f.message for f in flagged)
    assert all(f.repair is None for f in flagged)      # only with --density


def test_density_recomputes_the_masses_from_the_meshes(tmp_path, capsys):
    package = _ten_grams(tmp_path)
    status, said = convert(package, tmp_path / "out", "--density", "2700", capsys=capsys)
    assert status == 0, said
    model = compiled(tmp_path / "out")
    for link in FOUR_WHEELER_NESTED.links:
        mesh = trimesh.load(package / "meshes" / f"{link.name}.STL")
        hull = mesh.convex_hull
        # (MuJoCo writes its model file with six significant digits)
        assert model.body_mass[model.body(link.name).id] == pytest.approx(2700 * hull.volume,
                                                                           rel=1e-5)
    assert repairs_in_readme(tmp_path / "out").count("[density-implausible]") == len(
        FOUR_WHEELER_NESTED.links)


def test_density_must_be_a_density(capsys, tmp_path):
    package, _ = _arm(tmp_path)
    with pytest.raises(SystemExit):
        main(["convert", str(package), "-o", str(tmp_path / "o"), "--density", "2.7e6"])
    assert "kg/m^3" in capsys.readouterr().err


# -- mimic -----------------------------------------------------------------------------------

def test_a_mimic_of_a_missing_joint_names_the_closest_and_is_dropped(tmp_path, capsys):
    package = _mimic_of_missing_joint(tmp_path)
    urdf = urdf_of(package)
    [finding] = [f for f in check(package, stability=False).findings
                 if f.rule == "mimic-joint-missing"]
    assert "'middle_arm_joint'" in finding.message
    assert finding.line == line_of(urdf, "midle_arm_joint")
    assert 'mimic joint="middle_arm_joint"' in finding.fix
    status, said = convert(package, tmp_path / "out", capsys=capsys)
    assert status == 0, said
    assert compiled(tmp_path / "out").neq == 0
    assert "[mimic-joint-missing]" in repairs_in_readme(tmp_path / "out")


def test_a_good_mimic_is_kept_as_an_equality_and_said_so(tmp_path, capsys):
    package, urdf = _arm(tmp_path)
    edit_re(urdf, r'(name="end_arm_joint".*?)(</joint>)',
            r'\1<mimic joint="middle_arm_joint" multiplier="-1" />\n  \2')
    assert convert(package, tmp_path / "out", capsys=capsys)[0] == 0
    assert compiled(tmp_path / "out").neq == 1
    readme = (tmp_path / "out" / "README.md").read_text()
    assert "`end_arm_joint` follows `middle_arm_joint`" in readme
    assert "## Repairs" not in readme


# -- every repair at once, and the property ----------------------------------------------------

FAULTS = {
    "mesh-case": lambda urdf: edit(urdf, "meshes/end_arm_link.STL", "meshes/END_ARM_LINK.stl",
                                   count=2),
    "backslash": lambda urdf: edit(urdf, "meshes/middle_arm_link.STL",
                                   "meshes\\middle_arm_link.STL", count=2),
    "default-limit": lambda urdf: edit_re(urdf, r'lower="-0\.7854"\s+upper="0\.7854"\s+'
                                          r'effort="1000"\s+velocity="2"',
                                          'lower="0" upper="0" effort="0" velocity="0"'),
    "zero-effort": lambda urdf: edit(urdf, 'effort="1000"', 'effort="0"'),
    "triangle": lambda urdf: _break_triangle(urdf, 1e-4),
    "mimic": lambda urdf: edit_re(urdf, r'(name="end_arm_joint".*?)(</joint>)',
                                  r'\1<mimic joint="arm_joint" />\n  \2'),
}


@given(st.sets(st.sampled_from(sorted(FAULTS)), min_size=1), st.booleans())
@settings(**FAST)
def test_a_repaired_model_compiles_and_steps_two_seconds(tmp_path_factory, faults, lock):
    folder = tmp_path_factory.mktemp("faults")
    package, urdf = _arm(folder)
    for fault in sorted(faults):
        FAULTS[fault](urdf)
    before = snapshot(package)
    ctx = check_package(package, stability=False, options=Options(lock_default_limits=lock))
    if ctx.report.simulation_stoppers:     # then the report must say why
        assert all(f.message and f.fix for f in ctx.report.simulation_stoppers)
        return
    out = folder / "out"
    assert main(["convert", str(package), "-o", str(out)] +
                (["--lock-default-limits"] if lock else [])) == 0
    assert snapshot(package) == before
    model = compiled(out)
    data = mujoco.MjData(model)
    while data.time < 2.0:
        mujoco.mj_step(model, data)
    assert np.all(np.isfinite(data.qpos)) and np.all(np.isfinite(data.qvel))
    assert len(ctx.report.repaired) >= len(faults) - ("zero-effort" in faults and
                                                      "default-limit" in faults)


def test_every_fault_at_once_converts_with_a_repair_for_each(tmp_path, capsys):
    package, urdf = _arm(tmp_path)
    for fault in FAULTS.values():
        fault(urdf)
    status, said = convert(package, tmp_path / "out", capsys=capsys)
    assert status == 0, said
    section = repairs_in_readme(tmp_path / "out")
    for rule_id in ("mesh-not-found", "limit-exporter-default", "effort-not-positive",
                    "inertia-triangle", "mimic-joint-missing"):
        assert f"[{rule_id}]" in section, rule_id


def test_a_joint_without_axis_or_travel_is_locked_as_a_frame(tmp_path, capsys):
    package, urdf = _arm(tmp_path)
    edit_re(urdf, r'(name="end_arm_joint".*?<axis\s+)xyz="[^"]*"', r'\1xyz="0 0 0"')
    edit_re(urdf, r'(name="end_arm_joint".*?<limit\s+)lower="[^"]*"\s+upper="[^"]*"\s+'
            r'effort="[^"]*"\s+velocity="[^"]*"', r'\1lower="0" upper="0" effort="0" velocity="0"')
    report = check(package, stability=False)
    assert {"axis-zero", "limit-exporter-default"} <= report.rules()
    assert all("locked" in f.repair for f in report.findings
               if f.rule in ("axis-zero", "limit-exporter-default"))
    status, said = convert(package, tmp_path / "out", capsys=capsys)
    assert status == 0, said
    model = compiled(tmp_path / "out")
    assert "end_arm_joint" not in {model.joint(j).name for j in range(model.njnt)}


def test_a_zero_axis_on_a_joint_with_travel_stays_an_error(tmp_path, capsys):
    package, urdf = _arm(tmp_path)
    edit_re(urdf, r'(name="end_arm_joint".*?<axis\s+)xyz="[^"]*"', r'\1xyz="0 0 0"')
    [finding] = [f for f in check(package, stability=False).findings if f.rule == "axis-zero"]
    assert finding.repair is None
    assert convert(package, tmp_path / "out", capsys=capsys)[0] == 1


@pytest.mark.parametrize("name", sorted(REAL_EXPORTS))
def test_every_export_of_the_exporters_own_examples_converts(tmp_path, capsys, name):
    package = write_export(REAL_EXPORTS[name], tmp_path)
    status, said = convert(package, tmp_path / "out", capsys=capsys)
    if status:   # only the early export's all-zero inertias stop it, and it says how on
        assert "--density" in said, said
        status, said = convert(package, tmp_path / "out", "--density", "2700", capsys=capsys)
    assert status == 0, said
    compiled(tmp_path / "out")
