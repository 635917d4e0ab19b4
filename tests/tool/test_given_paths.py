"""What a user gives the tool besides the package folder itself: a .zip of the export (as
Windows, PowerShell and macOS make them), the folder a download or a clone wraps around
it, or the package's urdf/ folder."""

import json
import os
import subprocess
import sys
import zipfile
from pathlib import Path

import pytest

from packages import copy_example, edit, urdf_of, zipped
from sw2sim import archive
from sw2sim.check import check
from sw2sim.package import LoadError, find_package


def summary(report) -> list[tuple[str, str, int | None]]:
    return sorted((f.rule, f.message.split(": ")[0], f.line) for f in report.findings)


def test_a_zip_is_checked_as_the_folder_it_holds_and_named_through_the_archive(tmp_path, monkeypatch):
    package = copy_example(4, tmp_path / "export")
    edit(urdf_of(package), 'effort="', 'effort="-')    # a finding with a file and a line
    zip_path = zipped(package, tmp_path / "example_4.zip")
    before = zip_path.read_bytes()
    monkeypatch.chdir(tmp_path)
    from_zip, from_folder = check("example_4.zip"), check(package)
    # The one difference: a folder's unsaved hand edits (the edit above is one) are worth a
    # warning, since `sw2sim edits save` saves into the folder; a .zip is only read.
    folder_only = [f for f in summary(from_folder) if f[0] == "hand-edits-unsaved"]
    assert folder_only and "hand-edits-unsaved" not in {f.rule for f in from_zip.findings}
    assert from_zip.findings and summary(from_zip) == sorted(set(summary(from_folder))
                                                             - set(folder_only))
    urdf = "urdf/example_4.urdf"
    assert {f.file for f in from_zip.findings if f.line} == {f"example_4.zip/example_4/{urdf}"}
    assert from_zip.path == "example_4.zip/example_4"
    assert zip_path.read_bytes() == before, "the archive is only read"


@pytest.mark.parametrize("style", ["backslashes", "macos"])
def test_zips_from_powershell_and_macos_load(tmp_path, style):
    package = copy_example(1, tmp_path / "export")
    zip_path = zipped(package, tmp_path / "p.zip", **{style: True})
    loaded = find_package(zip_path)
    assert loaded.name == "example_1"
    assert not list(loaded.root.rglob("._*")), "the __MACOSX copies are left out"
    assert sorted(p.relative_to(loaded.root).as_posix() for p in loaded.root.rglob("*")
                  if p.is_file()) == sorted(p.relative_to(package).as_posix()
                                            for p in package.rglob("*") if p.is_file())
    assert check(zip_path).status == 0


def test_the_command_converts_a_zip_and_leaves_no_unpacked_copy(tmp_path):
    package = copy_example(1, tmp_path / "export")
    zip_path = zipped(package, tmp_path / "example_1.zip", backslashes=True)
    scratch = tmp_path / "tmp"
    scratch.mkdir()
    env = {**os.environ, "TMPDIR": str(scratch)}
    done = subprocess.run([sys.executable, "-m", "sw2sim", "convert", str(zip_path), "-o",
                           str(tmp_path / "model")], capture_output=True, text=True, env=env,
                          timeout=120)
    assert done.returncode == 0, done.stdout + done.stderr
    assert (tmp_path / "model" / "scene.xml").is_file()
    assert list(scratch.iterdir()) == [], "the unpacked copy is removed when the command ends"


def test_the_check_command_ends_with_its_whole_report_its_status_and_no_unpacked_copy(tmp_path):
    """`sw2sim check` ends its process as soon as the report is out (sw2sim.cli._end_now):
    the report still arrives whole through a pipe, the status is the worst package's, and
    the zips' unpacked copies are gone."""
    package = copy_example(4, tmp_path / "export")
    edit(urdf_of(package), 'effort="', 'effort="-')    # an error: status 1
    zips = [zipped(package, tmp_path / f"class_{n}.zip") for n in range(3)]
    scratch = tmp_path / "tmp"
    scratch.mkdir()
    env = {**os.environ, "TMPDIR": str(scratch)}
    done = subprocess.run([sys.executable, "-m", "sw2sim", "check", "--json", *map(str, zips),
                           str(copy_example(1, tmp_path / "clean"))], capture_output=True,
                          text=True, env=env, timeout=120)
    assert done.returncode == 1, done.stderr
    reports = json.loads(done.stdout)
    assert [r["status"] for r in reports] == [1, 1, 1, 0]
    assert [Path(r["path"]).name for r in reports] == ["example_4"] * 3 + ["example_1"]
    assert reports[-1]["stability"]["steps"] > 0
    assert list(scratch.iterdir()) == [], "the unpacked copies are removed when the command ends"


def test_a_zip_that_names_files_outside_it_is_refused_before_anything_is_written(tmp_path):
    zip_path = tmp_path / "evil.zip"
    with zipfile.ZipFile(zip_path, "w") as zf:
        zf.writestr("pkg/package.xml", "<package><name>pkg</name></package>")
        zf.writestr("../../outside.txt", "x")
    report = check(zip_path)
    [fatal] = report.findings
    assert fatal.rule == "input-unreadable" and "outside its own folder" in fatal.message
    assert "give the package folder" in fatal.fix
    assert not (tmp_path.parent / "outside.txt").exists()
    assert report.status == 2


