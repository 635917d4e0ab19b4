"""The check's own mesh readers (sw2sim/check/trimeshes.py) against trimesh, which reads the
files they leave: binary and text STL and OBJ of triangles must come out as trimesh reads
them, triangle for triangle, so that no verdict of the check depends on which one read a
file; whatever they do not fully understand they must leave to trimesh."""

from __future__ import annotations

import numpy as np
import pytest
import trimesh
from mesh_parts import part as _part

from sw2sim.check import trimeshes


def _obj_text(part: trimesh.Trimesh, form: str, *, header: str = "", crlf: bool = False,
              extra_vertex: bool = False) -> bytes:
    """`part` as OBJ by hand, its corners in `form` ("v", "v/t", "v//n" or "v/t/n")."""
    lines = [header] if header else []
    lines += [f"v {float(x)!r} {float(y)!r} {z:.6e}" for x, y, z in part.vertices]
    if extra_vertex:
        lines.append("v 5 5 5")   # used by no face: trimesh drops it
    lines += [f"vt {i % 7 / 7} 0.5" for i in range(9)]
    lines += ["vn 0 0 1", "vn 0 1 0", "vn 1 0 0"]
    for n, face in enumerate(part.faces):
        corners = []
        for k, v in enumerate(face + 1):
            t, m = (n + k) % 9 + 1, (n * k) % 3 + 1
            corners.append({"v": f"{v}", "v/t": f"{v}/{t}", "v//n": f"{v}//{m}",
                            "v/t/n": f"{v}/{t}/{m}"}[form])
        lines.append("f " + " ".join(corners))
    return (("\r\n" if crlf else "\n").join(lines) + "\n").encode()


def _obj_in_runs(part: trimesh.Trimesh) -> bytes:
    """`part` as OBJ whose vertices and faces each come in two runs of lines, with an empty
    line, a comment and a group between them (the reader's path for lines that do not stand
    together)."""
    vertices = [f"v {float(x)!r} {float(y)!r} {float(z)!r}" for x, y, z in part.vertices]
    faces = [f"f {a} {b} {c}" for a, b, c in part.faces + 1]
    half_v, half_f = len(vertices) // 2, len(faces) // 2
    lines = (vertices[:half_v] + ["", "# the rest"] + vertices[half_v:] + faces[:half_f]
             + ["g second"] + faces[half_f:])
    return ("\n".join(lines) + "\n").encode()


def _text_stl(part: trimesh.Trimesh, upper: bool = False) -> bytes:
    text = trimesh.exchange.stl.export_stl_ascii(part)
    return (text.upper() if upper else text).encode()


SIMPLE = {
    "binary STL": (".STL", lambda p: p.export(file_type="stl")),
    "text STL": (".stl", _text_stl),
    "text STL in capitals": (".STL", lambda p: _text_stl(p, upper=True)),
    "text STL, Windows line ends": (".stl", lambda p: _text_stl(p).replace(b"\n", b"\r\n")),
    "OBJ by trimesh": (".obj", lambda p: p.export(file_type="obj").encode()),
    "OBJ, vertex only": (".obj", lambda p: _obj_text(p, "v", extra_vertex=True)),
    "OBJ, vertex/texture": (".obj", lambda p: _obj_text(p, "v/t")),
    "OBJ, vertex//normal": (".obj", lambda p: _obj_text(p, "v//n")),
    "OBJ, vertex/texture/normal": (".obj", lambda p: _obj_text(p, "v/t/n", crlf=True)),
    "OBJ, its lines in runs": (".obj", _obj_in_runs),
    "OBJ with names and a material": (".obj", lambda p: _obj_text(
        p, "v", header="# part\nmtllib part.mtl\no part\ng body\ns off\nusemtl steel")),
}


def _same(mine: trimeshes.Mesh, theirs: trimeshes.Mesh) -> None:
    """The same triangles in the same order, and the same vertices (as many of each)."""
    assert np.array_equal(mine.triangles, theirs.triangles)
    assert len(mine.vertices) == len(theirs.vertices)
    assert np.array_equal(np.unique(mine.vertices, axis=0), np.unique(theirs.vertices, axis=0))


@pytest.mark.parametrize("kind", SIMPLE)
def test_the_readers_read_simple_files_as_trimesh_does(tmp_path, kind):
    suffix, write = SIMPLE[kind]
    path = tmp_path / f"part{suffix}"
    path.write_bytes(write(_part()))
    reader = trimeshes._stl if suffix.lower() == ".stl" else trimeshes._obj
    mine = reader(path.read_bytes())   # read here: no trimesh.load behind it
    _same(mine, trimeshes._with_trimesh(path))
    _same(trimeshes.read(path), mine)


