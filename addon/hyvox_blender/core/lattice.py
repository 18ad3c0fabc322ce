# SPDX-License-Identifier: GPL-3.0-or-later
"""A voxel lattice fixed in world space, for volumes that change over time (frame
sequences, Live): the voxel size is kept from the first evaluation and the grid's origin is
a whole multiple of it, so a part of the scene that does not move keeps exactly its voxels
while another part moves or deforms and the bounds change. Left to itself the module puts
the origin at each frame's bounds minimum, and every voxel of the static part shifts by
that frame's fraction of a voxel (the voxels swim)."""

import math
from dataclasses import dataclass
from typing import Optional, Tuple

import numpy as np

from .mesh_checks import box, used_vertices


@dataclass(frozen=True)
class Lattice:
    voxel_size: float
    origin: Tuple[float, float, float]  # voxel (0,0,0)'s min corner before padding: k * voxel_size


def used_bounds(vertices: np.ndarray, triangles: np.ndarray) -> Tuple[np.ndarray, np.ndarray]:
    """(min, max) float64 of the vertices the triangles use (the module's mesh bounds; a
    vertex no triangle uses would only widen the grid)."""
    if len(vertices) == 0 or len(triangles) == 0:
        raise ValueError("a lattice needs triangles")
    low, high = box(used_vertices(vertices, triangles))
    if not (np.isfinite(low).all() and np.isfinite(high).all()):  # min and max carry a NaN through
        raise ValueError("a vertex has a non-finite coordinate (NaN or Inf)")
    return low, high


def voxel_size_for_resolution(low: np.ndarray, high: np.ndarray, resolution: int) -> float:
    """The module's rule: the longest side of the bounds over the resolution."""
    longest = float(np.max(high - low))
    if not longest > 0.0:
        raise ValueError("the mesh has zero extent; give a voxel size instead of a resolution")
    return longest / resolution


def snapped_origin(low: np.ndarray, voxel_size: float) -> Tuple[float, float, float]:
    """The largest whole multiple of voxel_size at or below each coordinate of low."""
    origin = []
    for x in (float(v) for v in low):
        k = math.floor(x / voxel_size)
        if k * voxel_size > x:  # x / voxel_size rounded up to a whole number
            k -= 1
        origin.append(k * voxel_size)
    return tuple(origin)


def fixed_lattice(vertices: np.ndarray, triangles: np.ndarray, resolution: int, voxel_size: Optional[float]) -> Lattice:
    """The lattice for this evaluation: voxel_size when given (kept from the first
    evaluation), else the resolution's; the origin snapped to it."""
    low, high = used_bounds(vertices, triangles)
    size = float(voxel_size) if voxel_size else voxel_size_for_resolution(low, high, resolution)
    return Lattice(size, snapped_origin(low, size))
