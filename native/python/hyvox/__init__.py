# SPDX-License-Identifier: GPL-3.0-or-later
"""hyvox: exact, fast surface voxelization of triangle meshes, with OpenVDB output.

    import hyvox
    vertices, triangles = hyvox.read_mesh("bunny.ply")
    grid = hyvox.voxelize(vertices, triangles, resolution=256)
    grid.coords()            # int32 (K, 3) voxel indices
    grid.write_vdb("bunny.vdb")

Voxel (i, j, k) covers the closed box [origin + (i, j, k) * s, origin + (i+1, j+1, k+1) * s]
with s = grid.voxel_size; the .vdb's index space is voxel centres.
"""
from __future__ import annotations

import os
from typing import Callable, Optional, Sequence, Tuple, Union

import numpy as np

from . import _core
from ._core import (
    BackendError,
    Cancelled,
    CancelToken,
    ResourceError,
    VoxelGrid,
    gl_devices,
)

__version__: str = _core.__version__
METHODS: Tuple[str, ...] = tuple(_core.METHODS)
MODES: Tuple[str, ...] = tuple(_core.MODES)

__all__ = [
    "BackendError",
    "CancelToken",
    "Cancelled",
    "METHODS",
    "MODES",
    "ResourceError",
    "VoxelGrid",
    "__version__",
    "gl_devices",
    "read_mesh",
    "voxelize",
]

_UINT32_MAX = np.iinfo(np.uint32).max


def _is_float32_or_64(dtype: np.dtype) -> bool:
    return dtype.kind == "f" and dtype.itemsize in (4, 8)  # either byte order


def _as_float_rows(values, name: str, width: int) -> np.ndarray:
    array = np.asarray(values)
    if not _is_float32_or_64(array.dtype):
        raise ValueError(f"{name} must be float32 or float64, got dtype {array.dtype}")
    if array.ndim != 2 or array.shape[1] != width:
        raise ValueError(f"{name} must have shape (N, {width}), got {array.shape}")
    return np.ascontiguousarray(array, dtype=np.float32)


def _as_vertices(vertices) -> np.ndarray:
    with np.errstate(over="ignore"):  # values beyond float32 become inf: rejected natively as non-finite
        return _as_float_rows(vertices, "vertices", 3)


def _as_triangles(triangles) -> np.ndarray:
    array = np.asarray(triangles)
    if array.dtype == np.bool_ or not np.issubdtype(array.dtype, np.integer):
        raise ValueError(f"triangles must have an integer dtype, got {array.dtype}")
    if array.ndim != 2 or array.shape[1] != 3:
        raise ValueError(f"triangles must have shape (M, 3), got {array.shape}")
    if array.dtype != np.uint32 and array.size:
        low, high = int(array.min()), int(array.max())
        if low < 0:
            raise ValueError(f"triangles contain a negative vertex index ({low})")
        if high > _UINT32_MAX:
            raise ValueError(f"triangles contain a vertex index too large for 32 bits ({high})")
    return np.ascontiguousarray(array, dtype=np.uint32)


def _as_vertex_rows(values, name: str, width: int) -> Optional[np.ndarray]:
    return None if values is None else _as_float_rows(values, name, width)