def _swap(old: str, new: str, count: int = 1):
    def change(text: bytes) -> bytes:
        assert text.count(old.encode()) >= count
        return text.replace(old.encode(), new.encode(), count)
    return change


def _quads(part: trimesh.Trimesh) -> bytes:
    """Two triangles' worth of the part as one quad: "f a b c d"."""
    text = _obj_text(part, "v")
    first = text.index(b"\nf ")
    end = text.index(b"\n", first + 1)
    return text[:end] + b" 1" + text[end:]


def _coloured(text: bytes) -> bytes:
    """Every vertex with an RGB colour after its position: "v x y z r g b"."""
    return b"\n".join(line + b" 1 0 0" if line.startswith(b"v ") else line
                      for line in text.split(b"\n"))


def _material_after_first_face(text: bytes) -> bytes:
    second = text.index(b"\nf ", text.index(b"\nf ") + 1)
    return text[:second] + b"\nusemtl a" + text[second:]


def _two_solids(part: trimesh.Trimesh) -> bytes:
    text = _text_stl(part)
    return text + text.replace(b"solid", b"solid second", 1)


# What the readers here leave to trimesh: trimesh's result stands (None when it fails).
LEFT = {
    "OBJ of quads": (".obj", _quads),
    "OBJ with relative indices": (".obj", lambda p: _swap("\nf 1 ", "\nf -1 ")(
        _obj_text(p, "v"))),
    "OBJ with an index 0": (".obj", lambda p: _swap("\nf 1 ", "\nf 0 ")(_obj_text(p, "v"))),
    "OBJ with two materials": (".obj", lambda p: _swap("\nf ", "\nusemtl a\nf ", 1)(
        _obj_text(p, "v", header="usemtl b"))),
    "OBJ with a material after its first face": (".obj", lambda p: _material_after_first_face(
        _obj_text(p, "v"))),
    "OBJ with corners of two forms": (".obj", lambda p: _swap("\nf 1 ", "\nf 1/1 ")(
        _obj_text(p, "v"))),
    "OBJ with vertex colours": (".obj", lambda p: _coloured(_obj_text(p, "v"))),
    "OBJ with a tab": (".obj", lambda p: _swap("\nv ", "\nv\t")(_obj_text(p, "v"))),
    "OBJ with a word for a number": (".obj", lambda p: _swap("\nv ", "\nv x ")(
        _obj_text(p, "v"))),
    "OBJ with lines (l)": (".obj", lambda p: _obj_text(p, "v") + b"l 1 2\n"),
    "OBJ without faces": (".obj", lambda p: b"v 0 0 0\nv 1 0 0\nv 0 1 0\n"),
    "text STL of two solids": (".stl", _two_solids),
    "text STL with a quadrilateral facet": (".stl", lambda p: _swap(
        "endloop", "vertex 1 1 1\nendloop")(_text_stl(p))),
    "text STL with a word for a number": (".stl", lambda p: _swap("vertex ", "vertex x")(
        _text_stl(p))),
    "STL cut short": (".stl", lambda p: p.export(file_type="stl")[:-7]),
}


@pytest.mark.parametrize("kind", LEFT)
def test_the_readers_leave_what_they_do_not_fully_understand_to_trimesh(tmp_path, kind):
    suffix, write = LEFT[kind]
    path = tmp_path / f"part{suffix}"
    path.write_bytes(write(_part()))
    reader = trimeshes._stl if suffix == ".stl" else trimeshes._obj
    with pytest.raises(trimeshes._NotSimple):
        reader(path.read_bytes())
    theirs = trimeshes._with_trimesh(path)
    mine = trimeshes.read(path)
    if theirs is None or not len(theirs.faces):
        assert mine is None
    else:
        _same(mine, theirs)


def test_an_empty_binary_stl_is_no_mesh_without_trimesh(tmp_path):
    path = tmp_path / "empty.STL"
    path.write_bytes(bytes(84))
    assert trimeshes._stl(path.read_bytes()) is None
    assert trimeshes.read(path) is None


def test_merging_keeps_numpy_unique_s_vertices_and_order():
    """merge_vertices sorts the rows itself; np.unique(axis=0) is what it replaced."""
    rng = np.random.default_rng(3)
    points = np.round(rng.uniform(-1, 1, (300, 3)), 2)
    points[::7, 0] = -0.0              # -0.0 and 0.0 are one coordinate
    points[1::7, 0] = 0.0
    points[2::9] += 1e-10              # closer than MERGE_DIGITS: one vertex
    vertices = points[rng.integers(0, len(points), 3000)]
    faces = np.arange(3000).reshape(-1, 3)
    mesh = trimeshes.Mesh(vertices, faces)
    mesh.merge_vertices()
    keys = np.round(vertices, trimeshes.MERGE_DIGITS)
    _, first, inverse = np.unique(keys, axis=0, return_index=True, return_inverse=True)
    assert np.array_equal(mesh.vertices, vertices[first])
    assert np.array_equal(mesh.faces, inverse.reshape(-1)[faces])
    assert np.array_equal(mesh.triangles.round(8), vertices[faces].round(8))


