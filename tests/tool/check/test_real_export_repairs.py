"""The last problems of real exported packages, those plain MuJoCo refuses too: a tool frame
with a placeholder inertia, moving links of zero mass, COLLADA visuals, and meshes left as
Git LFS pointers. Each is tested from the finding `sw2sim check` writes, through what
`sw2sim convert` reports, to the converted model compiling and simulating in MuJoCo.

The packages are written as the exporter writes them (exporter_packages.py), then given
the one fault each of those packages had.
"""

from __future__ import annotations

import re
import shlex
from pathlib import Path

import mujoco
import numpy as np
import pytest
import trimesh

from sw2sim.check import check
from sw2sim.cli import main
from sw2sim.errors import LoadError
from sw2sim.loader import load_package
from sw2sim.mesh_formats import beside, lfs_pointer
from exporter_packages import FOUR_WHEELER_NESTED, ORIGINAL_3_DOF_ARM, write_export
from packages import edit, edit_re, line_of, urdf_of
from test_mesh_rules import LFS_POINTER
from test_repairs import compiled, convert, repairs_in_readme, snapshot

# The placeholder of the package measured: a unit tensor stretched along z.
PLACEHOLDER = 'ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="100"'


def simulated(out: Path, seconds: float = 2.0) -> mujoco.MjData:
    """The converted model, stepped for `seconds` from its rest pose; its state is finite."""
    model = compiled(out)
    data = mujoco.MjData(model)
    while data.time < seconds:
        mujoco.mj_step(model, data)
    assert np.all(np.isfinite(data.qpos)) and np.all(np.isfinite(data.qvel))
    return data


# -- a tool frame with a placeholder inertia ---------------------------------------------------

def _tool_frame(folder: Path, mass: str, joint: str = "fixed") -> Path:
    """The 1.4 arm with a tool frame at the end of link3: a link without visual or collision
    geometry whose <inertial> is a placeholder."""
    package = write_export(ORIGINAL_3_DOF_ARM, folder)
    axis = '<axis xyz="0 0 1" /><limit lower="-1" upper="1" effort="1" velocity="1" />' \
        if joint == "revolute" else ""
    edit(urdf_of(package), "</robot>",
         f'  <link name="tool0">\n    <inertial>\n      <origin xyz="0 0 0" rpy="0 0 0" />\n'
         f'      <mass value="{mass}" />\n      <inertia {PLACEHOLDER} />\n'
         f'    </inertial>\n  </link>\n'
         f'  <joint name="tool0_joint" type="{joint}">\n'
         f'    <origin xyz="0.18 0 0" rpy="0 0 0" />\n    <parent link="link3" />\n'
         f'    <child link="tool0" />{axis}\n  </joint>\n</robot>')
    return package


def test_a_massless_tool_frame_with_a_placeholder_inertia_converts_with_none(tmp_path, capsys):
    package = _tool_frame(tmp_path, "0")
    before = snapshot(package)
    report = check(package, stability=False)
    [finding] = [f for f in report.findings if f.rule == "inertia-triangle"]
    assert finding.line == line_of(urdf_of(package), PLACEHOLDER)
    assert "1 + 1 = 2 is less than 100" in finding.message
    assert 'link "tool0" has no visual or collision geometry and no mass' in finding.repair
    assert "Convert repairs it: link \"tool0\"" in finding.format()
    assert finding.fix.startswith("give the frame a tensor a body can have")
    assert not report.simulation_stoppers, report.format()

    assert convert(package, tmp_path / "strict", "--strict", capsys=capsys)[0] == 1
    status, said = convert(package, tmp_path / "out", capsys=capsys)
    assert status == 0, said
    assert "[inertia-triangle]" in said and "Convert repairs it: link \"tool0\"" in said
    assert "[inertia-triangle]" in repairs_in_readme(tmp_path / "out")
    assert snapshot(package) == before
    model = compiled(tmp_path / "out")
    tool = model.body("tool0").id
    assert model.body_mass[tool] == 0 and not model.body_inertia[tool].any()
    simulated(tmp_path / "out")


