# SPDX-License-Identifier: GPL-3.0-or-later
"""hyvox: exact, fast surface voxelization of triangle meshes, with OpenVDB output.

    import hyvox
    vertices, triangles = hyvox.read_mesh("bunny.ply")
    grid = hyvox.voxelize(vertices, triangles, resolution=256)
    grid.coords()            # int32 (K, 3) voxel indices
    grid.write_vdb("bunny.vdb")

One grid over many machines (docs/regions.md): voxelize(..., region="K/N") for K = 0 .. N-1,
each part written with write_vdb, then hyvox.merge_vdb(parts, "all.vdb") joins them into the
file the whole grid gives.

Voxel (i, j, k) covers the closed box [origin + (i, j, k) * s, origin + (i+1, j+1, k+1) * s]
with s = grid.voxel_size; the .vdb's index space is voxel centres.
"""

from __future__ import annotations

import os
import warnings
from typing import Callable, Iterable, List, Optional, Tuple, Union

import numpy as np

from . import _core
from ._core import (
    OPTIONS,
    WRITE_OPTIONS,
    BackendError,
    Cancelled,
    CancelToken,
    Options,
    OptionSpec,
    ResourceError,
    VoxelGrid,
    check_option,
    gl_devices,
    merge_vdb,
)

__version__: str = _core.__version__


def option(name: str) -> OptionSpec:
    """The schema entry of one option, of voxelize() (OPTIONS) or of VoxelGrid.write_vdb()
    (WRITE_OPTIONS); KeyError for an unknown name."""
    for spec in OPTIONS + WRITE_OPTIONS:
        if spec.name == name:
            return spec
    raise KeyError(name)


METHODS: Tuple[str, ...] = tuple(option("method").choices)
MODES: Tuple[str, ...] = tuple(option("mode").choices)


class IgnoredOptionWarning(UserWarning):
    """voxelize() was given an option the chosen method does not use (the CLI prints the
    same warning). Silence it with warnings.filterwarnings("ignore", category=...)."""


def ignored_options(method: str, names: Iterable[str]) -> List[str]:
    """Of the option `names`, those `method` ignores, in the given order: the schema's one
    rule (OptionSpec.applies_to), shared by the CLI, voxelize() and the Blender add-on.
    KeyError for an unknown option name, ValueError for an unknown method."""
    return [name for name in names if not option(name).applies_to(method)]


