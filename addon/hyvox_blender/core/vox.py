# SPDX-License-Identifier: GPL-3.0-or-later
"""MagicaVoxel .vox export (format version 150) of a set of voxels, numpy only.

A .vox model holds at most 256 voxels per side, so larger sets are split into models of at
most 256^3, each placed by the scene graph (nTRN -> nGRP -> nTRN/nSHP per model). Each
model's size is made even, so its translation (MagicaVoxel places a model by its centre,
size/2) is a whole number and voxel (x,y,z) of a model lies at translation - size/2 + (x,y,z).
The palette holds at most 255 colours (sRGB, 8 bits): the voxels' linear colours are
converted to sRGB and, when there are more than 255 distinct ones, quantised by median cut."""

import os
import struct
from typing import List, Optional, Tuple

import numpy as np

MODEL_LIMIT = 256  # voxels per side of one model (the format stores coordinates as bytes)
PALETTE_SIZE = 255  # index 0 means empty
DEFAULT_COLOR = (204, 204, 204)


def linear_to_srgb8(linear: np.ndarray) -> np.ndarray:
    c = np.clip(np.asarray(linear, dtype=np.float64), 0.0, 1.0)
    srgb = np.where(c <= 0.0031308, 12.92 * c, 1.055 * np.power(c, 1.0 / 2.4) - 0.055)
    return np.round(srgb * 255.0).astype(np.uint8)


def quantise(srgb: np.ndarray, limit: int = PALETTE_SIZE) -> Tuple[np.ndarray, np.ndarray]:
    """(palette (P,3) uint8, index (K,) int into the palette) with P <= limit: the distinct
    colours when they fit, else median cut (split the box of colours with the widest channel
    range, weighted by use, at the median, until there are `limit` boxes; each box's colour
    is its weighted mean)."""
    unique, inverse = np.unique(np.asarray(srgb, np.uint8).reshape(-1, 3), axis=0, return_inverse=True)
    inverse = inverse.reshape(-1)
    if len(unique) <= limit:
        return unique, inverse
    weights = np.bincount(inverse, minlength=len(unique)).astype(np.float64)
    values = unique.astype(np.float64)
    boxes: List[np.ndarray] = [np.arange(len(unique))]
    while len(boxes) < limit:
        spans = [float(np.ptp(values[b], axis=0).max()) if len(b) > 1 else -1.0 for b in boxes]
        widest = int(np.argmax(spans))
        if spans[widest] <= 0:
            break
        box = boxes.pop(widest)
        channel = int(np.argmax(np.ptp(values[box], axis=0)))
        box = box[np.argsort(values[box, channel], kind="stable")]
        cumulative = np.cumsum(weights[box])
        cut = int(np.searchsorted(cumulative, cumulative[-1] / 2.0))
        cut = min(max(cut, 1), len(box) - 1)  # both halves non-empty
        boxes += [box[:cut], box[cut:]]
    palette = np.zeros((len(boxes), 3), np.uint8)
    box_of = np.empty(len(unique), np.int64)
    for n, box in enumerate(boxes):
        palette[n] = np.round(np.average(values[box], axis=0, weights=weights[box])).astype(np.uint8)
        box_of[box] = n
    return palette, box_of[inverse]


def _chunk(tag: bytes, content: bytes, children: bytes = b"") -> bytes:
    return tag + struct.pack("<ii", len(content), len(children)) + content + children


def _string(text: str) -> bytes:
    data = text.encode()
    return struct.pack("<i", len(data)) + data


def _dict(pairs: dict) -> bytes:
    return struct.pack("<i", len(pairs)) + b"".join(_string(k) + _string(v) for k, v in pairs.items())


def _transform(node: int, child: int, layer: int, translation: Optional[Tuple[int, int, int]]) -> bytes:
    frame = {"_t": " ".join(str(int(t)) for t in translation)} if translation is not None else {}
    return _chunk(
        b"nTRN", struct.pack("<i", node) + _dict({}) + struct.pack("<iiii", child, -1, layer, 1) + _dict(frame)
    )


def split_models(ijk: np.ndarray):
    """[(model min corner (3,), model size (3,), rows of ijk in it)], models of at most
    MODEL_LIMIT per side, sizes even."""
    low = ijk.min(axis=0)
    block = (ijk - low) // MODEL_LIMIT
    keys = np.unique(block, axis=0)
    models = []
    for key in keys:
        rows = np.nonzero(np.all(block == key, axis=1))[0]
        corner = low + key * MODEL_LIMIT
        size = ijk[rows].max(axis=0) - corner + 1
        size = np.minimum(size + (size % 2), MODEL_LIMIT)  # even (MODEL_LIMIT is even)
        models.append((corner, size, rows))
    return models


def vox_bytes(ijk: np.ndarray, colors: Optional[np.ndarray] = None) -> Tuple[bytes, int]:
    """(the .vox file of voxels ijk (K,3) with optional linear colours (K,3), its number of
    models)."""
    ijk = np.asarray(ijk, dtype=np.int64).reshape(-1, 3)
    if len(ijk) == 0:
        raise ValueError("no voxels to write")
    if colors is not None:
        palette, index = quantise(linear_to_srgb8(np.asarray(colors).reshape(-1, 3)))
    else:
        palette, index = np.array([DEFAULT_COLOR], np.uint8), np.zeros(len(ijk), np.int64)
    models = split_models(ijk)
    children = []
    for corner, size, rows in models:
        local = (ijk[rows] - corner).astype(np.uint8)
        records = np.concatenate([local, (index[rows] + 1).astype(np.uint8)[:, None]], axis=1)
        children.append(_chunk(b"SIZE", struct.pack("<iii", *(int(s) for s in size))))
        children.append(_chunk(b"XYZI", struct.pack("<i", len(rows)) + records.tobytes()))
    # Scene graph: root transform 0 -> group 1 -> (transform 2+2m -> shape 3+2m -> model m).
    shape_ids = [3 + 2 * m for m in range(len(models))]
    children.append(_transform(0, 1, -1, None))
    children.append(
        _chunk(
            b"nGRP",
            struct.pack("<i", 1)
            + _dict({})
            + struct.pack("<i", len(models))
            + b"".join(struct.pack("<i", s - 1) for s in shape_ids),
        )
    )
    for m, (corner, size, _) in enumerate(models):
        children.append(_transform(shape_ids[m] - 1, shape_ids[m], 0, tuple(corner + size // 2)))
        children.append(
            _chunk(
                b"nSHP",
                struct.pack("<i", shape_ids[m]) + _dict({}) + struct.pack("<i", 1) + struct.pack("<i", m) + _dict({}),
            )
        )
    rgba = np.zeros((256, 4), np.uint8)
    rgba[: len(palette), :3] = palette
    rgba[:, 3] = 255
    children.append(_chunk(b"RGBA", rgba.tobytes()))
    return b"VOX " + struct.pack("<i", 150) + _chunk(b"MAIN", b"", b"".join(children)), len(models)


def write_vox(path: str, ijk: np.ndarray, colors: Optional[np.ndarray] = None) -> int:
    """Write atomically (a sibling temporary file renamed into place); returns the number of
    models the voxels were split into."""
    data, models = vox_bytes(ijk, colors)
    temporary = f"{path}.{os.getpid()}.partial"
    try:
        with open(temporary, "wb") as f:
            f.write(data)
        os.replace(temporary, path)
    except BaseException:
        if os.path.exists(temporary):
            os.remove(temporary)
        raise
    return models
