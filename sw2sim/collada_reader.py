"""COLLADA (.dae) meshes in their common simple form, read without trimesh.

Packages made for RViz name COLLADA files; trimesh reads them through pycollada, and
importing the two (with scipy and networkx behind them) costs more than a second, most of
what `sw2sim check` takes on such a package. Blender, MeshLab, SketchUp and trimesh itself
write one simple form, read here with lxml and numpy: geometries whose <mesh> holds
<triangles>, <polylist> of triangles only or <polygons> of triangles only, with positions
from the <float_array> of the <source> that <vertices> names as POSITION; placed by the
<node>s of the one <visual_scene> (nested, with <matrix>, <translate>, <rotate> and <scale>);
in metres by the document's <unit meter="...">. Like pycollada and trimesh, the <up_axis> is
recorded by nobody: Z_UP and Y_UP files come out as written.

`read_collada` gives the triangles trimesh gives (`trimesh.load(path, force="mesh",
process=False)`, then scaled by `sw2sim.mesh_formats.in_metres`), in the same order and with
the same numbers: positions as float32 as pycollada parses them, transforms composed and
applied as pycollada and trimesh do, mirror transforms reversing each face's corners.
trimesh merges the corners of each primitive by position (to 1e-8), normal and texture
coordinate; here they are merged by the file's own indices, so the vertices can be fewer than
trimesh's where normals split a position, and two positions of a file closer than 1e-8 stay
two (the check merges them itself). tests/tool/check/test_collada_reader.py compares both.

Anything else raises NotSimple, for trimesh to read: controllers and skins, <instance_node>,
libraries of nodes, images or animations, lines, strips and fans, polygons of more than three
corners, inputs other than positions, normals and texture coordinates, references that do not
resolve or leave the file, numbers that are not numbers, positions that are not finite. The
geometry is checked as strictly as pycollada checks it; materials, effects, cameras and lights
are only checked to be referred to correctly. A document that declares a DOCTYPE or entities
is parsed by nobody (Refused), as every XML file sw2sim reads (sw2sim.xmlsafe).
"""

from __future__ import annotations

import numpy as np
from lxml import etree

from . import xmlsafe

NAMESPACE = "http://www.collada.org/2005/11/COLLADASchema"   # COLLADA 1.4, what all write

# The root's children read here or passed over (materials and the rest are only referred to).
_TOP = {"asset", "library_geometries", "library_visual_scenes", "library_materials",
        "library_effects", "library_cameras", "library_lights", "scene", "extra"}
_NODE_PARTS = {"node", "instance_geometry", "instance_camera", "instance_light", "extra",
               "asset", "translate", "rotate", "scale", "matrix"}
_PRIMITIVE_PARTS = {"triangles": {"input", "p", "extra"},
                    "polylist": {"input", "vcount", "p", "extra"},
                    "polygons": {"input", "p", "extra"}}
_SHADERS = ("phong", "lambert", "blinn", "constant")
# How many numbers each input's <source> gives per item.
_WIDTH = {"POSITION": 3, "NORMAL": 3, "TEXCOORD": 2}
_INT32_MAX = 2 ** 31 - 1
# trimesh's tolerances: a transform closer than this to the identity is not applied, and
# one whose 3 x 3 part is this close to it is not a rotation (so it cannot mirror).
_IDENTITY_CLOSE, _ROTATION_CLOSE = 1e-8, 1e-6
# A placement this close to a rotation, but not closer, trimesh makes exactly one.
_RIGID_EXACT, _RIGID_CLOSE = 1e-13, 1e-5
_EYE = np.eye(4)
# trimesh scales "<unit> * meters" to metres through inches (trimesh.units): the same
# divisions here give the same numbers.
_INCHES_PER_METRE = 1 / 0.0254


class NotSimple(Exception):
    """The file is not in the form read here: trimesh reads it."""


class Refused(ValueError):
    """A document that declares a DOCTYPE or entities: sw2sim parses no such XML."""


def _tag(name: str) -> str:
    return f"{{{NAMESPACE}}}{name}"


