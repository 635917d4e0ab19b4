"""Checks of the mesh files a URDF names: that each is found inside the package, that MuJoCo
can read it, and that it is in metres.

A mesh path never leads to reading a file outside the package: `Context.mesh_file` resolves
symbolic links and `..` before anything is opened, and a path that ends up outside is only
reported. Problems of a file's content are reported once per file, at the first <mesh> that
names it, however many links or elements use it.

Each link's geometry as triangle meshes, which the inertia and collision checks measure,
is `geometry.py`'s.
"""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np

from ..mesh_formats import LFS_FIX, beside, lfs_pointer
from ..mesh_paths import case_variants, closest, matches
from ..xmlsafe import source_line
from .context import display
from .findings import ERROR, WARNING, rule
from .repairs import repair, set_attribute
from .geometry import STL_FACE_LIMIT, millimetre_suspect
from .urdf import owner, vector

# MuJoCo 4 decodes binary STL, OBJ and its own MSH; anything else stops the compile with
# "no decoder found for mesh file".
MUJOCO_FORMATS = (".stl", ".obj", ".msh")
# A collision mesh with more triangles than this is worth simplifying: MuJoCo collides its
# convex hull anyway, so the detail only costs compile time (a 300,000-face mesh takes
# seconds), and in Gazebo every triangle costs time at every step. A coarse SolidWorks
# export of a single part stays well below it.
HEAVY_FACES = 20_000
# Thinner than this fraction of its size, a mesh is flat: MuJoCo cannot build its hull.
FLAT = 1e-6

PATH_REPAIR = ("when exactly one file in the package has the path's file name and agrees "
               "best with its folders, ignoring capitals and with \\ read as /, the mesh is "
               "read from that file. With several such files, or none, nothing is repaired and "
               "the finding names the closest files.")

rule("mesh-no-filename", ERROR, "mesh", "A <mesh> has no filename",
     symptom="MuJoCo stops with an error about the mesh; ROS's parser (check_urdf) "
             "prints an error about the missing filename.",
     cause="A hand edit that left <mesh/> empty or misspelt the attribute (it is `filename`).",
     fix="Write the mesh's path as the exporter does: "
         "<mesh filename=\"package://<package>/meshes/<link>.STL\"/>.")
rule("mesh-outside-package", ERROR, "mesh", "A mesh path leads outside the package folder",
     symptom="The model loads on one computer only, or not at all once the package is copied; "
             "`sw2sim check` does not open the file.",
     cause="A path with `../`, an absolute path or a file:// URL, or a symbolic link inside "
           "meshes/ that points elsewhere. A package must carry its own meshes.",
     fix="Copy the mesh into the package's meshes/ folder and name it as "
         "package://<package>/meshes/<file>.",
     repair=PATH_REPAIR)
rule("mesh-not-found", ERROR, "mesh", "A mesh file does not exist",
     symptom="MuJoCo stops with \"resource not found\" or \"Error opening file\"; RViz and "
             "Gazebo show the link without its shape.",
     cause="The mesh was not exported (the exporter skips some sub-assemblies and imported "
           "bodies), was renamed or deleted, or the path has a typo; package:// paths resolve "
           "against the folder that holds package.xml.",
     fix="Export the assembly again with its meshes, or correct the path so it names a file "
         "in the package's meshes/ folder.",
     seen_in=("solidworks_urdf_exporter#89", "solidworks_urdf_exporter#126", "mujoco#1432"),
     repair=PATH_REPAIR)
rule("mesh-format", ERROR, "mesh", "MuJoCo cannot read this mesh format",
     symptom="MuJoCo stops with \"no decoder found for mesh file\".",
     cause="MuJoCo reads STL, OBJ and its own MSH files only; COLLADA (.dae), PLY, glTF and "
           "the like, which RViz and Gazebo accept, are not among them.",
     fix="Convert the mesh to binary STL or OBJ (MeshLab, Blender, or "
         "`trimesh.load(path).export(\"part.stl\")`) and point the URDF at the new file.",
     repair="the mesh is read from the file of the same name beside it in a format MuJoCo "
            "reads (`base.STL` for `base.dae`, any case of the extension), STL first, then "
            "OBJ, then MSH. Where there is none, the mesh is converted to binary STL with "
            "trimesh (pycollada reads COLLADA), in metres as a COLLADA file's `<unit>` says; "
            "the model folder holds the converted file.")