def test_archives_that_cannot_be_read_are_named_with_what_to_do(tmp_path, monkeypatch):
    broken = tmp_path / "cut.zip"
    broken.write_bytes(b"PK\x03\x04" + b"\x00" * 40)
    with pytest.raises(LoadError, match="not a readable zip archive") as error:
        find_package(broken)
    assert "unzip it yourself" in str(error.value)
    assert str(error.value).startswith(str(broken))

    secret = tmp_path / "secret.zip"
    with zipfile.ZipFile(secret, "w") as zf:
        zf.writestr("pkg/package.xml", "<package/>")
    # zipfile writes no encrypted archives: set the flag as an encrypting zip tool does,
    # in the file's local header and in the central directory
    data = bytearray(secret.read_bytes())
    for signature, offset in ((b"PK\x03\x04", 6), (b"PK\x01\x02", 8)):
        data[data.index(signature) + offset] |= 0x1
    secret.write_bytes(bytes(data))
    with pytest.raises(LoadError, match="encrypted"):
        find_package(secret)

    big = zipped(copy_example(1, tmp_path / "export"), tmp_path / "big.zip")
    monkeypatch.setattr(archive, "MAX_BYTES", 1000)
    with pytest.raises(LoadError, match="more than a package needs"):
        find_package(big)

    seven = tmp_path / "export.7z"
    seven.write_bytes(b"7z\xbc\xaf\x27\x1c")
    with pytest.raises(LoadError, match=r"a \.7z archive.*unpack it"):
        find_package(seven)


def test_the_folder_around_one_package_stands_for_it(tmp_path):
    package = copy_example(3, tmp_path / "Downloads" / "export-2026")
    assert find_package(tmp_path / "Downloads").root == package.resolve()
    for inside in ("urdf", "meshes", "launch", "config"):
        assert find_package(package / inside).root == package.resolve(), inside
    report = check(package / "urdf")
    assert report.status == 0 and report.path.endswith("example_3")


def test_a_folder_with_several_packages_lists_them(tmp_path, monkeypatch):
    for n in (1, 3):
        copy_example(n, tmp_path / "ws" / "src")
    (tmp_path / "ws" / "src" / ".hidden").mkdir()
    copy_example(4, tmp_path / "ws" / "src" / ".hidden")
    monkeypatch.chdir(tmp_path)
    [fatal] = check("ws").findings
    assert fatal.rule == "input-missing"
    assert "2 packages below: src/example_1/, src/example_3/" in fatal.message
    assert fatal.fix == "give one of them, such as ws/src/example_1"
    # a long list is cut short
    for n in range(10):
        copy_example(1, tmp_path / "many" / f"copy_{n}")
    [fatal] = check("many").findings
    assert "10 packages below: copy_0/example_1/, " in fatal.message
    assert fatal.message.endswith("copy_7/example_1/ and 2 more")


def test_what_is_wrong_inside_a_zip_is_named_through_the_archive(tmp_path):
    package = copy_example(1, tmp_path / "export")
    edit(urdf_of(package), "</robot>", "</robot")
    zip_path = zipped(package, tmp_path / "broken.zip")
    with pytest.raises(LoadError) as error:
        find_package(zip_path)
    assert str(error.value).startswith(f"{zip_path}/example_1/urdf/example_1.urdf:")
    [fatal] = check(zip_path).findings
    assert fatal.rule == "xml-syntax" and fatal.file.endswith("broken.zip/example_1/urdf/example_1.urdf")


@pytest.mark.parametrize("name, what", [("Arm_Assembly.SLDASM", "a SolidWorks document"),
                                        ("base_link.STEP", "a CAD exchange file"),
                                        ("base_link.STL", "a mesh (.STL)")])
def test_files_that_are_no_urdf_are_named_with_what_to_give(tmp_path, name, what):
    given = tmp_path / name
    given.write_bytes(bytes(range(256)) * 8)
    [fatal] = check(given).findings
    assert fatal.rule == "not-urdf" and fatal.message.startswith(what)
    assert "package folder" in fatal.fix


def test_a_urdf_that_notepad_saved_as_text_is_named_and_an_upper_case_one_is_read(tmp_path):
    package = copy_example(1, tmp_path)
    urdf = urdf_of(package)
    urdf.rename(urdf.with_name("example_1.urdf.txt"))
    [fatal] = check(package).findings
    assert fatal.rule == "not-urdf" and fatal.file.endswith("urdf/example_1.urdf.txt")
    assert fatal.fix.startswith("rename it without the .txt")
    urdf.with_name("example_1.urdf.txt").rename(urdf.with_name("EXAMPLE_1.URDF"))
    assert find_package(package).urdf.name == "EXAMPLE_1.URDF"


