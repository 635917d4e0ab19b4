"""`sw2sim check` on files written to attack the reader: it must refuse them, name the file,
finish at once, and read nothing outside the package.

Each case breaks a copy of examples/example_4 (small meshes, so each check is quick). Outside
the package sit a secret text file, a valid STL carrying the same secret, and a named pipe. The
pipe is the tripwire: opening it for reading, from Python or from C (libxml2, a mesh reader),
wakes a watcher thread that records the open. Python-level opens and trimesh loads are recorded
as well, so a read of the secret file is caught even though it would not block.
"""

from __future__ import annotations

import builtins
import errno
import io
import os
import shutil
import threading
import time
from pathlib import Path
from types import SimpleNamespace

import pytest
import trimesh
from lxml import etree

from sw2sim.check import ERROR, FATAL, check
from packages import copy_example, line_of, urdf_of

SECRET = "OUTSIDE-7f3a9c-SECRET"
PASSWD = "root:x:0:0"      # the first line of /etc/passwd on any Linux
SECONDS = 5.0              # generous: a safe refusal takes milliseconds


class Tripwire:
    """A named pipe that records every open for reading, and answers it with SECRET."""

    def __init__(self, path: Path):
        self.path = path
        self.opens = 0
        os.mkfifo(path)
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._watch, daemon=True)
        self._thread.start()

    def _watch(self) -> None:
        while not self._stop.is_set():
            try:
                fd = os.open(self.path, os.O_WRONLY | os.O_NONBLOCK)
            except OSError as exc:  # ENXIO: nobody has the pipe open for reading
                if exc.errno != errno.ENXIO:
                    raise
                time.sleep(0.002)
                continue
            self.opens += 1
            try:
                os.write(fd, f"{SECRET}\n".encode())
            except OSError:
                pass
            os.close(fd)
            time.sleep(0.01)

    def stop(self) -> None:
        self._stop.set()
        self._thread.join(1)


@pytest.fixture
def world(tmp_path, monkeypatch):
    """A package, the secrets beside it, the tripwire, and a record of Python-level reads."""
    outside = tmp_path / "outside"
    outside.mkdir()
    (outside / "secret.txt").write_text(SECRET + "\n")
    box = trimesh.creation.box(extents=[0.1, 0.1, 0.1])
    (outside / "secret.STL").write_bytes(SECRET.encode().ljust(80, b" ")
                                         + box.export(file_type="stl")[80:])
    (outside / "links.xml").write_text(f'<link name="{SECRET}"/>')
    package = copy_example(4, tmp_path / "pkg")
    wire = Tripwire(outside / "pipe")
    reads: list[str] = []

    def recording(real):
        def opener(*args, **kwargs):
            target = args[0] if args else kwargs.get("file", kwargs.get("file_obj"))
            if isinstance(target, (str, os.PathLike)):
                reads.append(os.fspath(target))
            return real(*args, **kwargs)
        return opener

    monkeypatch.setattr(builtins, "open", recording(builtins.open))
    monkeypatch.setattr(io, "open", recording(io.open))
    monkeypatch.setattr(trimesh, "load", recording(trimesh.load))
    monkeypatch.setattr(trimesh, "load_mesh", recording(trimesh.load_mesh))
    yield SimpleNamespace(package=package, urdf=urdf_of(package), outside=outside, wire=wire,
                          reads=reads)
    wire.stop()


def run(world, path, capsys):
    """Check `path`; assert it was quick, quiet, leak-free and touched nothing outside."""
    world.reads.clear()
    start = time.monotonic()
    report = check(path, stability=False)
    elapsed = time.monotonic() - start
    captured = capsys.readouterr()
    text = "\n".join([report.format(), report.to_json(), captured.out, captured.err])
    assert "Traceback" not in text
    assert SECRET not in text and PASSWD not in text
    assert elapsed < SECONDS, f"took {elapsed:.1f} s"
    assert world.wire.opens == 0, "the pipe outside the package was opened for reading"
    outside = world.outside.resolve()
    touched = [r for r in world.reads if outside in Path(r).resolve().parents]
    assert not touched, f"read outside the package: {touched}"
    return report


def refusals(report, file: Path):
    """Fatal or error findings that name `file`."""
    return [f for f in report.findings if f.severity in (FATAL, ERROR)
            and f.file is not None and Path(f.file).name == file.name]