def _name(element) -> str | None:
    """The local name of a COLLADA element; None for a comment or processing instruction."""
    if not isinstance(element.tag, str):
        return None
    if not element.tag.startswith(f"{{{NAMESPACE}}}"):
        raise NotSimple   # another namespace (COLLADA 1.5, none, an extension)
    return element.tag[len(NAMESPACE) + 2:]


def read_collada(data: bytes) -> tuple[np.ndarray, np.ndarray]:
    """The triangles of a COLLADA document, in metres: (vertices n x 3, faces m x 3).
    Raises Refused for a document with a DOCTYPE, NotSimple for one to leave to trimesh."""
    with np.errstate(all="ignore"):   # numbers beyond float32 are found and left, unsaid
        return _read(data)


def _read(data: bytes) -> tuple[np.ndarray, np.ndarray]:
    try:
        root = xmlsafe.parse_bytes(data)
    except xmlsafe.DoctypeDeclared:
        raise Refused("it declares a DOCTYPE, which sw2sim does not read") from None
    except etree.XMLSyntaxError:
        raise NotSimple from None   # malformed, or beyond the parser's limits
    if root is None or root.tag != _tag("COLLADA"):
        raise NotSimple
    parts = {}
    for child in root:
        name = _name(child)
        if name is not None and (name not in _TOP or (name in parts and name != "extra")):
            raise NotSimple   # controllers, library_nodes, images, animations, or two of one
        parts[name] = child
    materials = _materials(parts.get("library_materials"), parts.get("library_effects"))
    geometries = {}
    for geometry in _children(parts.get("library_geometries"), "geometry"):
        key = geometry.get("id")
        if not key or key in geometries or key == "world":
            raise NotSimple   # "world" is the root of trimesh's scene, which it confuses
        geometries[key] = _geometry(geometry)
    pieces: list[tuple[np.ndarray, np.ndarray]] = []
    for node in _children(_scene(parts), "node"):
        _place(node, _EYE, geometries, materials, pieces)
    if not pieces:
        return np.zeros((0, 3)), np.zeros((0, 3), dtype=np.int64)
    offsets = np.cumsum([0] + [len(v) for v, _ in pieces[:-1]])
    vertices = np.concatenate([v for v, _ in pieces])
    faces = np.concatenate([f + offset for (_, f), offset in zip(pieces, offsets)])
    unit = _unit(parts.get("asset"))
    if unit is not None:
        scale = np.eye(4)
        scale[:3, :3] *= _INCHES_PER_METRE * unit / _INCHES_PER_METRE
        vertices, faces = _moved(vertices, faces, scale)
    return vertices, faces


def _children(parent, name: str) -> list:
    """`parent`'s children called `name`; every other child but extra and asset is
    NotSimple (so nothing this reader does not know is passed over)."""
    if parent is None:
        return []
    found = []
    for child in parent:
        local = _name(child)
        if local == name:
            found.append(child)
        elif local not in (None, "extra", "asset"):
            raise NotSimple
    return found


def _materials(library, effects) -> set[str]:
    """The ids of the materials whose effect exists and has a common profile with a
    shader (pycollada drops the others, and with them every geometry instance that binds
    one)."""
    effect_ids = {e.get("id") for e in _children(effects, "effect")
                  if any(e.find(f"{_tag('profile_COMMON')}/{_tag('technique')}/{_tag(shader)}")
                         is not None for shader in _SHADERS)}
    found = set()
    for material in _children(library, "material"):
        effect = material.find(_tag("instance_effect"))
        url = effect.get("url") if effect is not None else None
        if url and url.startswith("#") and url[1:] in effect_ids:
            found.add(material.get("id"))
    return found


def _scene(parts: dict):
    """The one <visual_scene>, which <scene> instances."""
    scenes = _children(parts.get("library_visual_scenes"), "visual_scene")
    scene = parts.get("scene")
    instance = scene.find(_tag("instance_visual_scene")) if scene is not None else None
    if len(scenes) != 1 or instance is None or not scenes[0].get("id") \
            or instance.get("url") != "#" + scenes[0].get("id"):
        raise NotSimple
    return scenes[0]