def test_a_moving_tool_frame_with_a_mass_gets_a_small_sphere(tmp_path, capsys):
    package = _tool_frame(tmp_path, "0.05", joint="revolute")
    [finding] = [f for f in check(package, stability=False).findings
                 if f.rule == "inertia-triangle"]
    assert "its mass, 0.05 kg, is kept" in finding.repair
    status, said = convert(package, tmp_path / "out", capsys=capsys)
    assert status == 0, said
    model = compiled(tmp_path / "out")
    tool = model.body("tool0").id
    radius = (3 * 0.05 / (4 * np.pi * 1000)) ** (1 / 3)     # a sphere of water
    assert model.body_mass[tool] == pytest.approx(0.05)
    # (MuJoCo writes its model file with six significant digits)
    assert model.body_inertia[tool] == pytest.approx([0.4 * 0.05 * radius ** 2] * 3, rel=1e-5)
    assert model.body_inertia[tool][0] < 1e-4          # nothing like the placeholder's 1 kg m^2
    simulated(tmp_path / "out")


def test_a_frame_whose_placeholder_is_not_positive_definite_is_repaired_alike(tmp_path, capsys):
    package = _tool_frame(tmp_path, "0.05")
    edit(urdf_of(package), PLACEHOLDER, 'ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" izz="1"')
    [finding] = [f for f in check(package, stability=False).findings
                 if f.rule == "inertia-not-positive-definite"]
    assert "a solid sphere of that mass at 1000 kg/m^3" in finding.repair
    status, said = convert(package, tmp_path / "out", capsys=capsys)
    assert status == 0, said
    simulated(tmp_path / "out")


def test_a_wrong_tensor_of_a_plausible_size_on_a_link_with_geometry_is_not_repaired(
        tmp_path, capsys):
    """A link with a mesh is a real part: a wrong tensor of the size its mass allows is the
    user's to correct."""
    package = write_export(ORIGINAL_3_DOF_ARM, tmp_path)
    edit_re(urdf_of(package), r'(name="link3">.*?)ixx="[^"]*"\s+ixy="[^"]*"\s+ixz="[^"]*"\s+'
            r'iyy="[^"]*"\s+iyz="[^"]*"\s+izz="[^"]*"',
            r'\1ixx="2e-05" ixy="0" ixz="0" iyy="2e-05" iyz="0" izz="7e-05"')
    [finding] = [f for f in check(package, stability=False).findings
                 if f.rule == "inertia-triangle"]
    assert finding.repair is None
    assert convert(package, tmp_path / "out", capsys=capsys)[0] == 1


# The hand-edited arm measured: a grasping frame of 0.1 g at the end of the arm, with a small
# visual box to show it and the placeholder tensor (1, 100, 1) kg m^2.
GRASPING = 'ixx="1" ixy="0" ixz="0" iyy="100" iyz="0" izz="1"'


def _grasping_frame(folder: Path) -> Path:
    package = write_export(ORIGINAL_3_DOF_ARM, folder)
    edit(urdf_of(package), "</robot>",
         '  <link\n    name="grasping_frame">\n    <inertial>\n'
         '      <origin\n        xyz="0 0 0"\n        rpy="0 0 0" />\n'
         '      <mass\n        value="0.0001" />\n'
         f'      <inertia\n        {GRASPING} />\n    </inertial>\n'
         '    <visual>\n      <origin\n        xyz="0 0 0"\n        rpy="0 0 0" />\n'
         '      <geometry>\n        <box\n          size="0.01 0.01 0.01" />\n'
         '      </geometry>\n    </visual>\n  </link>\n'
         '  <joint\n    name="grasping_frame_joint"\n    type="fixed">\n'
         '    <origin\n      xyz="0.18 0 0"\n      rpy="0 0 0" />\n'
         '    <parent\n      link="link3" />\n    <child\n      link="grasping_frame" />\n'
         '  </joint>\n</robot>')
    return package


def test_a_placeholder_absurd_for_its_mass_is_repaired_whatever_the_geometry(tmp_path, capsys):
    package = _grasping_frame(tmp_path)
    before = snapshot(package)
    report = check(package, stability=False)
    [finding] = [f for f in report.findings if f.rule == "inertia-triangle"]
    assert "1 + 1 = 2 is less than 100" in finding.message
    assert 'link "grasping_frame" weighs 0.0001 kg, and its largest moment, 100 kg m^2' \
        in finding.repair
    assert "uniform solid of that mass" in finding.repair
    assert finding.fix.startswith("write the part's real tensor")
    assert not report.simulation_stoppers, report.format()
    # 0.1 g in the 1 cm^3 box is 100 kg/m^3, the range's edge, whatever the volume's last digit
    assert "density-implausible" not in report.rules(), report.format()

    status, said = convert(package, tmp_path / "out", capsys=capsys)    # default options
    assert status == 0, said
    assert "[inertia-triangle]" in said and 'Convert repairs it: link "grasping_frame"' in said
    assert "[inertia-triangle]" in repairs_in_readme(tmp_path / "out")
    assert snapshot(package) == before
    model = compiled(tmp_path / "out")
    # a 1 cm cube of 0.1 g: m s^2 / 6 about every axis; the parent keeps its own inertia
    cube = 1e-4 * 0.01 ** 2 / 6
    assert model.body_mass[model.body("grasping_frame").id] == pytest.approx(1e-4)
    assert model.body_inertia[model.body("grasping_frame").id] == pytest.approx(
        [cube] * 3, rel=1e-4)
    assert model.body_inertia[model.body("link3").id].max() < 1e-4
    simulated(tmp_path / "out")