rule("mesh-lfs-pointer", ERROR, "mesh", "The mesh file is a Git LFS pointer, not the mesh",
     symptom="MuJoCo stops with \"number of faces should be between 1 and 200000 in STL file "
             "...; perhaps this is an ASCII file?\" (or \"at least 4 vertices required\" for "
             "an OBJ); the file is about 130 bytes of text starting `version "
             "https://git-lfs.github.com/spec/v1`.",
     cause="The repository keeps its meshes in Git LFS (its .gitattributes names them with "
           "`filter=lfs`), and the copy at hand was cloned without Git LFS installed, or "
           "downloaded as an archive without its LFS files: each mesh is a pointer that "
           "names the real file on the server.",
     fix="Install Git LFS, run `git lfs install` once, then `git lfs pull` in the "
         "repository: the pointers are replaced by the meshes.")
rule("mesh-ascii-stl", ERROR, "mesh", "The STL file is text (ASCII), not binary",
     symptom="MuJoCo stops with \"number of faces should be between 1 and 200000 in STL "
             "file ...; perhaps this is an ASCII file?\".",
     cause="The file was saved as ASCII STL; MuJoCo's STL reader takes binary STL only. The "
           "exporter writes binary STL, so this comes from a mesh saved by hand.",
     fix="Save the part as binary STL (SolidWorks: Save As, STL, Options, Output as Binary), "
         "or convert it: `trimesh.load(path).export(path)` writes binary STL.")
rule("mesh-empty", ERROR, "mesh", "The mesh file holds no triangles",
     symptom="MuJoCo stops with \"invalid header\", \"STL file ... is empty\" or \"number of "
             "faces should be between 1 and 200000\"; RViz shows nothing for the link.",
     cause="The exporter sometimes writes an 80-byte STL, a header without a single triangle, "
           "for parts it could not tessellate: sub-assemblies, imported or hidden bodies.",
     fix="Make the part's bodies visible and export again; if it stays empty, save the part "
         "as STL from SolidWorks yourself (File, Save As, STL) into meshes/.",
     seen_in=("solidworks_urdf_exporter#88", "solidworks_urdf_exporter#89",
              "solidworks_urdf_exporter#126"))
rule("mesh-unreadable", ERROR, "mesh", "The mesh file is corrupt",
     symptom="MuJoCo stops with \"STL file ... has wrong size\", \"vertex coordinate ... is "
             "not finite\" or a parser error.",
     cause="A copy or download that was cut short, a file that is not a mesh at all under a "
           "mesh's name, or a writer that put NaN into the coordinates.",
     fix="Export the mesh again (or copy it again from where it was exported).")
rule("mesh-flat", ERROR, "mesh", "The mesh is flat",
     symptom="MuJoCo stops with \"mesh ... has coplanar vertices, cannot compute convex hull\" "
             "or \"at least 4 vertices required\".",
     cause="All of the mesh's points lie in one plane: a sketch, a surface body or a single "
           "face was exported instead of a solid.",
     fix="Export the solid body; for a plate give it its real thickness, or use a thin <box> "
         "as the collision geometry.",
     seen_in=("mujoco#759",))
rule("mesh-too-many-faces", ERROR, "mesh", "The STL mesh has more than 200,000 triangles",
     symptom="MuJoCo stops with \"number of faces should be between 1 and 200000 in STL "
             "file\".",
     cause="The part was exported at fine quality, or it has many small features (threads, "
           "knurls, fillets, text) that each become hundreds of triangles.",
     fix="Export with coarse quality (the exporter's mesh options, or SolidWorks' STL "
         "options), suppress cosmetic features before export, or decimate the mesh "
         "(MeshLab: Quadric Edge Collapse Decimation).",
     seen_in=("mujoco#327",))
rule("mesh-units", WARNING, "mesh", "The mesh looks as if it were in millimetres",
     symptom="The link shows up a thousand times too large; it fills the whole view, and "
             "contacts or the camera are far off.",
     cause="The STL was saved with SolidWorks' default unit, millimetres, instead of being "
           "written by the exporter (which writes metres), or copied from another tool. URDF "
           "lengths are metres.",
     fix="Save the STL in metres (SolidWorks: STL options, Unit: Meters), or add "
         "scale=\"0.001 0.001 0.001\" to the <mesh>.")
rule("mesh-heavy-collision", WARNING, "mesh", "The collision geometry is the full visual mesh",
     symptom="MuJoCo takes long to compile the model; Gazebo runs far slower than real time.",
     cause="The exporter writes the same mesh for <visual> and <collision>; a detailed part "
           "gives a collision mesh of tens of thousands of triangles.",
     fix="Use a simpler collision shape: a <box>, <cylinder> or <sphere> around the part, or "
         "a coarse or decimated copy of the mesh in meshes/ for <collision> only (`sw2sim "
         "port` writes such copies in meshes/simplified/ of the ROS 2 package).",
     seen_in=("solidworks_urdf_exporter#133",))