def _unit(asset) -> float | None:
    """The length of the document's unit in metres; None for metres (as trimesh, which
    takes a unit within numpy's isclose of 1 for metres, and no number for none)."""
    unit = asset.find(_tag("unit")) if asset is not None else None
    if unit is None:
        return None
    try:
        metres = float(unit.get("meter"))
    except (TypeError, ValueError):
        return None
    if not (np.isfinite(metres) and metres > 0):
        raise NotSimple
    return None if np.isclose(metres, 1.0) else metres


def _numbers(text: str | None, dtype) -> np.ndarray:
    """The numbers in an element's text, parsed as pycollada parses them (an empty or
    missing text is none)."""
    if text is None or text.isspace():
        return np.zeros(0, dtype=dtype)
    try:
        return np.fromstring(text, dtype=dtype, sep=" ")
    except ValueError:
        raise NotSimple from None


def _indices(text: str | None) -> np.ndarray:
    found = _numbers(text, np.int64)   # pycollada's int32 would wrap a larger number round
    if len(found) and (found.min() < 0 or found.max() > _INT32_MAX):
        raise NotSimple
    return found


def _source(source) -> np.ndarray:
    """A <source>'s float_array, one row per item of its accessor."""
    array = source.find(_tag("float_array"))
    accessor = source.find(f"{_tag('technique_common')}/{_tag('accessor')}")
    params = source.findall(f"{_tag('technique_common')}/{_tag('accessor')}/{_tag('param')}")
    if array is None or accessor is None or not params:
        raise NotSimple   # names or references instead of numbers, or no layout
    if accessor.get("stride", str(len(params))).strip() != str(len(params)) \
            or accessor.get("offset", "0").strip() != "0":
        raise NotSimple   # numbers skipped between items: pycollada does not skip them
    values = _numbers(array.text, np.float32)
    if len(values) % len(params):
        raise NotSimple
    return values.reshape(-1, len(params))


def _geometry(geometry) -> list[tuple[np.ndarray, np.ndarray]]:
    """A geometry's primitives, each as (vertices, faces) in the geometry's own frame."""
    meshes = _children(geometry, "mesh")
    if len(meshes) != 1:
        raise NotSimple   # <convex_mesh>, <spline>, <brep>, or nothing
    sources, vertices, primitives = {}, None, []
    for part in meshes[0]:
        name = _name(part)
        if name == "source":
            key = part.get("id")
            if not key or key in sources:
                raise NotSimple
            sources[key] = _source(part)
        elif name == "vertices":
            if vertices is not None:
                raise NotSimple
            vertices = part
        elif name in _PRIMITIVE_PARTS:
            primitives.append(part)
        elif name != "extra":
            raise NotSimple   # lines, strips, fans, or what pycollada would not read (it
            # drops a geometry whose mesh holds anything else, even a comment)
    if vertices is None or not vertices.get("id") or vertices.get("id") in sources:
        raise NotSimple
    shared = [(i.get("semantic"), _reference(i, sources)) for i in _inputs(vertices)]
    semantics = [s for s, _ in shared]
    if "POSITION" not in semantics or len(set(semantics)) != len(semantics) \
            or not set(semantics) <= set(_WIDTH):
        raise NotSimple
    read = (_primitive(p, sources, vertices.get("id"), shared) for p in primitives)
    return [piece for piece in read if piece is not None]


def _inputs(element) -> list:
    found = element.findall(_tag("input"))
    if not found:
        raise NotSimple
    return found


def _input_semantic(element) -> str:
    semantic = element.get("semantic")
    if semantic not in _WIDTH and semantic != "VERTEX":
        raise NotSimple   # colours, tangents, and what pycollada does not know
    return semantic


def _reference(element, sources: dict) -> str:
    url = element.get("source") or ""
    if not url.startswith("#") or url[1:] not in sources:
        raise NotSimple
    return url[1:]