def test_the_placeholder_bound_is_the_model_size(tmp_path):
    """The same tensor on a link whose mass can hold it (1 t within the arm's size) is a real,
    if wrong, tensor: not repaired."""
    package = _grasping_frame(tmp_path)
    edit(urdf_of(package), 'value="0.0001"', 'value="1000"')
    [finding] = [f for f in check(package, stability=False).findings
                 if f.rule == "inertia-triangle"]
    assert finding.repair is None


def test_solid_properties_match_trimesh():
    from sw2sim.check.trimeshes import solid_properties
    shape = trimesh.creation.box(extents=[0.1, 0.2, 0.3])
    shape.apply_translation([1, 2, 3])
    volume, centroid, tensor = solid_properties(shape.triangles)
    assert volume == pytest.approx(shape.volume)
    assert centroid == pytest.approx(shape.center_mass)
    assert tensor == pytest.approx(shape.moment_inertia / shape.density, abs=1e-12)


# -- moving links of zero mass -------------------------------------------------------------

def _massless_wheels(folder: Path) -> Path:
    """The four-wheeler with three of its wheels exported at zero mass."""
    package = write_export(FOUR_WHEELER_NESTED, folder)
    edit(urdf_of(package), 'value="0.0948368282302419"', 'value="0"', count=3)
    return package


def _command(fix: str) -> str:
    found = re.match(r"`(sw2sim convert [^`]+)`", fix)
    assert found, fix
    return found.group(1)


def test_zero_masses_stay_errors_whose_fix_is_the_command_that_converts(tmp_path, capsys):
    package = _massless_wheels(tmp_path)
    report = check(package, stability=False)
    zero = [f for f in report.findings if f.rule == "mass-not-positive"]
    assert len(zero) == 3 and all(f.repair is None for f in zero)
    command = _command(zero[0].fix)
    assert {f.fix for f in zero} == {zero[0].fix}
    assert command == shlex.join(["sw2sim", "convert", str(package), "-o",
                                  f"{package}_mujoco", "--density", "2700"])
    assert "aluminium 6061" in zero[0].fix and "steel: 7850" in zero[0].fix \
        and "ABS: 1040" in zero[0].fix
    assert convert(package, tmp_path / "plain", capsys=capsys)[0] == 1

    assert main(shlex.split(command)[1:]) == 0
    said = capsys.readouterr().out
    assert said.count("[mass-not-positive]") == 3 and "2700 kg/m^3 (--density)" in said
    out = Path(f"{package}_mujoco")
    assert repairs_in_readme(out).count("[mass-not-positive]") == 3
    model = compiled(out)
    for link in FOUR_WHEELER_NESTED.links[1:4]:
        volume = trimesh.load(package / "meshes" / f"{link.name}.STL").volume
        assert model.body_mass[model.body(link.name).id] == pytest.approx(2700 * volume, rel=1e-5)
    simulated(out)


@pytest.mark.parametrize("given, out", [
    ("4_WHEELER_NESTED_description", "4_WHEELER_NESTED_description_mujoco"),
    ("4_WHEELER_NESTED_description/urdf/4_WHEELER_NESTED_description.urdf",
     "4_WHEELER_NESTED_description_mujoco"),
    (".", "../4_WHEELER_NESTED_description_mujoco"),
])
def test_the_command_names_the_package_as_the_user_did(tmp_path, monkeypatch, capsys, given, out):
    package = _massless_wheels(tmp_path)
    monkeypatch.chdir(package if given == "." else tmp_path)
    [fix] = {f.fix for f in check(given, stability=False).findings
             if f.rule == "mass-not-positive"}
    command = _command(fix)
    assert command == f"sw2sim convert {given} -o {out} --density 2700"
    assert main(shlex.split(command)[1:]) == 0, capsys.readouterr()
    compiled(Path(out))