def check(ctx) -> None:
    """Add a finding to ctx for every problem of this group."""
    found: dict[Path, list] = {}
    unresolved: dict[str, list] = {}
    for mesh in _mesh_elements(ctx):
        filename = (mesh.get("filename") or "").strip()
        if not filename:
            ctx.add("mesh-no-filename", f"{_role(mesh)}: the <mesh> has no filename",
                    line=source_line(mesh, "filename"))
            continue
        path = ctx.mesh_file(mesh)
        if path is None:
            unresolved.setdefault(filename, []).append(mesh)
        else:
            found.setdefault(path, []).append(mesh)
    for filename, meshes in unresolved.items():
        _unresolved(ctx, filename, meshes)
    readable = {path for path, meshes in found.items() if _file(ctx, path, meshes)}
    for link in ctx.robot.findall("link"):
        _units(ctx, link, readable)
        _heavy_collision(ctx, link, readable)


def _mesh_elements(ctx):
    """Every <mesh> of every link, in file order."""
    for link in ctx.robot.findall("link"):
        yield from _link_meshes(link)


def _link_meshes(link):
    """The <mesh> elements of a link's <visual> and <collision> elements, in file order."""
    for element in link:
        if element.tag in ("visual", "collision"):
            yield from element.findall("geometry/mesh")


def _role(mesh) -> str:
    """'collision of link "x"', for messages."""
    kind = mesh.getparent().getparent().tag
    return f"{kind} of {owner(mesh)}"


def _also(ctx, meshes) -> str:
    """' (also named at lines 12, 40)' when more than one <mesh> names the same file."""
    lines = [str(source_line(m, "filename")) for m in meshes[1:]]
    return f" (also named at line{'s' if len(lines) > 1 else ''} {', '.join(lines)})" \
        if lines else ""


# -- paths -----------------------------------------------------------------------------

def _unresolved(ctx, filename: str, meshes) -> None:
    """Say why a mesh path does not lead to a file in the package (once per path)."""
    package = ctx.package
    first = meshes[0]
    line = source_line(first, "filename")
    named = f'{_role(first)}: mesh "{filename}"'
    if filename.startswith("package://"):
        # A path naming another package is looked for in the folder given, as
        # Context.mesh_file reads it: package-name-mismatch reports the name, and each
        # missing file is still reported here.
        name, _, rest = filename[len("package://"):].partition("/")
        target = package.root / rest
    elif filename.startswith("file://"):
        target = Path(filename[len("file://"):])
    else:
        target = package.urdf.parent / filename
    lexical = Path(os.path.normpath(target))
    try:
        resolved = target.resolve()
    except (OSError, RuntimeError):  # a symbolic link loop, a name too long
        ctx.add("mesh-not-found", f"{named} cannot be followed to a file (a loop of "
                f"symbolic links, or a name too long){_also(ctx, meshes)}", line=line)
        return
    if not _inside(resolved, package.root):
        how = (f"through a symbolic link to {resolved}" if _inside(lexical, package.root)
               else f"to {resolved}")
        fixed, hint, fix = (None, "", None) if _inside(lexical, package.root) else \
            _path_repair(ctx, filename, meshes)
        ctx.add("mesh-outside-package", f"{named} leads {how}, outside the package folder "
                f"{display(package.root)}; the file was not opened{hint}{_also(ctx, meshes)}",
                line=line, fix=fix, repair=fixed)
        return
    try:
        exists = resolved.exists()
    except OSError:  # a name too long for the file system
        exists = False
    if exists:
        ctx.add("mesh-not-found", f"{named} is not a regular file ({display(resolved)})"
                f"{_also(ctx, meshes)}", line=line)
        return
    hint = ""
    if filename.startswith("package://") and name != package.name:
        hint = (f'; "{name}" is not this package\'s name (package-name-mismatch), so the '
                f"path was read in the folder given, {display(package.root)}")
    elif filename.startswith("package://"):
        hint = (f"; package://{package.name}/ stands for the package folder "
                f"{display(package.root)}")
    elif not filename.startswith("file://"):
        hint = "; a relative path starts at the URDF's folder"
    fixed, found, fix = _path_repair(ctx, filename, meshes)
    ctx.add("mesh-not-found", f"{named} not found: looked for {display(resolved)}{hint}{found}"
            f"{_also(ctx, meshes)}", line=line, fix=fix, repair=fixed)


