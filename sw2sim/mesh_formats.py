"""Which mesh files MuJoCo can read, and what stands in for one it cannot.

MuJoCo 4 decodes binary STL, OBJ and its own MSH; a COLLADA (.dae), PLY or glTF file stops
its compile with "no decoder found for mesh file". Packages made for RViz and Gazebo often
name such files, and many of them carry a readable copy beside each one (`base.dae` and
`base.STL`, the visual and the collision shape). `stand_in` says what MuJoCo reads instead:
that copy when there is one, else the file converted to binary STL in memory (COLLADA in its
common simple form by sw2sim.collada_reader, anything else by trimesh, which reads COLLADA
through pycollada). The loader uses it, and `sw2sim check` reports the same choice as
convert's repair, so that the check and the model can never disagree.

A repository that keeps its meshes in Git LFS, cloned without Git LFS, holds small text
files in their place; `lfs_pointer` tells them apart, so that the fix named is `git lfs pull`
and not a parse error of a mesh that is not there.
"""

from __future__ import annotations

from pathlib import Path

# What MuJoCo's own decoders read, by file extension (any case).
MUJOCO_FORMATS = (".stl", ".obj", ".msh")
# Where one of several readable copies exists, the one MuJoCo reads best: binary STL is
# what the SolidWorks exporter writes; OBJ may carry several objects; MSH is rare.
PREFERENCE = {suffix: rank for rank, suffix in enumerate(MUJOCO_FORMATS)}

# The first line of every Git LFS pointer file (git-lfs's docs/spec.md: the first key is
# always `version`), and the size below which git-lfs itself looks for a pointer in a file
# (its blobSizeCutoff): a pointer is about 130 bytes.
LFS_HEADER = b"version https://git-lfs.github.com/spec/v1"
LFS_CUTOFF = 1024
LFS_FIX = ("the repository keeps its meshes in Git LFS: install Git LFS (`git lfs install`) "
           "and run `git lfs pull` in the repository, which puts the meshes in place of the "
           "pointers")

# The suffix a mesh converted in memory is named with: MuJoCo picks the decoder by it.
CONVERTED_SUFFIX = ".stl"


class Unconvertible(Exception):
    """A mesh file MuJoCo cannot read, that trimesh cannot turn into triangles either."""


def readable(path: Path) -> bool:
    """Whether MuJoCo has a decoder for the file's format."""
    return path.suffix.lower() in MUJOCO_FORMATS


def lfs_pointer(path: Path) -> bool:
    """Whether the file is a Git LFS pointer: a short text file naming the real content."""
    try:
        if path.stat().st_size >= LFS_CUTOFF:
            return False
        with path.open("rb") as stream:
            return stream.read(len(LFS_HEADER)) == LFS_HEADER
    except OSError:
        return False


def beside(path: Path) -> Path | None:
    """The file of the same name beside `path` in a format MuJoCo reads (any case of its
    extension: `base.dae` -> `base.STL`), or None. Pointers of Git LFS do not count."""
    try:
        found = [p for p in path.parent.iterdir()
                 if p.stem == path.stem and p != path and readable(p) and p.is_file()
                 and not lfs_pointer(p)]
    except OSError:
        return None
    if not found:
        return None
    return min(found, key=lambda p: (PREFERENCE[p.suffix.lower()], p.name))


def stand_in(path: Path) -> Path | None:
    """What MuJoCo reads for a mesh file: the file itself when it can, the readable file
    beside it, or None when only a conversion (`stl_bytes`) will do."""
    if readable(path):
        return path
    return beside(path)


def converted_name(path: Path) -> str:
    """The name a mesh converted in memory goes by: its own name with .stl added, so that
    the model's asset says what it was made from (`base.dae.stl`)."""
    return str(path) + CONVERTED_SUFFIX


def converted_from(name: str) -> Path:
    """The mesh file a `converted_name` was made from."""
    return Path(name[: -len(CONVERTED_SUFFIX)])


def stl_bytes(path: Path) -> bytes:
    """The mesh in `path` (COLLADA, PLY, glTF, ...) as binary STL, in metres.

    The whole file becomes one mesh, with the transforms of its scene applied. A COLLADA
    file's <unit meter="..."> is applied too: it says how long one of the file's units is,
    and a URDF's lengths are metres. Raises Unconvertible with the reason.

    COLLADA in its common simple form is read by sw2sim.collada_reader, without importing
    trimesh, and written here: the same bytes as trimesh's export of what it reads (an
    80-byte header of zeros, each face's unit normal from its corners, zero for a face of
    no area; tests/tool/check/test_collada_reader.py compares them). A COLLADA document
    that declares a DOCTYPE is not read at all; any other file goes to trimesh."""
    if path.suffix.lower() == ".dae":
        from .collada_reader import NotSimple, Refused, read_collada
        try:
            vertices, faces = read_collada(path.read_bytes())
        except Refused as exc:
            raise Unconvertible(str(exc)) from None
        except (OSError, NotSimple):
            pass   # trimesh reads it, or says why it cannot
        else:
            if not len(faces):
                raise Unconvertible("it holds no triangles")
            return binary_stl(vertices[faces])
    try:
        import collada  # noqa: F401  (trimesh reads COLLADA through pycollada)
    except ImportError:
        if path.suffix.lower() == ".dae":
            raise Unconvertible("pycollada, which reads COLLADA files, is not installed "
                                "(pip install pycollada)") from None
    import trimesh
    try:
        mesh = trimesh.load(str(path), force="mesh", process=False)
    except Exception as exc:  # noqa: BLE001  (any reader failure means "cannot convert")
        raise Unconvertible(f"trimesh cannot read it ({type(exc).__name__}: {exc})") from None
    if not isinstance(mesh, trimesh.Trimesh) or not len(mesh.faces):
        raise Unconvertible("it holds no triangles")
    if not in_metres(mesh):
        raise Unconvertible(f"its unit, {mesh.units!r}, is not a length")
    return mesh.export(file_type="stl")


# Below this length a face's cross product is no direction: zero is its normal (trimesh's
# tolerance, a hundred times float64's resolution).
_NO_AREA = 1e-13


def binary_stl(triangles) -> bytes:
    """Triangles (an n x 3 x 3 numpy array) as binary STL, with trimesh's arithmetic."""
    import numpy as np   # not at import: mesh_formats is imported where numpy is not needed
    record = np.dtype([("normal", "<f4", (3,)), ("corners", "<f4", (3, 3)),
                       ("attribute", "<u2")])
    crosses = np.cross(triangles[:, 1] - triangles[:, 0], triangles[:, 2] - triangles[:, 1])
    lengths = np.sqrt(np.dot(crosses * crosses, [1.0, 1.0, 1.0]))
    valid = lengths > _NO_AREA
    lengths[valid] **= -1
    records = np.zeros(len(triangles), dtype=record)
    records["normal"][valid] = (crosses * lengths.reshape((-1, 1)))[valid]
    records["corners"] = triangles
    return bytes(80) + len(triangles).to_bytes(4, "little") + records.tobytes()


def in_metres(mesh) -> bool:
    """Scale a trimesh mesh to metres where its file named another unit (a COLLADA <unit>,
    which trimesh records but does not apply); False when that unit is no length."""
    units = mesh.units
    if not units or units == "meters":
        return True
    try:
        mesh.convert_units("meters")
    except (ValueError, KeyError, TypeError):
        return False
    return True
