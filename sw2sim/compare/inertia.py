"""When two inertia tensors differ, and the one mistake that moves a tensor by a known
amount: taken about the link's frame (the joint's) instead of the centre of mass.

URDF's <inertia> is about the centre of mass, in the axes of the <inertial> origin; the
exporter writes it so. SolidWorks' Mass Properties lists the same body's moments three
times: principal, "taken at the center of mass" (Lxx, Lxy, ...) and "taken at the output
coordinate system" (Ixx, Ixy, ...). Copying the last into the URDF gives the tensor about
the link's origin, which is the centre-of-mass one plus the parallel-axis (Steiner) term

    I_origin = I_com + m (|d|^2 * 1 - d d^T),   d: the centre of mass seen from the origin,

so such a tensor is recognised exactly, where the moments alone would only say "spread
differently".
"""

from __future__ import annotations

import numpy as np

from . import tolerances as tol


def parallel_axis(mass: float, d) -> np.ndarray:
    """What moving the axes from the centre of mass to a point `d` away adds to a tensor."""
    d = np.asarray(d, dtype=float)
    return mass * (float(d @ d) * np.eye(3) - np.outer(d, d))


def difference(tensor_m: np.ndarray, tensor_r: np.ndarray) -> str | None:
    """How `tensor_m` differs from `tensor_r` (both in the same axes): "moments" when a
    principal moment is off, "turned" when only the axes are, None within tolerance.

    Principal moments under SMALL_MOMENT of the largest are judged against that share of
    the largest, as the faceting of the large features decides their error."""
    moments_r, moments_m = np.linalg.eigvalsh(tensor_r), np.linalg.eigvalsh(tensor_m)
    floor = tol.SMALL_MOMENT * max(moments_r[-1], 0.0)
    if np.any(np.abs(moments_m - moments_r) > tol.INERTIA * np.maximum(moments_r, floor)):
        return "moments"
    if np.linalg.norm(tensor_m - tensor_r) > tol.INERTIA * np.linalg.norm(tensor_r):
        return "turned"
    return None


def about_origin(tensor_m, tensor_r, mass: float, centre) -> bool:
    """Whether `tensor_m` is `tensor_r` taken about the link's origin instead of its centre
    of mass, `centre` away (all in the same axes), and not `tensor_r` itself."""
    if mass <= 0:
        return False
    moved = tensor_r + parallel_axis(mass, centre)
    return difference(tensor_m, tensor_r) is not None and difference(tensor_m, moved) is None
