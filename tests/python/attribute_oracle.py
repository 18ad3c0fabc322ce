# SPDX-License-Identifier: GPL-3.0-or-later
"""The attribute voxel definition (docs/design.md, "Attributes"), written independently in numpy.

For each voxel v, over the triangles t whose closed box meets v:
    value(v) = sum_t w_t * a_t(c_t) / sum_t w_t
with w_t = area of t clipped to v's closed box (voxel units) + 1e-6 and c_t the centroid of the
clipped polygon; a touch without area (clipped area below TOUCH_AREA) uses the midpoint of the
two clipped points farthest apart (a point: the point). a_t(c) is t's attribute interpolated
with its barycentrics at c (clamped to [0, 1] and renormalised), a texture sampled at the
interpolated UV. Normals: the same mean, then normalised; a mean shorter than
CANCELLED_NORMAL_LENGTH (opposite faces cancelling in a voxel) is zero.

All clipping is Sutherland-Hodgman in double, vectorised over every (triangle, voxel) pair.
"""

from __future__ import annotations

import numpy as np

AREA_EPSILON = 1e-6  # the weight of a touch
TOUCH_AREA = 1e-14  # clipped areas below this count as a touch (voxel units²)
MAX_VERTICES = 9  # a triangle clipped by 6 half-spaces has at most 3 + 6 corners
CANCELLED_NORMAL_LENGTH = 1e-5  # a shorter mean normal has no direction: zero
TOUCH_MARGIN = 1e-9  # box growth that finds touches the exact clip loses to rounding


def srgb_to_linear(c):
    c = np.asarray(c, dtype=np.float64)
    return np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)


def load_texture(path) -> np.ndarray:
    """(H, W, C) float64 linear texels, row 0 = the image's top row; alpha stays linear."""
    from PIL import Image

    image = Image.open(path)
    array = np.asarray(image)
    scale = 65535.0 if array.dtype == np.uint16 else 255.0
    if array.ndim == 2:
        array = np.stack([array] * 3, axis=-1)
    values = array.astype(np.float64) / scale
    values[..., :3] = srgb_to_linear(values[..., :3])
    return values


def sample_texture(texels: np.ndarray, uv: np.ndarray) -> np.ndarray:
    """Bilinear, repeat wrap; texel centres at (x + 0.5) / W; v = 0 is the image's bottom row."""
    height, width = texels.shape[:2]
    x = uv[:, 0] * width - 0.5
    y = (1.0 - uv[:, 1]) * height - 0.5
    x0, y0 = np.floor(x), np.floor(y)
    fx, fy = (x - x0)[:, None], (y - y0)[:, None]
    x0 = x0.astype(np.int64) % width
    y0 = y0.astype(np.int64) % height
    x1, y1 = (x0 + 1) % width, (y0 + 1) % height
    top = texels[y0, x0] * (1 - fx) + texels[y0, x1] * fx
    bottom = texels[y1, x0] * (1 - fx) + texels[y1, x1] * fx
    return top * (1 - fy) + bottom * fy


def _clip(polys: np.ndarray, counts: np.ndarray, axis: int, bound: np.ndarray, keep_above: bool):
    """Clips every polygon to x[axis] >= bound (keep_above) or x[axis] <= bound."""
    pairs = polys.shape[0]
    out = np.zeros_like(polys)
    out_counts = np.zeros_like(counts)
    rows = np.arange(pairs)
    for e in range(MAX_VERTICES):
        active = e < counts
        nxt_index = np.where(e + 1 < counts, e + 1, 0)
        cur = polys[:, e]
        nxt = polys[rows, nxt_index]
        sign = 1.0 if keep_above else -1.0
        dc = sign * (cur[:, axis] - bound)
        dn = sign * (nxt[:, axis] - bound)
        keep = active & (dc >= 0)
        out[rows[keep], out_counts[keep]] = cur[keep]
        out_counts += keep
        cross = active & (((dc > 0) & (dn < 0)) | ((dc < 0) & (dn > 0)))
        with np.errstate(divide="ignore", invalid="ignore"):
            t = dc / (dc - dn)
            point = cur + (nxt - cur) * t[:, None]
            point[:, axis] = bound  # exactly on the plane
        out[rows[cross], out_counts[cross]] = point[cross]
        out_counts += cross
    return out, out_counts