def _primitive(element, sources, vertices_id, shared):
    """One primitive's triangles as (vertices, faces), None when it has none; its
    corners' positions, normals and texture coordinates must all be in their sources."""
    kind = _name(element)
    for part in element:
        if _name(part) not in _PRIMITIVE_PARTS[kind] | {None}:
            raise NotSimple   # a polygon with holes (<ph>), or an unknown part
    columns = []   # (semantic, index column, source id)
    for item in _inputs(element):
        try:
            offset = int(item.get("offset"))
        except (TypeError, ValueError):
            raise NotSimple from None
        semantic = _input_semantic(item)
        if offset < 0 or offset > 64:
            raise NotSimple
        if semantic == "VERTEX":
            if item.get("source") != "#" + vertices_id:
                raise NotSimple
            columns += [(s, offset, key) for s, key in shared]
        else:
            columns.append((semantic, offset, _reference(item, sources)))
    semantics = [c[0] for c in columns]
    if semantics.count("POSITION") != 1 or semantics.count("NORMAL") > 1 \
            or sum(1 for i in _inputs(element) if i.get("semantic") == "VERTEX") != 1:
        raise NotSimple
    stride = 1 + max(c[1] for c in columns)
    index = _corners(element, kind, stride)
    if not len(index):
        return None
    for semantic, offset, key in columns:
        rows = sources[key]
        if rows.shape[1] != _WIDTH[semantic] or index[:, :, offset].max() >= len(rows):
            raise NotSimple
    positions = next(sources[key] for s, _, key in columns if s == "POSITION")
    if not np.isfinite(positions).all():
        raise NotSimple   # pycollada makes NaN 0, and trimesh drops infinite corners
    corners = index[:, :, next(o for s, o, _ in columns if s == "POSITION")]
    used, first, inverse = np.unique(corners.ravel(), return_index=True, return_inverse=True)
    order = np.argsort(first, kind="stable")   # vertices in the order of first use
    rank = np.empty(len(order), dtype=np.int64)
    rank[order] = np.arange(len(order))
    return positions[used[order]].astype(np.float64), rank[inverse].reshape(-1, 3)


def _corners(element, kind: str, stride: int) -> np.ndarray:
    """The primitive's indices as (triangles, 3 corners, stride)."""
    lists = element.findall(_tag("p"))
    if kind == "polygons":
        if any(p.text is None for p in lists):
            raise NotSimple
        polygons = [_indices(p.text) for p in lists]
        if any(len(p) != 3 * stride for p in polygons):
            raise NotSimple   # a polygon of more than three corners
        index = np.concatenate(polygons) if polygons else np.zeros(0, dtype=np.int64)
    else:
        if len(lists) != 1:
            raise NotSimple
        index = _indices(lists[0].text)
        if kind == "polylist":
            counts = element.findall(_tag("vcount"))
            if len(counts) != 1:
                raise NotSimple
            vcount = _indices(counts[0].text)
            if (vcount != 3).any() or 3 * stride * len(vcount) != len(index):
                raise NotSimple   # polygons of more than three corners
    if len(index) % (3 * stride):
        raise NotSimple
    return index.reshape(-1, 3, stride)