def _path_repair(ctx, filename: str, meshes):
    """(repair, what the package holds, fix) for a mesh path that leads to no file: the
    repair when exactly one file can be meant, else None and the closest files."""
    files = ctx.package_files()
    found = matches(files, filename)
    if len(found) == 1:
        new = f"package://{ctx.package.name}/{found[0].as_posix()}"
        variants = case_variants(files, found[0])
        why = ("the file whose name matches the path's exactly, capitals too (beside it, "
               f"{', '.join(v.as_posix() for v in variants)} differs in capitals only)"
               if variants else "the one file in the package the path can mean")
        return (repair(f'the mesh is read from {found[0].as_posix()}, {why}',
                       *((m, set_attribute("filename", new)) for m in meshes)),
                f"; the package holds {found[0].as_posix()}",
                f'write filename="{new}": the name exactly as on disk, with / (Linux and ROS tell '
                "capitals apart; Windows does not)")
    if found:
        names = ", ".join(f.as_posix() for f in found[:5])
        return (None, f"; it could mean any of {names}",
                "write the path of the one that is meant, as package://"
                f"{ctx.package.name}/<folder>/<file>")
    near = closest(files, filename)
    if near:
        return (None, f"; the closest files are {', '.join(f.as_posix() for f in near)}", None)
    return None, "", None


def _inside(path: Path, root: Path) -> bool:
    return root in path.parents


# -- file contents ----------------------------------------------------------------------

def _file(ctx, path: Path, meshes) -> bool:
    """Check one mesh file (named by `meshes`); True when its geometry is usable."""
    first = meshes[0]
    line = source_line(first, "filename")
    named = f'{_role(first)}: {display(path)}'
    also = _also(ctx, meshes)
    suffix = path.suffix.lower()
    if lfs_pointer(path):
        ctx.add("mesh-lfs-pointer", f"{named} is a Git LFS pointer ({path.stat().st_size} "
                f"bytes of text), not the mesh{also}", line=line, fix=LFS_FIX)
        return False
    if suffix not in MUJOCO_FORMATS:
        kind = f'a "{suffix}" file' if suffix else "a file without an extension"
        ctx.add("mesh-format", f"{named} is {kind}; MuJoCo reads .stl, .obj and .msh "
                f"only{also}", line=line, repair=_format_repair(ctx, path, meshes))
    if suffix == ".msh":
        return False  # MuJoCo's own format: nothing here reads it
    if suffix == ".stl":
        problem = _stl_problem(path)
        if problem:
            rule_id, message = problem
            ctx.add(rule_id, f"{named} {message}{also}", line=line)
            if rule_id in ("mesh-empty", "mesh-unreadable"):
                return False
    scaled = [m for m in meshes if _scale_ok(m)]
    if not scaled:
        return False  # every <mesh> naming it has a malformed scale: structure.py says so
    mesh = ctx.mesh(scaled[0])
    if mesh is None:
        if suffix == ".obj" and not _obj_has_faces(path):
            ctx.add("mesh-empty", f"{named} has no faces (no \"f\" lines){also}", line=line)
        else:
            ctx.add("mesh-unreadable", f"{named} cannot be read as a mesh{also}", line=line)
        return False
    bad = int(np.count_nonzero(~np.isfinite(mesh.vertices)))
    if bad:
        ctx.add("mesh-unreadable", f"{named} has {bad} vertex coordinates that are not finite "
                f"numbers (NaN or infinity){also}", line=line)
        return False
    flat = _flatness(mesh.vertices)
    if flat:
        ctx.add("mesh-flat", f"{named} {flat}{also}", line=line)
        return False
    return True


def _format_repair(ctx, path: Path, meshes):
    """What convert does about a mesh MuJoCo cannot decode (as `sw2sim.load_package` does
    it, see sw2sim.mesh_formats): read the readable file of the same name beside it, or else
    convert it when it can be read at all."""
    root = ctx.package.root
    other = beside(path)
    if other is not None:
        return repair(f"the mesh is read from {other.relative_to(root).as_posix()}, the file "
                      f"of the same name beside {path.name} in a format MuJoCo reads")
    if any(_scale_ok(m) and ctx.mesh(m) is not None for m in meshes):
        return repair(f"{path.relative_to(root).as_posix()} is converted to binary STL with "
                      "trimesh (in metres) and the model reads that; "
                      "there is no readable file of the same name beside it")
    return None


