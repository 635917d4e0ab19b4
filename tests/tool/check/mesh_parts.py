"""A part for the mesh reader tests (test_mesh_readers.py, test_collada_reader.py)."""

from __future__ import annotations

import trimesh


def part() -> trimesh.Trimesh:
    """A closed part with a few hundred triangles, off the origin and turned, so that its
    numbers have all their digits."""
    made = trimesh.creation.annulus(r_min=0.011, r_max=0.03, height=0.017, sections=40)
    made.apply_transform(trimesh.transformations.euler_matrix(0.3, -1.1, 2.0))
    made.apply_translation([0.123456789, -0.2, 0.05])
    return made