@pytest.mark.parametrize("code_page", ["gbk", "cp866", "utf-8"])
def test_names_a_windows_zip_writes_in_its_code_page_are_read_as_the_urdf_names_them(
        tmp_path, code_page):
    """Explorer writes a name in Windows' OEM code page without marking it (GBK on a Chinese
    Windows, 866 on a Russian one; some tools write UTF-8 unmarked): zipfile reads it as
    code page 437, and the mesh the URDF names would be missing."""
    package = copy_example(1, tmp_path / "export")
    mesh = {"gbk": "底座", "cp866": "основание", "utf-8": "базовая"}[code_page]
    (package / "meshes" / "base_link.STL").rename(package / "meshes" / f"{mesh}.STL")
    edit(urdf_of(package), "meshes/base_link.STL", f"meshes/{mesh}.STL", count=2)
    # zipfile marks every non-ASCII name UTF-8: write a stand-in name of the same length
    # in bytes, then put the code page's bytes in its place, unmarked, as Explorer does
    raw = mesh.encode(code_page)
    stand_in = "x" * len(raw)
    (package / "meshes" / f"{mesh}.STL").rename(package / "meshes" / f"{stand_in}.STL")
    zip_path = zipped(package, tmp_path / "export.zip")
    data = zip_path.read_bytes().replace(f"meshes/{stand_in}.STL".encode(),
                                         b"meshes/" + raw + b".STL")
    zip_path.write_bytes(data)
    with zipfile.ZipFile(zip_path) as zf:
        assert f"export/meshes/{mesh}.STL" not in zf.namelist(), "zipfile misreads the name"
    loaded = find_package(zip_path)
    assert (loaded.root / "meshes" / f"{mesh}.STL").is_file()
    assert check(zip_path).status == 0


def test_scripts_come_out_of_a_zip_executable_as_ros_wants_its_nodes(tmp_path):
    package = copy_example(3, tmp_path / "export")
    node = package / "scripts" / "random_setpoints_node.py"
    assert node.read_bytes().startswith(b"#!")
    node.chmod(0o755)
    unix = zipped(package, tmp_path / "unix.zip")          # zipfile keeps the mode, as zip does
    windows = tmp_path / "windows.zip"                     # Explorer's: no mode at all
    with zipfile.ZipFile(unix) as source, zipfile.ZipFile(windows, "w") as zf:
        for info in source.infolist():
            copy = zipfile.ZipInfo(info.filename, info.date_time)
            copy.create_system, copy.external_attr = 0, 0x20   # MS-DOS, "archive"
            zf.writestr(copy, source.read(info))
    for archive_path in (unix, windows):
        root = find_package(archive_path).root
        unpacked = root / "scripts" / "random_setpoints_node.py"
        assert os.access(unpacked, os.X_OK), archive_path.name
        assert not os.access(root / "package.xml", os.X_OK), archive_path.name


def test_a_package_zipped_without_its_folder_is_named_as_unzipping_would_name_it(tmp_path):
    package = copy_example(1, tmp_path / "export")
    flat = tmp_path / "my_export.zip"
    with zipfile.ZipFile(flat, "w") as zf:
        for path in sorted(package.rglob("*")):
            if path.is_file():
                zf.write(path, path.relative_to(package).as_posix())
    report = check(flat)
    [folder_name] = [f for f in report.findings if f.rule == "package-folder-name"]
    assert '"my_export"' in folder_name.message, "the folder Extract all would make"
    assert folder_name.file == f"{flat}/package.xml"

    empty = tmp_path / "empty.zip"
    zipfile.ZipFile(empty, "w").close()
    [fatal] = check(empty).findings
    assert fatal.rule == "input-missing" and fatal.file == str(empty)


def test_a_zip_that_changes_is_read_again(tmp_path):
    package = copy_example(1, tmp_path / "export")
    zip_path = zipped(package, tmp_path / "export.zip")
    first = find_package(zip_path)
    assert find_package(zip_path).root == first.root, "unpacked once"
    edit(urdf_of(package), 'name="example_1"', 'name="renamed"')
    zipped(package, zip_path)
    os.utime(zip_path, ns=(0, first.root.stat().st_mtime_ns + 10**9))
    again = find_package(zip_path)
    assert again.root != first.root and again.robot.get("name") == "renamed"


def test_solidworks_documents_sent_instead_of_an_export_are_named(tmp_path):
    """A Pack and Go folder (or its zip): the assembly and its parts, no URDF."""
    folder = tmp_path / "pack_and_go" / "Arm"
    folder.mkdir(parents=True)
    for name in ("Arm.SLDASM", "base.SLDPRT", "arm.SLDPRT"):
        (folder / name).write_bytes(bytes(range(256)))
    zip_path = zipped(folder, tmp_path / "Arm.zip")
    for given in (tmp_path / "pack_and_go", zip_path):
        [fatal] = check(given).findings
        assert fatal.rule == "not-urdf"
        assert fatal.message.startswith("SolidWorks documents (1 assembly, 2 parts)")
        assert fatal.fix.startswith("export the assembly with the exporter")