def _polygon_area_centroid(polys: np.ndarray, counts: np.ndarray):
    pairs = polys.shape[0]
    area = np.zeros(pairs)
    moment = np.zeros((pairs, 3))
    p0 = polys[:, 0]
    for k in range(1, MAX_VERTICES - 1):
        valid = (k + 1) < counts
        a = polys[:, k] - p0
        b = polys[:, k + 1] - p0
        tri = 0.5 * np.linalg.norm(np.cross(a, b), axis=1)
        tri = np.where(valid, tri, 0.0)
        area += tri
        moment += tri[:, None] * (p0 + polys[:, k] + polys[:, k + 1]) / 3.0
    # Touches: the midpoint of the farthest pair of clipped points.
    index = np.arange(MAX_VERTICES)
    valid = index[None, :] < counts[:, None]
    diff = polys[:, :, None, :] - polys[:, None, :, :]
    dist = np.einsum("pijk,pijk->pij", diff, diff)
    dist = np.where(valid[:, :, None] & valid[:, None, :], dist, -1.0)
    flat = dist.reshape(pairs, -1).argmax(axis=1)
    i, j = flat // MAX_VERTICES, flat % MAX_VERTICES
    rows = np.arange(pairs)
    midpoint = 0.5 * (polys[rows, i] + polys[rows, j])
    touch = area < TOUCH_AREA
    with np.errstate(divide="ignore", invalid="ignore"):
        centroid = np.where(touch[:, None], midpoint, moment / area[:, None])
    return area, centroid


def _barycentrics(corners: np.ndarray, points: np.ndarray) -> np.ndarray:
    a, b, c = corners[:, 0], corners[:, 1], corners[:, 2]
    v0, v1, v2 = b - a, c - a, points - a
    d00 = np.einsum("ij,ij->i", v0, v0)
    d01 = np.einsum("ij,ij->i", v0, v1)
    d11 = np.einsum("ij,ij->i", v1, v1)
    d20 = np.einsum("ij,ij->i", v2, v0)
    d21 = np.einsum("ij,ij->i", v2, v1)
    denom = d00 * d11 - d01 * d01
    v = (d11 * d20 - d01 * d21) / denom
    w = (d00 * d21 - d01 * d20) / denom
    bary = np.clip(np.stack([1.0 - v - w, v, w], axis=1), 0.0, 1.0)
    return bary / bary.sum(axis=1, keepdims=True)


def clipped_pairs(corners: np.ndarray, dims, margin=0.0, only=None):
    """Every (triangle, voxel) pair whose clip is non-empty, for voxel-space triangles (M, 3, 3),
    the boxes grown by margin; only: a set of voxel keys (i * ny + j) * nz + k to look at.

    Returns (triangle index, voxel ijk (P, 3), weight, centroid)."""
    lo = np.ceil(corners.min(axis=1)).astype(np.int64) - 1
    hi = np.floor(corners.max(axis=1)).astype(np.int64)
    lo = np.maximum(lo, 0)
    hi = np.minimum(hi, np.asarray(dims) - 1)
    tri_ids, voxels = [], []
    for t in range(corners.shape[0]):
        if (hi[t] < lo[t]).any():
            continue
        grid = np.stack(
            np.meshgrid(*[np.arange(lo[t, a], hi[t, a] + 1) for a in range(3)], indexing="ij"), axis=-1
        ).reshape(-1, 3)
        voxels.append(grid)
        tri_ids.append(np.full(len(grid), t))
    tri_ids = np.concatenate(tri_ids)
    voxels = np.concatenate(voxels)
    if only is not None:
        wanted = np.isin((voxels[:, 0] * dims[1] + voxels[:, 1]) * dims[2] + voxels[:, 2], np.fromiter(only, np.int64))
        tri_ids, voxels = tri_ids[wanted], voxels[wanted]
    polys = np.zeros((len(tri_ids), MAX_VERTICES, 3))
    polys[:, :3] = corners[tri_ids]
    counts = np.full(len(tri_ids), 3)
    for axis in range(3):
        polys, counts = _clip(polys, counts, axis, voxels[:, axis] - margin, True)
        polys, counts = _clip(polys, counts, axis, voxels[:, axis] + 1.0 + margin, False)
    hit = counts > 0
    tri_ids, voxels, polys, counts = tri_ids[hit], voxels[hit], polys[hit], counts[hit]
    area, centroid = _polygon_area_centroid(polys, counts)
    return tri_ids, voxels, area + AREA_EPSILON, centroid