def voxelize(
    vertices,
    triangles,
    resolution: int = 256,
    voxel_size: Optional[float] = None,
    mode: str = "conservative",
    method: str = "cpu",
    padding: int = 0,
    threads: int = 0,
    origin: Optional[Sequence[float]] = None,
    progress: Optional[Callable[[int], object]] = None,
    cancel: Optional[CancelToken] = None,
    *,
    uvs=None,
    normals=None,
    bounds: Optional[Tuple[Sequence[float], Sequence[float]]] = None,
    memory_budget: Optional[int] = None,
    gl_device: Optional[str] = None,
    shader_dir: Optional[str] = None,
    hybrid_cutoff: Optional[float] = None,
    tess_gamma: Optional[float] = None,
    pn_triangles: Optional[bool] = None,
    displacement_image: Optional[str] = None,
    displacement_strength: Optional[float] = None,
    displacement_midlevel: Optional[float] = None,
    displacement_pixels=None,
    tess_counts: Optional[bool] = None,
    tess_measure_accuracy: Optional[bool] = None,
) -> VoxelGrid:
    """Voxelize the surface of a triangle mesh.

    vertices: (N, 3) float32 or float64 (converted to float32), world units.
    triangles: (M, 3) integer vertex indices (converted to uint32; negative or too large
        values raise ValueError). Degenerate triangles are skipped and counted in stats.
    resolution: voxels along the longest side of the mesh bounds; voxel_size overrides it.
    mode: "conservative" (every voxel the surface touches, 26-separating) or "thin"
        (6-separating). method: one of hyvox.METHODS ("cpu" is exact and needs no GPU).
    padding: empty voxels added on every side. threads: CPU threads, 0 = all cores.
    origin: world position of voxel (0, 0, 0)'s min corner (default: bounds min).
    progress: called on this thread with the percent done (int), while the voxelization
        waits; raising in it stops the voxelization and the exception propagates.
    cancel: a hyvox.CancelToken; token.cancel() from any thread raises hyvox.Cancelled here.
    bounds: ((x0, y0, z0), (x1, y1, z1)) grid bounds instead of the mesh's; geometry outside
        is clipped. memory_budget: bytes allowed for the bit grid (default 4 GiB).
    gl_device, shader_dir: GL methods ("" = auto device, "software", or an index).
    hybrid_cutoff: the hybrid method's large-triangle area cutoff in voxel units^2 (<0: auto).
    uvs, normals: optional per-vertex (N, 2) / (N, 3) floats (tessellation: displacement
        lookup, PN-triangles; absent normals are area-weighted vertex normals).
    tess_gamma, pn_triangles, displacement_image/_strength/_midlevel: tessellation method;
        displacement_pixels: a (height, width) float height image (row 0 = top) used instead
        of displacement_image; tess_counts: fill VoxelGrid.counts(); tess_measure_accuracy:
        also run the exact cpu method and put bias / false voxels in stats["metrics"].
    Unset (None) options take the native defaults.

    The GIL is released while native code runs. Raises ValueError for bad input,
    hyvox.ResourceError (a RuntimeError) when the grid does not fit the memory budget,
    hyvox.BackendError (a RuntimeError) when the method cannot run here, hyvox.Cancelled.
    """
    options = {
        "gl_device": gl_device,
        "shader_dir": shader_dir,
        "hybrid_cutoff": hybrid_cutoff,
        "tess_gamma": tess_gamma,
        "pn_triangles": pn_triangles,
        "displacement_image": displacement_image,
        "displacement_strength": displacement_strength,
        "displacement_midlevel": displacement_midlevel,
        "tess_counts": tess_counts,
        "tess_measure_accuracy": tess_measure_accuracy,
    }
    extra = {name: value for name, value in options.items() if value is not None}
    if origin is not None:
        origin = tuple(float(x) for x in origin)
        if len(origin) != 3:
            raise ValueError("origin must have 3 coordinates")
    if bounds is not None:
        low, high = (tuple(float(x) for x in corner) for corner in bounds)
        if len(low) != 3 or len(high) != 3:
            raise ValueError("bounds must be ((x0, y0, z0), (x1, y1, z1))")
        bounds = (low, high)
    if cancel is not None and not isinstance(cancel, CancelToken):
        raise TypeError("cancel must be a hyvox.CancelToken or None")
    if voxel_size is not None:
        voxel_size = float(voxel_size)
    if displacement_pixels is not None:
        pixels = np.asarray(displacement_pixels)
        if pixels.ndim != 2 or not np.issubdtype(pixels.dtype, np.number):
            raise ValueError(f"displacement_pixels must be a numeric (height, width) array, got {pixels.shape}")
        extra["displacement_pixels"] = np.ascontiguousarray(pixels, dtype=np.float32)
    return _core.voxelize(
        _as_vertices(vertices),
        _as_triangles(triangles),
        uvs=_as_vertex_rows(uvs, "uvs", 2),
        normals=_as_vertex_rows(normals, "normals", 3),
        resolution=int(resolution),
        voxel_size=voxel_size,
        mode=mode,
        method=method,
        padding=int(padding),
        threads=int(threads),
        origin=origin,
        bounds=bounds,
        memory_budget=memory_budget,
        cancel=cancel,
        progress=progress,
        **extra,
    )


def read_mesh(path: Union[str, os.PathLike], attributes: bool = False):
    """Read a mesh file (PLY binary/ascii, .ply.gz, OBJ, and what assimp reads).

    Returns (vertices float32 (N, 3), triangles uint32 (M, 3)), triangles exactly as in the
    file (degenerate ones included). With attributes=True, returns
    (vertices, triangles, attrs) where attrs may hold "colors" (float32 (N, 4) RGBA 0..1)
    and "uvs" (float32 (N, 2)). Raises ValueError for a missing or unreadable file.
    """
    vertices, triangles, colors, uvs = _core.read_mesh(os.fspath(path))
    if not attributes:
        return vertices, triangles
    attrs = {}
    if colors is not None:
        attrs["colors"] = colors
    if uvs is not None:
        attrs["uvs"] = uvs
    return vertices, triangles, attrs