def _place(node, parent: np.ndarray, geometries, materials, pieces) -> None:
    """Add the triangles of `node` and the nodes under it, moved by `parent` and by the
    node's own transforms, to `pieces`, in the order trimesh adds them."""
    own, children = [], []
    for child in node:
        name = _name(child)
        if name is None or name in ("extra", "asset"):
            continue
        if name not in _NODE_PARTS:
            raise NotSimple   # instance_node, instance_controller, lookat, skew, ...
        if name in ("translate", "rotate", "scale", "matrix"):
            own.append(_transform(name, child.text))
        elif name in ("instance_camera", "instance_light"):
            if not (child.get("url") or "").startswith("#"):
                raise NotSimple
        else:
            children.append((name, child))
    # pycollada composes a node's transforms in float32; trimesh multiplies them in.
    matrix = np.identity(4, dtype=np.float32) if len(own) != 1 else own[0]
    if len(own) > 1:
        for transform in own:
            matrix = np.dot(matrix, transform)
    placed = np.dot(parent, matrix)
    if not np.isfinite(placed).all():
        raise NotSimple   # numbers that overflow float32 on the way
    for name, child in children:
        if name == "node":
            _place(child, placed, geometries, materials, pieces)
            continue
        url = child.get("url") or ""
        if not url.startswith("#") or url[1:] not in geometries:
            raise NotSimple   # another file's geometry, or none
        binding = f"{_tag('bind_material')}/{_tag('technique_common')}/" \
                  f"{_tag('instance_material')}"
        for bound in child.findall(binding):
            target = bound.get("target") or ""
            if not target.startswith("#") or target[1:] not in materials:
                raise NotSimple   # pycollada would drop the instance
        pieces += [_moved(v, f, _squared(placed)) for v, f in geometries[url[1:]]]


def _transform(name: str, text: str | None) -> np.ndarray:
    """A <translate>, <rotate> (axis and degrees), <scale> or <matrix> as the float32
    matrix pycollada makes of it."""
    if text is None:
        raise NotSimple
    values = _numbers(text, np.float32)
    if len(values) != {"translate": 3, "rotate": 4, "scale": 3, "matrix": 16}[name] \
            or not np.isfinite(values).all():
        raise NotSimple
    if name == "matrix":
        if (values[12:] != [0, 0, 0, 1]).any():
            raise NotSimple   # a projection, which trimesh's scene could not square
        return values.reshape(4, 4)
    matrix = np.identity(4, dtype=np.float32)
    if name == "translate":
        matrix[:3, 3] = values
    elif name == "scale":
        matrix[[0, 1, 2], [0, 1, 2]] = values
    else:
        x, y, z, degrees = values
        angle = degrees * np.pi / 180.0
        c, s = np.cos(angle), np.sin(angle)
        t = 1 - c   # about the axis as given, not made a unit vector (as pycollada)
        matrix[:3, :3] = [[t * x * x + c, t * x * y - s * z, t * x * z + s * y],
                          [t * x * y + s * z, t * y * y + c, t * y * z - s * x],
                          [t * x * z - s * y, t * y * z + s * x, t * z * z + c]]
    return matrix


def _squared(matrix: np.ndarray) -> np.ndarray:
    """A placement as trimesh's scene graph gives it: one whose 3 x 3 part is within 1e-5 of
    a rotation or mirror (float32 rounding, products of such) made exactly one, the
    orthogonal factor of its singular value decomposition; any other as it is."""
    turn = matrix[:3, :3]
    error = np.abs(np.dot(turn, turn.T) - _EYE[:3, :3]).max()
    if not _RIGID_EXACT < error < _RIGID_CLOSE:
        return matrix
    left, _, right = np.linalg.svd(turn)
    squared = np.eye(4)
    squared[:3, :3] = np.dot(left, right)
    squared[:3, 3] = matrix[:3, 3]
    return squared


def _moved(vertices: np.ndarray, faces: np.ndarray, matrix: np.ndarray):
    """`vertices` moved by the 4 x 4 `matrix` with trimesh's arithmetic, and `faces` with
    their corners reversed where it mirrors them (as trimesh's apply_transform)."""
    matrix = np.asarray(matrix, dtype=np.float64)
    if float(np.ptp(matrix - _EYE)) < _IDENTITY_CLOSE:
        return vertices, faces
    if len(vertices) and not np.abs(matrix - _EYE).max() < _IDENTITY_CLOSE:
        stacked = np.column_stack((vertices, np.ones(len(vertices))))
        vertices = np.dot(matrix, stacked.T).T[:, :3]
    rotates = not float(np.ptp(matrix[:3, :3] - _EYE[:3, :3])) < _ROTATION_CLOSE
    if rotates and np.linalg.det(matrix[:3, :3]) < 0.0:
        faces = np.ascontiguousarray(faces[:, ::-1])
    return vertices, faces
