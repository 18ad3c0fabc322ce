# SPDX-License-Identifier: GPL-3.0-or-later
"""Blocks output (core/blocks.py) against a dense numpy count of exposed faces, and the
MagicaVoxel .vox export (core/vox.py) read back by an independent parser written here from
the format's description."""

import os
import struct
import sys

import numpy as np
import pytest

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "addon"))

from hyvox_blender.core import blocks, vox  # noqa: E402


def dense_exposed_faces(ijk):
    """Per side (+x, -x, +y, -y, +z, -z): occupied cells whose neighbour that way is empty,
    counted on a padded dense array."""
    ijk = np.asarray(ijk).reshape(-1, 3)
    low = ijk.min(axis=0)
    shape = ijk.max(axis=0) - low + 3
    occ = np.zeros(shape, bool)
    occ[tuple((ijk - low + 1).T)] = True
    counts = []
    for axis in range(3):
        for step in (1, -1):
            neighbour = np.roll(occ, -step, axis=axis)  # the padding makes the wrap-around empty
            counts.append(int(np.count_nonzero(occ & ~neighbour)))
    return counts


def random_voxels(seed, n, extent):
    rng = np.random.default_rng(seed)
    return np.unique(rng.integers(-extent, extent, size=(n, 3)), axis=0)


CASES = {
    "one": np.array([[0, 0, 0]]),
    "cube2": np.stack(np.meshgrid(*[np.arange(2)] * 3, indexing="ij"), -1).reshape(-1, 3),
    "sparse": random_voxels(1, 200, 50),
    "dense": random_voxels(2, 4000, 10),
    "negative": random_voxels(3, 500, 4) - 1000,
}


@pytest.mark.parametrize("name", CASES)
def test_face_counts_match_a_dense_count(name):
    ijk = CASES[name]
    mesh = blocks.blocks_mesh(ijk, 0.5, (1.0, 2.0, 3.0))
    per_side = np.bincount(mesh.face_sides, minlength=6).tolist()
    assert per_side == dense_exposed_faces(ijk)
    assert len(mesh.faces) == sum(per_side)


def test_voxelized_bunny_blocks(bunny):
    import hyvox

    grid = hyvox.voxelize(*bunny, resolution=48, method="cpu")
    ijk = grid.coords()
    mesh = blocks.blocks_mesh(ijk, grid.voxel_size, grid.origin)
    assert np.bincount(mesh.face_sides, minlength=6).tolist() == dense_exposed_faces(ijk)
    # Every block lies where its voxel is: inside the grid's box.
    low = np.array(grid.origin)
    high = low + np.array(grid.dims) * grid.voxel_size
    assert np.all(mesh.vertices >= low - 1e-4) and np.all(mesh.vertices <= high + 1e-4)


def test_faces_face_out_of_the_solid_and_corners_are_welded():
    ijk = CASES["dense"]
    size, origin = 0.25, np.array([1.0, -2.0, 0.5])
    mesh = blocks.blocks_mesh(ijk, size, origin)
    occupied = {tuple(v) for v in ijk}
    corners = mesh.vertices[mesh.faces].astype(np.float64)  # (F,4,3)
    normal = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    np.testing.assert_allclose(normal, blocks.DIRECTIONS[mesh.face_sides] * size * size, atol=1e-5)
    centre = corners.mean(axis=1)
    inside = np.floor((centre - origin) / size - 0.5 * blocks.DIRECTIONS[mesh.face_sides]).astype(int)
    outside = inside + blocks.DIRECTIONS[mesh.face_sides]
    assert all(tuple(v) in occupied for v in inside)
    assert not any(tuple(v) in occupied for v in outside)
    # Welded: one vertex per distinct corner, each used.
    assert len(np.unique(mesh.vertices, axis=0)) == len(mesh.vertices)
    assert set(np.unique(mesh.faces)) == set(range(len(mesh.vertices)))


def test_face_colours_come_from_their_voxel():
    ijk = CASES["sparse"]
    colors = np.random.default_rng(5).random((len(ijk), 3)).astype(np.float32)
    mesh = blocks.blocks_mesh(ijk, 1.0, (0, 0, 0), colors)
    np.testing.assert_array_equal(mesh.face_colors, colors[mesh.face_voxels])
    assert blocks.blocks_mesh(ijk, 1.0).face_colors is None


def test_bad_input():
    with pytest.raises(ValueError, match="twice"):
        blocks.blocks_mesh(np.array([[0, 0, 0], [0, 0, 0]]), 1.0)
    with pytest.raises(ValueError, match="colours"):
        blocks.blocks_mesh(np.array([[0, 0, 0]]), 1.0, colors=np.zeros((2, 3)))
    empty = blocks.blocks_mesh(np.zeros((0, 3)), 1.0)
    assert empty.faces.shape == (0, 4) and empty.vertices.shape == (0, 3)


