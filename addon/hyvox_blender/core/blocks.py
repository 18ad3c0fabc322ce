# SPDX-License-Identifier: GPL-3.0-or-later
"""Voxels as blocks: a mesh of one cube per occupied voxel with only the exposed faces
(no face between two occupied voxels), welded at shared corners, with each face's colour
taken from its voxel. numpy only; no bpy.

Voxel (i,j,k) covers [origin + (i,j,k)*s, origin + (i+1,j+1,k+1)*s] (docs/design.md), so the
blocks sit exactly where the voxels are, with no half-voxel shift."""

from dataclasses import dataclass
from typing import Optional, Tuple

import numpy as np

# The six sides: the direction to the neighbour, and the side's corners on the unit cube
# in counter-clockwise order seen from outside (so normals point out of the solid).
DIRECTIONS = np.array([(1, 0, 0), (-1, 0, 0), (0, 1, 0), (0, -1, 0), (0, 0, 1), (0, 0, -1)], np.int64)
SIDE_CORNERS = np.array(
    [
        [(1, 0, 0), (1, 1, 0), (1, 1, 1), (1, 0, 1)],
        [(0, 0, 0), (0, 0, 1), (0, 1, 1), (0, 1, 0)],
        [(0, 1, 0), (0, 1, 1), (1, 1, 1), (1, 1, 0)],
        [(0, 0, 0), (1, 0, 0), (1, 0, 1), (0, 0, 1)],
        [(0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)],
        [(0, 0, 0), (0, 1, 0), (1, 1, 0), (1, 0, 0)],
    ],
    np.int64,
)


@dataclass
class BlocksMesh:
    vertices: np.ndarray  # (V,3) float32, world space
    faces: np.ndarray  # (F,4) int32 vertex indices, normals outwards
    face_voxels: np.ndarray  # (F,) int64: index of the voxel (row of ijk) a face belongs to
    face_sides: np.ndarray  # (F,) int8: index into DIRECTIONS
    face_colors: Optional[np.ndarray]  # (F,3) float32 linear RGB, or None


def _keys(ijk: np.ndarray, low: np.ndarray, extent: np.ndarray) -> np.ndarray:
    """One int64 per cell of the box [low, low + extent)."""
    shifted = ijk - low
    return (shifted[:, 0] * extent[1] + shifted[:, 1]) * extent[2] + shifted[:, 2]


def exposed_faces(ijk: np.ndarray) -> Tuple[np.ndarray, np.ndarray]:
    """(voxel index, side index) of every side of a voxel whose neighbour is empty.
    Duplicate rows in ijk are an error (a voxel is occupied or not)."""
    ijk = np.asarray(ijk, dtype=np.int64).reshape(-1, 3)
    if len(ijk) == 0:
        return np.zeros(0, np.int64), np.zeros(0, np.int8)
    low = ijk.min(axis=0) - 1  # room for the neighbours outside
    extent = ijk.max(axis=0) - low + 2
    if float(np.prod(extent.astype(np.float64))) >= 2.0**62:
        raise ValueError("the voxels span too large a box to index")
    keys = _keys(ijk, low, extent)
    order = np.argsort(keys)
    sorted_keys = keys[order]
    if np.any(sorted_keys[1:] == sorted_keys[:-1]):
        raise ValueError("the same voxel is listed twice")
    voxels, sides = [], []
    for side, step in enumerate(DIRECTIONS):
        neighbour = _keys(ijk + step, low, extent)
        at = np.minimum(np.searchsorted(sorted_keys, neighbour), len(sorted_keys) - 1)
        empty = sorted_keys[at] != neighbour
        index = np.nonzero(empty)[0]
        voxels.append(index)
        sides.append(np.full(len(index), side, np.int8))
    return np.concatenate(voxels), np.concatenate(sides)


def blocks_mesh(
    ijk: np.ndarray, voxel_size: float, origin=(0.0, 0.0, 0.0), colors: Optional[np.ndarray] = None
) -> BlocksMesh:
    """The blocks of the voxels ijk (K,3) of a grid (voxel_size, origin); colors (K,3), per
    voxel, become per-face colours."""
    ijk = np.asarray(ijk, dtype=np.int64).reshape(-1, 3)
    if colors is not None:
        colors = np.asarray(colors, dtype=np.float32).reshape(-1, 3)
        if len(colors) != len(ijk):
            raise ValueError(f"{len(colors)} colours for {len(ijk)} voxels")
    face_voxels, face_sides = exposed_faces(ijk)
    corners = ijk[face_voxels][:, None, :] + SIDE_CORNERS[face_sides]  # (F,4,3) lattice points
    flat = corners.reshape(-1, 3)
    if len(flat):
        low = flat.min(axis=0)
        extent = flat.max(axis=0) - low + 1
        unique, inverse = np.unique(_keys(flat, low, extent), return_inverse=True)
        # Back from keys to lattice points: the inverse of _keys.
        k = unique % extent[2]
        j = (unique // extent[2]) % extent[1]
        i = unique // (extent[1] * extent[2])
        lattice = np.stack([i, j, k], axis=1) + low
    else:
        inverse, lattice = np.zeros(0, np.int64), np.zeros((0, 3), np.int64)
    vertices = (np.asarray(origin, np.float64) + lattice * float(voxel_size)).astype(np.float32)
    faces = inverse.reshape(-1, 4).astype(np.int32)
    face_colors = colors[face_voxels] if colors is not None else None
    return BlocksMesh(vertices, faces, face_voxels, face_sides, face_colors)