def test_under_convert_the_command_is_the_users_own_with_density_added(tmp_path, capsys):
    package = _massless_wheels(tmp_path)
    out = tmp_path / "my models" / "wheels"
    status, said = convert(package, out, "--force", capsys=capsys)
    assert status == 1
    typed = shlex.join(["sw2sim", "convert", str(package), "-o", str(out), "--force"])
    suggested = f"{typed} --density 2700"
    assert said.count(f"`{suggested}` converts the package") == 3, said
    assert f"`{suggested}` (2700 kg/m^3: aluminium" in said
    assert main(shlex.split(suggested)[1:]) == 0
    compiled(out)


def test_with_density_given_the_fix_is_the_rules_own(tmp_path):
    from sw2sim.check import Options, check_package
    ctx = check_package(_massless_wheels(tmp_path), stability=False,
                        options=Options(density=2700))
    zero = [f for f in ctx.report.findings if f.rule == "mass-not-positive"]
    assert zero and all(f.repair and "sw2sim convert" not in f.fix for f in zero)


# -- COLLADA visuals -----------------------------------------------------------------------

def _collada_visuals(folder: Path, where: str = "meshes", beside_too: bool = True,
                     millimetres: bool = False) -> Path:
    """The four-wheeler whose <visual> meshes are COLLADA files in `where`, with the STL
    the exporter wrote beside each (in meshes/) when `beside_too`."""
    package = write_export(FOUR_WHEELER_NESTED, folder)
    urdf = urdf_of(package)
    (package / where).mkdir(exist_ok=True)
    for link in FOUR_WHEELER_NESTED.links:
        mesh = trimesh.load(package / "meshes" / f"{link.name}.STL")
        if millimetres:
            mesh.apply_scale(1000)
        dae = mesh.export(file_type="dae").decode()
        if millimetres:
            dae = dae.replace("<up_axis>", '<unit meter="0.001" name="millimeter" />\n'
                                           "    <up_axis>", 1)
        (package / where / f"{link.name}.dae").write_text(dae)
        # the <visual>'s mesh comes first; the <collision> keeps the STL
        edit(urdf, f"meshes/{link.name}.STL", f"{where}/{link.name}.dae")
    if not beside_too:
        assert where != "meshes"
    return package


def test_collada_visuals_are_read_from_the_stl_beside_them(tmp_path, capsys):
    package = _collada_visuals(tmp_path)
    before = snapshot(package)
    report = check(package, stability=False)
    formats = [f for f in report.findings if f.rule == "mesh-format"]
    assert len(formats) == len(FOUR_WHEELER_NESTED.links)
    assert not report.simulation_stoppers, report.format()
    for finding, link in zip(formats, FOUR_WHEELER_NESTED.links):
        assert finding.message.endswith(f'{link.name}.dae is a ".dae" file; MuJoCo reads '
                                        ".stl, .obj and .msh only")
        assert finding.repair == (f"the mesh is read from meshes/{link.name}.STL, the file of "
                                  f"the same name beside {link.name}.dae in a format MuJoCo "
                                  "reads")
    assert convert(package, tmp_path / "strict", "--strict", capsys=capsys)[0] == 1
    status, said = convert(package, tmp_path / "out", capsys=capsys)
    assert status == 0, said
    assert said.count("Convert repairs it: the mesh is read from meshes/") == len(formats)
    section = repairs_in_readme(tmp_path / "out")
    assert section.count("[mesh-format]") == len(formats)
    assert snapshot(package) == before
    model = compiled(tmp_path / "out")
    # visual and collision read the one STL of each link
    assert model.nmesh == len(FOUR_WHEELER_NESTED.links)
    assert sorted(p.name for p in (tmp_path / "out" / "assets").iterdir()) == sorted(
        f"{link.name}.STL" for link in FOUR_WHEELER_NESTED.links)
    simulated(tmp_path / "out")


def test_a_lower_case_stl_beside_a_collada_file_is_found(tmp_path, capsys):
    package = _collada_visuals(tmp_path, where="meshes/visual")
    (package / "meshes" / "visual" / "base_link.stl").write_bytes(
        (package / "meshes" / "base_link.STL").read_bytes())
    formats = {f.message.split(".dae")[0].rsplit("/", 1)[1]: f
               for f in check(package, stability=False).findings if f.rule == "mesh-format"}
    assert formats["base_link"].repair.startswith(
        "the mesh is read from meshes/visual/base_link.stl,")
    assert "converted to binary STL" in formats["back_left_link"].repair
    status, said = convert(package, tmp_path / "out", capsys=capsys)
    assert status == 0, said
    simulated(tmp_path / "out")