__all__ = [
    "BackendError",
    "CancelToken",
    "Cancelled",
    "IgnoredOptionWarning",
    "METHODS",
    "MODES",
    "OPTIONS",
    "OptionSpec",
    "Options",
    "ResourceError",
    "VoxelGrid",
    "WRITE_OPTIONS",
    "__version__",
    "check_option",
    "gl_devices",
    "ignored_options",
    "merge_vdb",
    "option",
    "plan_grid",
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


def _as_material_ids(values) -> np.ndarray:
    array = np.asarray(values)
    if array.dtype == np.bool_ or not np.issubdtype(array.dtype, np.integer) or array.ndim != 1:
        raise ValueError(f"material_ids must be a 1-D integer array, got {array.dtype} {array.shape}")
    if array.size and (int(array.min()) < 0 or int(array.max()) > _UINT32_MAX):
        raise ValueError("material_ids must lie in 0 .. 2**32 - 1")
    return np.ascontiguousarray(array, dtype=np.uint32)


def _as_vertex_rows(values, name: str, width: int) -> Optional[np.ndarray]:
    return None if values is None else _as_float_rows(values, name, width)


def voxelize(
    vertices,
    triangles,
    *,
    uvs=None,
    normals=None,
    displacement_pixels=None,
    colors=None,
    texture=None,
    material_ids=None,
    palette=None,
    textures=None,
    face_normals=None,
    progress: Optional[Callable[[int], object]] = None,
    cancel: Optional[CancelToken] = None,
    **options,
) -> VoxelGrid:
    """Voxelize the surface of a triangle mesh.

    vertices: (N, 3) float32 or float64 (converted to float32), world units.
    triangles: (M, 3) integer vertex indices (converted to uint32; negative or too large
        values raise ValueError). Degenerate triangles are skipped and counted in stats.
    uvs, normals: optional per-vertex (N, 2) / (N, 3) floats (tessellation: displacement
        lookup, PN-triangles; absent normals are area-weighted vertex normals).
    displacement_pixels: a (height, width) float height image (row 0 = top), used by the
        tessellation method instead of displacement_image.
    Attribute voxels (option attributes, e.g. attributes=("color", "normal") or "color,normal";
    the grid's attributes() returns them aligned with coords(); mode="solid": the inside takes
    the surface's values layer by layer inward, a whole-brick tile region one value for all its
    voxels). attributes=("sdf",) adds a narrow-band signed distance grid (the grid's sdf(),
    the .vdb's level set "sdf"; docs/sdf.md). Colour comes from the first source given:
    texture: a PNG path, or (height, width, 3|4) pixels (uint8/uint16: sRGB-encoded, float:
        linear; row 0 = top), sampled bilinearly with repeat wrap at uvs (v = 0: bottom row);
    colors: (N, 3|4) per vertex or (3M, 3|4) per triangle corner; uint8 = sRGB-encoded bytes
        (as in files and Blender byte colours), float = linear;
    material_ids: (M,) integers into palette: (P, 3|4) linear floats;
    textures: with them, one entry per palette colour: None (the flat colour) or a texture as
        above, sampled at uvs on that material's triangles instead (OBJ+MTL map_Kd).
    normals (N, 3) per vertex are interpolated; face_normals: (M, 3) per triangle; neither:
        the geometric normal.
    progress: called on this thread with the percent done (int), while the voxelization
        waits; raising in it stops the voxelization and the exception propagates.
    cancel: a hyvox.CancelToken; token.cancel() from any thread raises hyvox.Cancelled here.
    **options: the options of hyvox.OPTIONS by name (listed below). Unset or None options take
        the native default, after the environment variables the schema names.

    An option the chosen method does not use (e.g. tess_gamma with method="cpu") is ignored
    with a hyvox.IgnoredOptionWarning, as the CLI warns.

    The GIL is released while native code runs. Raises ValueError for bad input or an option
    out of its limits, TypeError for an unknown option or a value of the wrong kind,
    hyvox.ResourceError (a RuntimeError) when the grid does not fit the memory budget,
    hyvox.BackendError (a RuntimeError) when the method cannot run here, hyvox.Cancelled.
    """
    native_options = Options()
    native_options.apply_environment()
    for name, value in options.items():
        native_options.set(name, value)
    method = native_options.get("method")
    given = [name for name, value in options.items() if value is not None]
    for name in ignored_options(method, given):
        warnings.warn(f"{name} does not apply to the {method} method: ignored", IgnoredOptionWarning, stacklevel=2)
    if cancel is not None and not isinstance(cancel, CancelToken):
        raise TypeError("cancel must be a hyvox.CancelToken or None")
    pixels = None
    if displacement_pixels is not None:
        pixels = np.asarray(displacement_pixels)
        if pixels.ndim != 2 or not np.issubdtype(pixels.dtype, np.number):
            raise ValueError(f"displacement_pixels must be a numeric (height, width) array, got {pixels.shape}")
        pixels = np.ascontiguousarray(pixels, dtype=np.float32)
    colors_srgb = False
    if colors is not None:
        colors = np.asarray(colors)
        colors_srgb = colors.dtype == np.uint8
        colors = (
            colors.astype(np.float32) / 255.0
            if colors_srgb
            else _as_float_rows(colors, "colors", colors.shape[-1] if colors.ndim == 2 else 3)
        )
    texture_path = None
    if isinstance(texture, (str, os.PathLike)):
        texture_path, texture = os.fspath(texture), None
    elif texture is not None:
        texture = _as_texture_entry(texture)
    if material_ids is not None:
        material_ids = _as_material_ids(material_ids)
    if textures is not None:
        textures = [_as_texture_entry(entry) for entry in textures]
    return _core.voxelize(
        _as_vertices(vertices),
        _as_triangles(triangles),
        native_options,
        uvs=_as_vertex_rows(uvs, "uvs", 2),
        normals=_as_vertex_rows(normals, "normals", 3),
        displacement_pixels=pixels,
        colors=colors,
        colors_srgb=colors_srgb,
        texture=texture,
        texture_path=texture_path,
        material_ids=material_ids,
        palette=None if palette is None else _as_float_rows(palette, "palette", np.asarray(palette).shape[-1]),
        textures=textures,
        face_normals=_as_vertex_rows(face_normals, "face_normals", 3),
        cancel=cancel,
        progress=progress,
    )


def _as_texture_entry(texture):
    """A texture argument as the native module takes it: None, a path (str) or contiguous pixels."""
    if texture is None or isinstance(texture, str):
        return texture
    if isinstance(texture, os.PathLike):
        return os.fspath(texture)
    texture = np.asarray(texture)
    if texture.dtype.kind == "f":
        texture = texture.astype(np.float32)
    return np.ascontiguousarray(texture)


def _options_doc() -> str:
    """The option list of voxelize()'s docstring, from the schema."""
    lines = ["", "    Options (hyvox.OPTIONS; the CLI flag is --name with '-' for '_'):"]
    for spec in OPTIONS:
        default = "unset" if spec.nullable else repr(spec.default)
        unit = f" [{spec.unit}]" if spec.unit else ""
        env = f"; env {spec.env}" if spec.env else ""
        lines.append(f"    {spec.name} ({spec.type}, {spec.requirement}; default {default}{env}):")
        lines.append(f"        {spec.help}{unit}")
    return "\n".join(lines) + "\n"


voxelize.__doc__ = (voxelize.__doc__ or "") + _options_doc()


def plan_grid(vertices, triangles, **options) -> dict:
    """The grid voxelize() would lay out for this mesh and these options, without
    voxelizing: {"origin": (x, y, z), "voxel_size": s, "dims": (nx, ny, nz)}. The same
    validation (degenerate triangles do not count towards the bounds) and the same rule, so
    voxelize(..., voxel_size=plan_grid(...)["voxel_size"]) lays out the same grid."""
    native_options = Options()
    native_options.apply_environment()
    for name, value in options.items():
        native_options.set(name, value)
    return _core.plan_grid(_as_vertices(vertices), _as_triangles(triangles), native_options)


def read_mesh(
    path: Union[str, os.PathLike],
    attributes: bool = False,
    cancel: Optional[CancelToken] = None,
    memory_budget_mib: int = 0,
):
    """Read a mesh file: PLY, OBJ, STL, OFF and glTF/GLB (also gzipped, as mesh.ply.gz) by
    hyvox's own strict readers; binary FBX and 3MF through assimp, in a process of
    its own, so that no file can crash or hang the caller (docs/mesh-formats.md).

    Returns (vertices float32 (N, 3), triangles uint32 (M, 3)), triangles exactly as in the
    file (degenerate ones included). With attributes=True, returns
    (vertices, triangles, attrs) where attrs may hold "colors" (float32 (N, 4) RGBA 0..1),
    "uvs" (float32 (N, 2)) and, for an OBJ with materials, "material_ids" (uint32 (M,)),
    "palette" (float32 (P, 3), linear MTL Kd), "textures" (P paths of map_Kd PNGs or None)
    and "material_names"; these go to voxelize() as they are. What the reader could not use
    (a missing .mtl or image: the material keeps its Kd) is a UserWarning. Raises ValueError
    for a missing, unreadable or damaged file and a format hyvox does not read (the message
    names the file and what is wrong), and hyvox.Cancelled when `cancel` (a
    hyvox.CancelToken) is cancelled from another thread while the file is read (the GIL is
    released meanwhile). memory_budget_mib bounds a gzip's output and the assimp process's
    memory (0 = half of this machine's memory, as voxelize's memory_budget_mib).
    """
    if cancel is not None and not isinstance(cancel, CancelToken):
        raise TypeError("cancel must be a hyvox.CancelToken or None")
    vertices, triangles, colors, uvs, materials, problems = _core.read_mesh(
        os.fspath(path), cancel=cancel, memory_budget_mib=memory_budget_mib
    )
    if not attributes:
        return vertices, triangles
    for problem in problems:
        warnings.warn(problem, UserWarning, stacklevel=2)
    attrs = {}
    if colors is not None:
        attrs["colors"] = colors
    if uvs is not None:
        attrs["uvs"] = uvs
    if materials is not None:
        attrs.update(materials)
    return vertices, triangles, attrs