# -- .vox ---------------------------------------------------------------------------------
def parse_vox(data):
    """An independent reader: {'models': [(size, xyzi)], 'translations': {shape's model: t},
    'palette': (256,4)}, following the scene graph from transforms to shapes."""
    assert data[:4] == b"VOX " and struct.unpack_from("<i", data, 4)[0] == 150

    def read_string(offset):
        n = struct.unpack_from("<i", data, offset)[0]
        return data[offset + 4 : offset + 4 + n].decode(), offset + 4 + n

    def read_dict(offset):
        pairs = struct.unpack_from("<i", data, offset)[0]
        offset += 4
        out = {}
        for _ in range(pairs):
            key, offset = read_string(offset)
            out[key], offset = read_string(offset)
        return out, offset

    tag, content, children = data[8:12], *struct.unpack_from("<ii", data, 12)
    assert tag == b"MAIN" and content == 0 and 20 + children == len(data)
    offset, models, sizes, transforms, shapes, palette = 20, [], [], {}, {}, None
    while offset < len(data):
        tag = data[offset : offset + 4]
        content, nested = struct.unpack_from("<ii", data, offset + 4)
        body = offset + 12
        if tag == b"SIZE":
            sizes.append(struct.unpack_from("<iii", data, body))
        elif tag == b"XYZI":
            n = struct.unpack_from("<i", data, body)[0]
            models.append(np.frombuffer(data, np.uint8, 4 * n, body + 4).reshape(n, 4))
        elif tag == b"nTRN":
            node = struct.unpack_from("<i", data, body)[0]
            _, at = read_dict(body + 4)
            child, reserved, _layer, frames = struct.unpack_from("<iiii", data, at)
            assert reserved == -1 and frames == 1
            frame, _ = read_dict(at + 16)
            transforms[child] = tuple(int(v) for v in frame["_t"].split()) if "_t" in frame else (0, 0, 0)
        elif tag == b"nSHP":
            node = struct.unpack_from("<i", data, body)[0]
            _, at = read_dict(body + 4)
            assert struct.unpack_from("<i", data, at)[0] == 1
            shapes[node] = struct.unpack_from("<i", data, at + 4)[0]
        elif tag == b"RGBA":
            palette = np.frombuffer(data, np.uint8, 1024, body).reshape(256, 4)
        offset = body + content + nested
    assert len(sizes) == len(models) and palette is not None
    translations = {shapes[node]: t for node, t in transforms.items() if node in shapes}
    return {"models": list(zip(sizes, models)), "translations": translations, "palette": palette}


def voxels_of(parsed):
    """World voxel -> palette colour (r,g,b) of a parsed file."""
    out = {}
    for m, (size, xyzi) in enumerate(parsed["models"]):
        assert all(0 < s <= 256 and s % 2 == 0 for s in size), size
        assert np.all(xyzi[:, :3] < np.array(size)) and np.all(xyzi[:, 3] >= 1)
        corner = np.array(parsed["translations"][m]) - np.array(size) // 2
        for x, y, z, c in xyzi.astype(int):
            key = tuple(corner + (x, y, z))
            assert key not in out
            out[key] = tuple(parsed["palette"][c - 1, :3])
    return out


def test_vox_round_trip_with_exact_palette(tmp_path):
    ijk = CASES["sparse"]
    rng = np.random.default_rng(7)
    choices = rng.random((40, 3))  # 40 distinct colours: kept exactly
    colors = choices[rng.integers(0, 40, len(ijk))]
    path = tmp_path / "a.vox"
    assert vox.write_vox(str(path), ijk, colors) == 1
    assert os.listdir(tmp_path) == ["a.vox"]
    got = voxels_of(parse_vox(path.read_bytes()))
    low = ijk.min(axis=0)
    srgb = vox.linear_to_srgb8(colors)
    expected = {tuple(v): tuple(c) for v, c in zip(ijk, srgb)}
    # The file's voxels are the input's, up to the one shift that puts the minimum at its corner.
    shift = np.array(list(got)).min(axis=0) - low
    assert {tuple(np.array(k) - shift): c for k, c in got.items()} == expected


def test_vox_splits_into_models_of_at_most_256():
    ijk = np.array([[x, 0, 0] for x in range(600)] + [[0, 300, 5], [0, 0, 299]])
    parsed = parse_vox(vox.vox_bytes(ijk)[0])
    assert len(parsed["models"]) == 5  # x: 3 blocks of 256; the two far voxels: one block each
    got = voxels_of(parsed)
    shift = np.array(list(got)).min(axis=0) - ijk.min(axis=0)
    assert {tuple(np.array(k) - shift) for k in got} == {tuple(v) for v in ijk}
    assert set(got.values()) == {vox.DEFAULT_COLOR}


def test_vox_palette_quantised_from_many_colours():
    """Thousands of colours around a few hues (as a textured model has): the median-cut
    palette has at most 255 entries and fits them better than a uniform 6x7x6 palette."""
    g = np.arange(20)
    ijk = np.stack(np.meshgrid(g, g, g, indexing="ij"), -1).reshape(-1, 3)
    rng = np.random.default_rng(11)
    hues = rng.integers(30, 226, size=(12, 3))
    srgb_wanted = np.clip(hues[rng.integers(0, 12, len(ijk))] + rng.integers(-25, 26, (len(ijk), 3)), 0, 255)
    assert len(np.unique(srgb_wanted, axis=0)) > 5000
    linear = ((srgb_wanted / 255.0 + 0.055) / 1.055) ** 2.4
    got = voxels_of(parse_vox(vox.vox_bytes(ijk, linear)[0]))
    assert len(set(got.values())) <= 255
    shift = np.array(list(got)).min(axis=0)
    error = np.array([np.subtract(got[tuple(v + shift)], c, dtype=float) for v, c in zip(ijk, srgb_wanted)])
    levels = np.array([6, 7, 6])
    uniform = np.round(np.round(srgb_wanted / 255.0 * (levels - 1)) / (levels - 1) * 255.0)
    assert np.mean(error**2) < np.mean((uniform - srgb_wanted) ** 2)


def test_vox_refuses_nothing():
    with pytest.raises(ValueError, match="no voxels"):
        vox.vox_bytes(np.zeros((0, 3)))