def voxel_attributes(
    vertices,
    triangles,
    origin,
    voxel_size,
    dims,
    *,
    colors=None,
    uvs=None,
    texture=None,
    material_ids=None,
    palette=None,
    normals=None,
    voxels=None,
):
    """Returns (ijk (K, 3) sorted, dict name -> (K, n) arrays).

    colors: per-vertex linear (N, 3|4); uvs (N, 2) + texture (H, W, C) linear texels;
    material_ids (M,) + palette (P, 3|4); normals (N, 3) per vertex, else face normals.
    voxels: the voxels an exact method set (K, 3), if known: those no clip reaches (a touch
    lost to rounding) take the pieces of boxes grown by TOUCH_MARGIN, as the methods do."""
    vertices = np.asarray(vertices, dtype=np.float32).astype(np.float64)
    triangles = np.asarray(triangles, dtype=np.int64)
    corners_world = vertices[triangles]
    corners = (corners_world - np.asarray(origin, dtype=np.float64)) / float(voxel_size)
    cross = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    usable = (
        (np.linalg.norm(cross, axis=1) > 0)
        & (triangles[:, 0] != triangles[:, 1])
        & (triangles[:, 1] != triangles[:, 2])
        & (triangles[:, 0] != triangles[:, 2])
    )
    keep = np.nonzero(usable)[0]
    tri_local, found, weight, centroid = clipped_pairs(corners[keep], dims)
    if voxels is not None:
        voxels = np.asarray(voxels, dtype=np.int64)
        set_keys = set(((voxels[:, 0] * dims[1] + voxels[:, 1]) * dims[2] + voxels[:, 2]).tolist())
        found_keys = set(((found[:, 0] * dims[1] + found[:, 1]) * dims[2] + found[:, 2]).tolist())
        lost = set_keys - found_keys
        if lost:
            more = clipped_pairs(corners[keep], dims, TOUCH_MARGIN, lost)
            tri_local, found, weight, centroid = (
                np.concatenate([a, b]) for a, b in zip((tri_local, found, weight, centroid), more)
            )
    voxels = found
    tri = keep[tri_local]
    bary = _barycentrics(corners[tri], centroid)

    def interpolate(per_vertex):
        per_vertex = np.asarray(per_vertex, dtype=np.float64)
        return np.einsum("pc,pcn->pn", bary, per_vertex[triangles[tri]])

    values = {}
    if texture is not None:
        values["color"] = sample_texture(np.asarray(texture, dtype=np.float64), interpolate(uvs))
    elif colors is not None:
        values["color"] = interpolate(colors)
    elif palette is not None:
        values["color"] = np.asarray(palette, dtype=np.float64)[np.asarray(material_ids)[tri]]
    if normals is not None:
        values["normal"] = interpolate(normals)
    else:
        face = cross / np.linalg.norm(cross, axis=1, keepdims=True).clip(1e-300)
        values["normal"] = face[tri]

    keys = (voxels[:, 0] * dims[1] + voxels[:, 1]) * dims[2] + voxels[:, 2]
    order = np.unique(keys, return_inverse=True)
    unique_keys, inverse = order
    sum_weight = np.bincount(inverse, weights=weight)
    out = {}
    for name, value in values.items():
        sums = np.stack([np.bincount(inverse, weights=weight * value[:, c]) for c in range(value.shape[1])], axis=1)
        mean = sums / sum_weight[:, None]
        if name == "color" and mean.shape[1] == 4:
            out["alpha"] = mean[:, 3]
            mean = mean[:, :3]
        if name == "normal":
            length = np.linalg.norm(mean, axis=1, keepdims=True)
            # Where opposite faces cancel (a two-sided wall) the mean is zero but for rounding,
            # which differs between any two area formulas: zero below the line. The length is
            # kept so that a comparison can leave out the few means rounding puts near the line.
            out["normal_length"] = length[:, 0]
            direction = length > CANCELLED_NORMAL_LENGTH
            mean = np.where(direction, mean / np.where(direction, length, 1), 0)
        out[name] = mean
    ijk = np.stack(
        [unique_keys // (dims[1] * dims[2]), (unique_keys // dims[2]) % dims[1], unique_keys % dims[2]], axis=1
    )
    return ijk, out
