"""The raw sample export (examples/Arm_Assembly) and the claims of the "Your own model" page."""

import shutil
from collections import Counter

import pytest

from sw2sim.check import check
from course.practices import ROOT, sample_export
from page_text import squash

PAGE = ROOT / "_pages" / "reference" / "03-your-own-model.md"
SAMPLE = ROOT / "examples" / sample_export.PACKAGE
# What the page says the check finds on the raw export, and how often.
FOUND = {"limit-exporter-default": 2, "mesh-empty": 1, "package-name-style": 1}


@pytest.fixture(scope="module")
def report():
    return check(SAMPLE, stability=False)


def test_the_sample_is_what_its_generator_writes(tmp_path):
    written = sample_export.write(tmp_path)
    for path in [*written, tmp_path / sample_export.PACKAGE / "meshes" / "end_arm_link.STL"]:
        rel = path.relative_to(tmp_path)
        assert (ROOT / "examples" / rel).read_bytes() == path.read_bytes(), (
            f"examples/{rel} differs from course/practices/sample_export.py; "
            "run `python -m course.practices`")


def test_the_check_finds_what_the_page_lists(report):
    assert Counter(f.rule for f in report.findings) == FOUND, report.format()
    assert report.status == 1
    text = PAGE.read_text()
    for rule in FOUND:
        assert f"**`{rule}`**" in text


def test_the_empty_mesh_is_the_exporters_80_byte_header(report):
    mesh = SAMPLE / "meshes" / f"{sample_export.EMPTY_MESH}.STL"
    assert mesh.stat().st_size == 80
    assert "80 bytes long" in squash(PAGE.read_text())


def test_the_pages_fixes_leave_only_the_warning_and_the_limits_as_ranges(tmp_path):
    """The fixes the page makes, made here the same way: errors gone, limits in MuJoCo."""
    import mujoco
    from sw2sim.cli import main

    package = tmp_path / sample_export.PACKAGE
    shutil.copytree(SAMPLE, package)
    shutil.copy(ROOT / "examples/example_3/meshes/end_arm_link.STL",
                package / "meshes" / "end_arm_link.STL")
    urdf = package / "urdf" / f"{sample_export.PACKAGE}.urdf"
    text = urdf.read_text()
    exported = '<limit\n      lower="0"\n      upper="0"\n      effort="0"\n      velocity="0" />'
    typed = '<limit\n      lower="-0.7854"\n      upper="0.7854"\n      effort="1000"\n      velocity="2" />'
    assert text.count(exported) == 2 and exported in PAGE.read_text() and typed in PAGE.read_text()
    urdf.write_text(text.replace(exported, typed))

    fixed = check(package)
    assert [f.rule for f in fixed.findings] == ["package-name-style"], fixed.format()
    assert fixed.status == 0 and fixed.stability is not None

    assert main(["convert", str(package), "-o", str(tmp_path / "arm_mujoco")]) == 0
    model = mujoco.MjModel.from_xml_path(str(tmp_path / "arm_mujoco" / "scene.xml"))
    hinges = [j for j in range(model.njnt) if model.jnt_type[j] == mujoco.mjtJoint.mjJNT_HINGE]
    assert len(hinges) == 2
    for j in hinges:
        assert list(model.jnt_range[j]) == pytest.approx([-0.7854, 0.7854])
    assert model.jnt_type[0] == mujoco.mjtJoint.mjJNT_FREE   # no world link: a loose base
    assert model.nu == 0                                       # no transmissions: no actuators