# --- the tripwire itself --------------------------------------------------------------------


def test_the_tripwire_and_the_record_see_a_python_read(world):
    with open(world.wire.path) as pipe:
        assert SECRET in pipe.read()
    assert world.wire.opens == 1
    (world.outside / "secret.txt").read_text()
    assert str(world.outside / "secret.txt") in world.reads


def test_the_tripwire_sees_libxml2_follow_an_entity(world):
    doc = (f'<!DOCTYPE r [<!ENTITY x SYSTEM "file://{world.wire.path}">]><r>&x;</r>').encode()
    unsafe = etree.XMLParser(resolve_entities=True, load_dtd=True, no_network=True)
    assert SECRET in etree.fromstring(doc, unsafe).text
    assert world.wire.opens == 1


# --- DOCTYPE and entities in the URDF -------------------------------------------------------


LAUGHS = "".join(f'<!ENTITY lol{i} "{(f"&lol{i - 1};" if i > 1 else "lol") * 10}">'
                 for i in range(1, 10))


def doctypes(world) -> dict[str, tuple[str, str]]:
    """Case name -> (DOCTYPE, text put inside <robot> or as its name)."""
    pipe, secret = world.wire.path, world.outside / "secret.txt"
    return {
        "billion-laughs-attribute": (f"<!DOCTYPE robot [{LAUGHS}]>", 'name="&lol9;"'),
        "billion-laughs-content": (f"<!DOCTYPE robot [{LAUGHS}]>", "&lol9;"),
        "external-passwd": ('<!DOCTYPE robot [<!ENTITY x SYSTEM "file:///etc/passwd">]>', "&x;"),
        "external-outside-file": (f'<!DOCTYPE robot [<!ENTITY x SYSTEM "file://{secret}">]>',
                                  "&x;"),
        "external-pipe": (f'<!DOCTYPE robot [<!ENTITY x SYSTEM "file://{pipe}">]>', "&x;"),
        "external-pipe-attribute": (f'<!DOCTYPE robot [<!ENTITY x SYSTEM "file://{pipe}">]>',
                                    'name="&x;"'),
        "parameter-entity": (f'<!DOCTYPE robot [<!ENTITY % p SYSTEM "file://{pipe}"> %p;]>', ""),
        "parameter-entity-chain": (
            f'<!DOCTYPE robot [<!ENTITY % f SYSTEM "file://{secret}">'
            '<!ENTITY % w "<!ENTITY x SYSTEM \'file:///nowhere/%f;\'>"> %w;]>', "&x;"),
        "external-dtd": (f'<!DOCTYPE robot SYSTEM "file://{pipe}">', ""),
    }


CASES = ["billion-laughs-attribute", "billion-laughs-content", "external-passwd",
         "external-outside-file", "external-pipe", "external-pipe-attribute",
         "parameter-entity", "parameter-entity-chain", "external-dtd"]


def hostile_urdf(world, case: str, encoding: str) -> int:
    """Write the case into the package's URDF; return the DOCTYPE's line (after the declaration)."""
    doctype, use = doctypes(world)[case]
    text = world.urdf.read_text()
    declaration, rest = text.split("\n", 1)
    if use.startswith("name="):
        rest = rest.replace('name="example_4"', use, 1)
    else:
        rest = rest.replace('name="example_4">', f'name="example_4">{use}', 1)
    text = f'<?xml version="1.0" encoding="{encoding}"?>\n{doctype}\n{rest}'
    world.urdf.write_bytes(text.encode(encoding))
    return 2


@pytest.mark.parametrize("encoding", ["utf-8", "utf-16"])
@pytest.mark.parametrize("case", CASES)
def test_a_doctype_in_the_urdf_is_refused(world, capsys, case, encoding):
    line = hostile_urdf(world, case, encoding)
    report = run(world, world.package, capsys)
    refused = refusals(report, world.urdf)
    assert refused and report.status == 2, report.format()
    if encoding == "utf-8":
        assert any(f.line == line for f in refused), report.format()


