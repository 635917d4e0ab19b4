"""Meshes with nothing to compare: files with no triangles, and shapes with no volume.

The comparison of a link's mesh measures its size, so a mesh that cannot be read was
simply left out of it. But two kinds of mesh read "fine" and are always a mistake, and
leaving them out let a package with them match the lesson's:

- an STL that holds no triangles: SolidWorks writes one, an 80-byte header and nothing
  more (or a header announcing 0 triangles), when the part was hidden or suppressed, or
  had no solid body, as the exporter saved the link's mesh;
- a mesh whose vertices all lie in one plane (or on one line, or at one point): it
  encloses no volume. A surface body or a sketch exported instead of a solid gives one,
  and so does a <mesh scale> with a 0 in it.

`sw2sim check` reports both for any package; here they are said as differences from the
lesson's, whose meshes are solids.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

# Thinner than this fraction of its largest spread, a mesh is flat (STL stores float32,
# whose rounding is 6e-8 of a coordinate; the thinnest real sheet is 1e-4 of its part).
FLAT = 1e-6
HEADER = 80          # bytes of a binary STL's header, before its triangle count


@dataclass
class MeshFault:
    file: str           # the mesh file, as the user would write it
    why: str            # what is wrong with it, after the file name: "holds no triangles ..."
    empty: bool         # no triangles at all (else: flat)
    scale_zero: bool = False   # the <mesh scale> has a 0 in it


def emptiness(file: Path) -> str | None:
    """Why a mesh file holds no triangles, or None when it holds some (or is not an STL,
    or cannot be read: `sw2sim check` names those)."""
    if file.suffix.lower() != ".stl":
        return None
    try:
        data = file.read_bytes()
    except OSError:
        return None
    if not data:
        return "is empty (0 bytes)"
    count = int.from_bytes(data[HEADER:HEADER + 4], "little") if len(data) >= HEADER + 4 else 0
    if len(data) >= HEADER + 4 and len(data) == HEADER + 4 + 50 * count:
        return None if count else "is a binary STL header that announces 0 triangles"
    if data.lstrip()[:5].lower() == b"solid" and _text(data[:1024]):
        return None if b"facet" in data else "is a text STL without a single facet"
    if len(data) < HEADER + 4:
        return f"is {len(data)} bytes long: a binary STL's header and not a single triangle"
    return None


def _text(start: bytes) -> bool:
    """Whether a file starts as text does: a binary STL's header may say "solid" too
    (SolidWorks writes one so), but the triangles after it are not text."""
    return not start.translate(None, bytes(range(32, 127)) + b"\t\n\r\f\v")


def flatness(vertices: np.ndarray) -> str | None:
    """Why a mesh encloses no volume (its vertices on one plane, line or point), or None."""
    if not len(vertices):
        return None
    spread = np.linalg.svd(vertices - vertices.mean(axis=0), compute_uv=False)
    if spread[0] <= 0:
        return "has all its vertices at one point, so it encloses no volume"
    if spread[1] <= FLAT * spread[0]:
        return "has all its vertices on one line, so it encloses no volume"
    if spread[2] <= FLAT * spread[0]:
        return "has all its vertices in one plane, so it encloses no volume"
    return None