def test_a_mesh_s_box_is_numpy_s_min_and_max():
    """Mesh.bounds and Mesh.extents read each column on its own; numpy's axis=0 reductions
    are what they replaced, number for number (NaN included)."""
    rng = np.random.default_rng(5)
    for points in (rng.uniform(-3, 2, (1000, 3)), np.array([[1.0, -2.0, 3.0]]),
                   np.array([[0.0, np.nan, 1.0], [-1.0, 2.0, np.inf]])):
        mesh = trimeshes.Mesh(points, np.zeros((0, 3)))
        expected = np.array([points.min(axis=0), points.max(axis=0)])
        assert np.array_equal(mesh.bounds, expected, equal_nan=True)
        assert np.array_equal(mesh.extents, np.ptp(points, axis=0), equal_nan=True)
    assert np.array_equal(trimeshes.Mesh(np.zeros((0, 3)), np.zeros((0, 3))).extents, np.zeros(3))


@pytest.mark.parametrize("faces", [b"f 1 2 4\n", b"f 1/1 2/2 4/1\nf 1/2 2/1 4/2\n",
                                   b"f 1//1 2//1 4//1\n"])
def test_an_obj_s_points_no_face_uses_are_kept_aside_through_scale_and_copy(faces):
    """The OBJ reader leaves out of the vertices a `v` line no face uses, as trimesh does,
    and keeps it in `loose` (MuJoCo's hull takes it in), whatever the corners' form."""
    text = b"v 0 0 0\nv 1 0 0\nv 7 8 9\nv 0 1 0\nv -5 -6 -7\nvt 0 0\nvt 1 1\nvn 0 0 1\n" + faces
    mesh = trimeshes._obj(text)
    assert sorted(set(map(tuple, mesh.vertices))) == [(0, 0, 0), (0, 1, 0), (1, 0, 0)]
    assert mesh.loose.tolist() == [[7, 8, 9], [-5, -6, -7]]
    scaled = mesh.copy()
    scaled.apply_scale([2, 1, 0.5])
    assert scaled.loose.tolist() == [[14, 8, 4.5], [-10, -6, -3.5]]
    assert mesh.loose.tolist() == [[7, 8, 9], [-5, -6, -7]]   # the copy's own
    moved = mesh.copy()
    moved.apply_transform(np.array([[1, 0, 0, 1], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1.0]]))
    assert moved.loose[:, 0].tolist() == [8, -4]
    assert trimeshes.Mesh(mesh.vertices, mesh.faces).copy().loose is None   # not known


@pytest.mark.parametrize("text", [
    b"\nv 1 2 3\nv 4 5 6\n\nf 1 2 3\n",
    b"\n# made by hand\nmtllib a.mtl\nusemtl steel\no part\ng all\ns off\nvn 0 0 1\nvt 0 0\nf 1/1/1 2/2/1 3/3/1",
    b"\n\n\nv 1 2 3\nvv 1\nf\n fv 1 2 3\n\n",
    b"\nv",
])
def test_the_obj_reader_counts_statements_as_a_search_of_the_text_does(text):
    """The line heads compared at once (_statement_counts) give what `bytes.count` gives."""
    counts, empty, lines = trimeshes._statement_counts(text)
    assert counts == {key: text.count(b"\n" + key) for key in trimeshes._OBJ_STATEMENTS}
    assert lines == text.count(b"\n")
    assert empty == sum(1 for line in text.split(b"\n")[1:] if not line)


def test_the_check_reads_each_mesh_file_once(monkeypatch):
    """The bytes that tell files of the same content apart are the bytes the mesh is decoded
    from: the file is not read again by name."""
    import collections
    import pathlib

    from sw2sim.check import check
    from repository import EXAMPLES
    reads = collections.Counter()
    read_bytes = pathlib.Path.read_bytes

    def counted(self):
        if self.suffix.lower() == ".stl":
            reads[self.name] += 1
        return read_bytes(self)

    monkeypatch.setattr(pathlib.Path, "read_bytes", counted)
    check(EXAMPLES / "example_3", stability=False)
    assert reads and set(reads.values()) == {1}, reads