def test_an_xinclude_is_not_followed(world, capsys):
    # The block's link is to come from a file outside: unfollowed, its joint names a missing link.
    text = world.urdf.read_text()
    start = text.index('  <link\n    name="block_link">')
    end = text.index("</link>", start) + len("</link>")
    include = (f'<xi:include xmlns:xi="http://www.w3.org/2001/XInclude" '
               f'href="file://{world.outside / "links.xml"}"/>'
               f'<xi:include xmlns:xi="http://www.w3.org/2001/XInclude" '
               f'href="file://{world.wire.path}" parse="text"/>')
    world.urdf.write_text(text[:start] + include + text[end:])
    report = run(world, world.package, capsys)
    assert refusals(report, world.urdf), report.format()


def test_the_urdf_as_a_named_pipe_is_refused_without_waiting(world, capsys):
    world.urdf.unlink()
    wire = Tripwire(world.urdf)   # answers a read, so that a reader fails the test, not hangs
    try:
        report = run(world, world.package, capsys)
    finally:
        wire.stop()
    assert wire.opens == 0, "the checker read from a pipe given as the URDF"
    assert refusals(report, world.urdf) and report.status == 2, report.format()


# --- DOCTYPE and entities in package.xml ----------------------------------------------------


@pytest.mark.parametrize("case", ["billion-laughs", "external-outside-file", "external-pipe"])
def test_a_doctype_in_package_xml_is_refused(world, capsys, case):
    manifest = world.package / "package.xml"
    target = world.outside / "secret.txt" if case == "external-outside-file" else world.wire.path
    doctype, name = {
        "billion-laughs": (f"<!DOCTYPE package [{LAUGHS}]>", "&lol9;"),
        "external-outside-file": (f'<!DOCTYPE package [<!ENTITY x SYSTEM "file://{target}">]>',
                                  "&x;"),
        "external-pipe": (f'<!DOCTYPE package [<!ENTITY x SYSTEM "file://{target}">]>', "&x;"),
    }[case]
    text = manifest.read_text().replace("<name>example_4</name>", f"<name>{name}</name>")
    manifest.write_text(text.replace('<?xml version="1.0"?>', f'<?xml version="1.0"?>{doctype}'))
    report = run(world, world.package, capsys)
    assert refusals(report, manifest), report.format()


# --- mesh paths that leave the package ------------------------------------------------------


def mesh_paths(world) -> dict[str, str]:
    secret = world.outside / "secret.STL"
    up = os.path.relpath(secret, world.urdf.parent)
    return {
        "package-dot-dot": f"package://example_4/../{os.path.relpath(secret, world.package)}",
        "relative-dot-dot": up,
        "absolute": str(secret),
        "file-url": f"file://{secret}",
        "pipe": f"file://{world.wire.path}",
    }


@pytest.mark.parametrize("case", ["package-dot-dot", "relative-dot-dot", "absolute", "file-url",
                                  "pipe"])
def test_a_mesh_path_leaving_the_package_is_refused(world, capsys, case):
    line = line_of(world.urdf, "package://example_4/meshes/base_link.STL")
    text = world.urdf.read_text()
    world.urdf.write_text(text.replace("package://example_4/meshes/base_link.STL",
                                       mesh_paths(world)[case]))
    report = run(world, world.package, capsys)
    refused = refusals(report, world.urdf)
    assert any(f.line == line for f in refused), report.format()


@pytest.mark.parametrize("target", ["secret.STL", "pipe", "folder"])
def test_a_symlink_in_meshes_pointing_outside_is_refused(world, capsys, target):
    meshes = world.package / "meshes"
    if target == "folder":
        shutil.copytree(meshes, world.outside / "meshes")
        shutil.rmtree(meshes)
        meshes.symlink_to(world.outside / "meshes", target_is_directory=True)
    else:
        (meshes / "base_link.STL").unlink()
        (meshes / "base_link.STL").symlink_to(world.outside / target)
    report = run(world, world.package, capsys)
    mesh = meshes / "base_link.STL"
    assert refusals(report, world.urdf) or refusals(report, mesh), report.format()


@pytest.mark.parametrize("target", ["links.xml", "pipe"])
def test_a_package_xml_linking_outside_is_refused_unread(world, capsys, target):
    manifest = world.package / "package.xml"
    manifest.unlink()
    manifest.symlink_to(world.outside / target)
    report = run(world, world.package, capsys)
    assert report.status == 2
    assert refusals(report, manifest), report.format()