def _scale_ok(mesh) -> bool:
    text = mesh.get("scale")
    return text is None or vector(text, 3) is not None


def _stl_problem(path: Path) -> tuple[str, str] | None:
    """(rule id, message) for an STL file MuJoCo would refuse, from its size and header."""
    try:
        size = path.stat().st_size
        with path.open("rb") as stream:
            head = stream.read(84)
    except OSError as exc:
        return "mesh-unreadable", f"cannot be read ({exc.strerror or type(exc).__name__})"
    if size == 0:
        return "mesh-empty", "is empty (0 bytes)"
    if size >= 84:
        count = int.from_bytes(head[80:84], "little")
        if size == 84 + 50 * count:
            if count == 0:
                return "mesh-empty", "is a binary STL header that announces no triangles"
            if count > STL_FACE_LIMIT:
                return ("mesh-too-many-faces", f"has {count:,} triangles; MuJoCo reads at most "
                        f"{STL_FACE_LIMIT:,}")
            return None
    if size < 84:
        return "mesh-empty", f"holds only {size} bytes: an STL header and no triangles"
    if head.lstrip()[:5].lower() == b"solid" and _text(path):
        facets = _count(path, b"endfacet")
        if facets == 0:
            return "mesh-empty", "is a text (ASCII) STL without a single facet"
        return "mesh-ascii-stl", f"is a text (ASCII) STL with {facets:,} facets"
    return ("mesh-unreadable", f"is {size:,} bytes long, but its binary STL header announces "
            f"{count:,} triangles, which take {84 + 50 * count:,} bytes (a cut-short copy, "
            "or not an STL file)")


def _text(path: Path) -> bool:
    """Whether the file starts as text does. A binary STL's 80-byte header may say "solid"
    too (SolidWorks writes one so), but the triangles after it are not text."""
    with path.open("rb") as stream:
        start = stream.read(1024)
    return not start.translate(None, _TEXT_BYTES)


_TEXT_BYTES = bytes(range(32, 127)) + b"\t\n\r\f\v"


def _count(path: Path, token: bytes) -> int:
    """How often `token` occurs in a file, read in blocks."""
    total, tail = 0, b""
    with path.open("rb") as stream:
        while block := stream.read(1 << 20):
            data = tail + block
            total += data.count(token)
            tail = data[-(len(token) - 1):]
    return total


def _obj_has_faces(path: Path) -> bool:
    try:
        with path.open("rb") as stream:
            return any(line.lstrip().startswith(b"f ") for line in stream)
    except OSError:
        return True


def _flatness(vertices: np.ndarray) -> str | None:
    """Why MuJoCo cannot build a hull from these points, or None when it can."""
    if len(vertices) < 4:
        return f"has only {len(vertices)} vertices; MuJoCo needs at least 4"
    spread = np.linalg.svd(vertices - vertices.mean(axis=0), compute_uv=False)
    if spread[2] <= FLAT * spread[0]:
        return "is flat: all its vertices lie in one plane (or on one line or point)"
    return None


# -- units and weight --------------------------------------------------------------------


def _units(ctx, link, readable: set) -> None:
    seen = set()
    for mesh_el in _link_meshes(link):
        path = ctx.mesh_file(mesh_el)
        if path not in readable or path in seen:
            continue
        seen.add(path)
        mesh = ctx.mesh(mesh_el)
        why = None if mesh is None else millimetre_suspect(link, mesh)
        if why:
            ctx.add("mesh-units", f"{_role(mesh_el)}: {display(path)} looks like millimetres: "
                    f"{why}", line=source_line(mesh_el, "filename"))


def _heavy_collision(ctx, link, readable: set) -> None:
    visual = {ctx.mesh_file(m) for m in link.findall("visual/geometry/mesh")}
    seen = set()
    for mesh_el in link.findall("collision/geometry/mesh"):
        path = ctx.mesh_file(mesh_el)
        if path not in readable or path not in visual or path in seen:
            continue
        seen.add(path)
        mesh = ctx.mesh(mesh_el)
        if mesh is None or len(mesh.faces) <= HEAVY_FACES:
            continue
        if path.suffix.lower() != ".stl" or len(mesh.faces) <= STL_FACE_LIMIT:  # else an error
            ctx.add("mesh-heavy-collision", f"{_role(mesh_el)}: the collision geometry is the "
                    f"visual mesh {display(path)}, {len(mesh.faces):,} triangles (more than "
                    f"{HEAVY_FACES:,})", line=source_line(mesh_el, "filename"))


# -- geometry for the other checks -------------------------------------------------------