def test_a_collada_file_alone_is_converted_in_metres(tmp_path, capsys):
    package = _collada_visuals(tmp_path, where="meshes/visual", beside_too=False,
                               millimetres=True)
    report = check(package, stability=False)
    formats = [f for f in report.findings if f.rule == "mesh-format"]
    assert len(formats) == len(FOUR_WHEELER_NESTED.links)
    assert formats[0].repair == ("meshes/visual/base_link.dae is converted to binary STL with "
                                 "trimesh (in metres) and the model reads that; there is no "
                                 "readable file of the same name beside it")
    assert "mesh-units" not in report.rules()     # the <unit> is read: millimetres
    status, said = convert(package, tmp_path / "out", capsys=capsys)
    assert status == 0, said
    out = tmp_path / "out"
    readme = (out / "README.md").read_text()
    assert ("`assets/visual/base_link.dae.stl` converted to binary STL from "
            "`meshes/visual/base_link.dae`") in readme
    model = compiled(out)
    for link in FOUR_WHEELER_NESTED.links:
        exported = trimesh.load(package / "meshes" / f"{link.name}.STL")
        converted = trimesh.load(out / "assets" / "visual" / f"{link.name}.dae.stl")
        assert converted.extents == pytest.approx(exported.extents, rel=1e-6)
        assert model.mesh(f"{link.name}.dae").id >= 0
    simulated(out)


def test_a_mesh_nothing_can_read_is_not_repaired(tmp_path, capsys):
    package = _collada_visuals(tmp_path, where="meshes/visual", beside_too=False)
    (package / "meshes" / "visual" / "base_link.dae").write_text("<COLLADA><oops")
    report = check(package, stability=False)
    [broken] = [f for f in report.findings if f.rule == "mesh-format" and "base_link" in f.message]
    assert broken.repair is None and "mesh-unreadable" in report.rules()
    assert convert(package, tmp_path / "out", capsys=capsys)[0] == 1
    with pytest.raises(LoadError) as raised:      # as `sw2sim view` would load it
        load_package(package)
    assert "meshes/visual/base_link.dae" in str(raised.value)
    assert "cannot be converted: trimesh cannot read it" in str(raised.value)


def test_the_stl_beside_comes_before_an_obj_and_a_pointer_never_counts(tmp_path):
    (tmp_path / "part.dae").write_text("<COLLADA/>")
    assert beside(tmp_path / "part.dae") is None
    (tmp_path / "part.obj").write_text("v 0 0 0\n")
    assert beside(tmp_path / "part.dae") == tmp_path / "part.obj"
    (tmp_path / "part.STL").write_bytes(LFS_POINTER)
    assert lfs_pointer(tmp_path / "part.STL")
    assert beside(tmp_path / "part.dae") == tmp_path / "part.obj"
    (tmp_path / "part.STL").write_bytes(bytes(84))
    assert beside(tmp_path / "part.dae") == tmp_path / "part.STL"


# -- Git LFS pointers ----------------------------------------------------------------------

def test_a_git_lfs_pointer_is_named_with_git_lfs_pull(tmp_path, capsys):
    package = write_export(FOUR_WHEELER_NESTED, tmp_path)
    (package / "meshes" / "base_link.STL").write_bytes(LFS_POINTER)
    report = check(package, stability=False)
    [finding] = [f for f in report.findings if f.rule == "mesh-lfs-pointer"]
    assert finding.line == line_of(urdf_of(package), "meshes/base_link.STL")
    assert "base_link.STL is a Git LFS pointer (130 bytes of text), not the mesh" \
        in finding.message
    assert "git lfs pull" in finding.fix and finding.repair is None
    assert not {"mesh-unreadable", "mesh-empty", "mesh-ascii-stl"} & report.rules()

    status, said = convert(package, tmp_path / "out", capsys=capsys)
    assert status == 1 and "git lfs pull" in said
    with pytest.raises(LoadError) as raised:
        load_package(package)
    assert "meshes/base_link.STL is a Git LFS pointer" in str(raised.value)
    assert "git lfs pull" in str(raised.value)
    assert raised.value.line == finding.line


def test_a_collada_pointer_is_a_pointer_not_a_format(tmp_path):
    package = _collada_visuals(tmp_path)
    (package / "meshes" / "base_link.dae").write_bytes(LFS_POINTER)
    rules = [f.rule for f in check(package, stability=False).findings
             if "base_link.dae" in f.message]
    assert rules == ["mesh-lfs-pointer"]
