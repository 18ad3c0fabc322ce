# SPDX-License-Identifier: GPL-3.0-or-later
"""The colour each exported part brings (numpy only, no bpy), and how the parts of one group
combine into the one colour source hyvox.voxelize takes.

A part's colour is per triangle corner, in one of two forms:
- `corner_colors` (3M,4) float32 linear RGBA: a colour attribute, or per-slot base colours
  (the same colour on a triangle's three corners), or Blender's default grey;
- `uvs` (3M,2) with `texture` (the image as hyvox takes it: uint8 sRGB or float linear,
  row 0 = top) for the triangles in `textured` (a (M,) bool mask), the rest of the part's
  triangles taking `corner_colors`.

An `alpha` grid is made only when some colour is not opaque (alpha < 1).

Combining (one call of hyvox.voxelize per group): when every triangle of the group is
textured by one and the same image, the group is passed as uvs + texture, so the native
code samples the image inside each voxel (nothing lost). Otherwise every part becomes
per-corner colours: attribute and per-slot colours lose nothing that way, while a texture
is sampled at the corners only (its detail inside a triangle is lost); combine() says so
in its warning."""

from dataclasses import dataclass
from typing import Optional, Sequence, Tuple

import numpy as np

from .pipeline import merge_meshes

DEFAULT_GREY = (0.8, 0.8, 0.8, 1.0)  # what Blender renders an object without material as


@dataclass
class PartColour:
    corner_colors: Optional[np.ndarray] = None  # (3M,4) float32 linear
    uvs: Optional[np.ndarray] = None  # (3M,2) float32, with texture
    texture: Optional[np.ndarray] = None  # (H,W,3|4) uint8 sRGB or float32 linear
    texture_key: str = ""  # which image (the same key: the same pixels)
    textured: Optional[np.ndarray] = None  # (M,) bool: triangles that take the texture

    def fully_textured(self) -> bool:
        return self.texture is not None and self.textured is not None and bool(self.textured.all())


def srgb_to_linear(encoded: np.ndarray) -> np.ndarray:
    """The sRGB transfer function's inverse (IEC 61966-2-1), as hyvox decodes bytes."""
    encoded = np.asarray(encoded, np.float64)
    return np.where(encoded <= 0.04045, encoded / 12.92, ((encoded + 0.055) / 1.055) ** 2.4)


def texture_linear(texture: np.ndarray) -> np.ndarray:
    """(H,W,4) float64 linear RGBA of a texture in hyvox's form (uint8/uint16 sRGB, float linear)."""
    texture = np.asarray(texture)
    if texture.dtype.kind == "u":
        rgb = srgb_to_linear(texture[..., :3] / float(np.iinfo(texture.dtype).max))
        alpha = (
            texture[..., 3:4] / float(np.iinfo(texture.dtype).max)
            if texture.shape[-1] == 4
            else np.ones(texture.shape[:2] + (1,))
        )
    else:
        rgb = texture[..., :3].astype(np.float64)
        alpha = texture[..., 3:4].astype(np.float64) if texture.shape[-1] == 4 else np.ones(texture.shape[:2] + (1,))
    return np.concatenate([rgb, alpha], axis=-1)


def sample_bilinear(texture: np.ndarray, uvs: np.ndarray) -> np.ndarray:
    """(K,4) linear RGBA of the texture at uvs, bilinear with repeat wrap, v = 0 the bottom
    row (hyvox's texture convention: pixel centres at (i + 0.5) / size)."""
    pixels = texture_linear(texture)
    height, width = pixels.shape[:2]
    x = np.asarray(uvs[:, 0], np.float64) * width - 0.5
    y = (1.0 - np.asarray(uvs[:, 1], np.float64)) * height - 0.5  # row 0 = top
    x0, y0 = np.floor(x), np.floor(y)
    fx, fy = (x - x0)[:, None], (y - y0)[:, None]
    xi = [np.mod(x0.astype(np.int64) + d, width) for d in (0, 1)]
    yi = [np.mod(y0.astype(np.int64) + d, height) for d in (0, 1)]
    top = pixels[yi[0], xi[0]] * (1 - fx) + pixels[yi[0], xi[1]] * fx
    bottom = pixels[yi[1], xi[0]] * (1 - fx) + pixels[yi[1], xi[1]] * fx
    return top * (1 - fy) + bottom * fy


def _as_corner_colors(part: PartColour, triangle_count: int) -> np.ndarray:
    colors = (
        np.array(part.corner_colors, np.float32)
        if part.corner_colors is not None
        else np.tile(np.float32(DEFAULT_GREY), (3 * triangle_count, 1))
    )
    if part.texture is not None and part.textured is not None and part.textured.any():
        corners = np.repeat(part.textured, 3)
        colors[corners] = sample_bilinear(part.texture, part.uvs[corners]).astype(np.float32)
    return colors


def combine(parts: Sequence[Tuple[np.ndarray, np.ndarray, Optional[PartColour]]]):
    """From the group's (vertices, triangles, colour) parts: (vertices, triangles, the colour
    keyword arguments for hyvox.voxelize, a warning or ""). No part with a colour: no
    colour arguments. The vertices and triangles are merged like pipeline.merge_meshes; in
    the texture form they are unshared (one vertex per corner) so each corner keeps its UV."""
    vertices, triangles = merge_meshes([(v, t) for v, t, _ in parts])
    colours = [c for _, _, c in parts]
    if all(c is None for c in colours):
        return vertices, triangles, {}, ""
    keys = {c.texture_key for c in colours if c is not None and c.texture is not None}
    if len(keys) == 1 and all(c is not None and c.fully_textured() for c in colours):
        uvs = np.concatenate([c.uvs for c in colours]).astype(np.float32, copy=False)
        corners = vertices[triangles.reshape(-1)]
        unshared = np.arange(len(corners), dtype=np.uint32).reshape(-1, 3)
        return corners, unshared, {"uvs": uvs, "texture": colours[0].texture}, ""
    corner_colors = np.concatenate(
        [_as_corner_colors(c if c is not None else PartColour(), len(t)) for _, t, c in parts]
    )
    warning = ""
    if keys:
        warning = (
            "Color: textures sampled at the triangle corners (objects with different color "
            "sources or images voxelized together); one object at a time keeps the texture's detail"
        )
    if np.all(corner_colors[:, 3] == 1.0):
        corner_colors = np.ascontiguousarray(corner_colors[:, :3])  # opaque: no `alpha` grid
    return vertices, triangles, {"colors": corner_colors}, warning
