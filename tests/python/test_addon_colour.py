# SPDX-License-Identifier: GPL-3.0-or-later
"""The add-on's colour combining (core/colour.py, no bpy): which form a group's colour takes,
and that the per-corner form gives the same voxels' colours as hyvox.voxelize would for
each source on its own."""

import os
import sys

import numpy as np

import hyvox

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "addon"))

from hyvox_blender.core.colour import PartColour, combine, sample_bilinear  # noqa: E402

TRIANGLE = (np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0]], np.float32), np.array([[0, 1, 2]], np.uint32))


def textured_part(offset, texture, key="img"):
    v, t = TRIANGLE
    uvs = np.array([[0.1, 0.2], [0.9, 0.3], [0.4, 0.8]], np.float32)
    return (
        v + offset,
        t,
        PartColour(
            uvs=uvs,
            texture=texture,
            texture_key=key,
            textured=np.array([True]),
            corner_colors=np.zeros((3, 4), np.float32),
        ),
    )


def test_no_colour_gives_no_arguments():
    _, _, kwargs, warning = combine([(*TRIANGLE, None), (*TRIANGLE, None)])
    assert kwargs == {} and warning == ""


def test_one_image_everywhere_stays_a_texture_on_unshared_vertices():
    texture = np.random.default_rng(1).integers(0, 256, (8, 8, 3), dtype=np.uint8)
    parts = [textured_part(0.0, texture), textured_part(2.0, texture)]
    vertices, triangles, kwargs, warning = combine(parts)
    assert warning == "" and set(kwargs) == {"uvs", "texture"}
    assert len(vertices) == len(kwargs["uvs"]) == 6
    # The same voxels and colours as the parts merged by hand with shared UVs.
    merged = np.concatenate([TRIANGLE[0], TRIANGLE[0] + 2.0])
    direct = hyvox.voxelize(
        merged,
        np.array([[0, 1, 2], [3, 4, 5]], np.uint32),
        resolution=16,
        uvs=np.concatenate([parts[0][2].uvs, parts[1][2].uvs]),
        texture=texture,
        attributes="color",
    )
    combined = hyvox.voxelize(vertices, triangles, resolution=16, attributes="color", **kwargs)
    np.testing.assert_array_equal(direct.coords(), combined.coords())
    np.testing.assert_allclose(direct.attributes()["color"], combined.attributes()["color"], atol=1e-6)


def test_mixed_sources_become_corner_colours_with_a_warning():
    texture = np.random.default_rng(2).integers(0, 256, (8, 8, 3), dtype=np.uint8)
    v, t = TRIANGLE
    flat = PartColour(corner_colors=np.tile(np.float32([0.2, 0.4, 0.6, 1.0]), (3, 1)))
    part = textured_part(2.0, texture)
    vertices, triangles, kwargs, warning = combine([(v, t, flat), part, (v + 4.0, t, None)])
    assert set(kwargs) == {"colors"} and "corners" in warning
    colors = kwargs["colors"]
    assert colors.shape == (9, 3) and len(triangles) == 3  # all opaque: RGB only
    np.testing.assert_allclose(colors[:3], flat.corner_colors[:, :3])
    np.testing.assert_allclose(colors[3:6], sample_bilinear(texture, part[2].uvs)[:, :3], atol=1e-6)
    np.testing.assert_allclose(colors[6:], np.full((3, 3), 0.8))  # no source: Blender's grey
    # A colour that is not opaque keeps the alpha (hyvox then writes an `alpha` grid).
    flat.corner_colors[0, 3] = 0.5
    assert combine([(v, t, flat)])[2]["colors"].shape == (3, 4)


def test_sample_bilinear_matches_hyvox_at_a_vertex_voxel():
    # A tiny triangle inside one voxel around one UV: hyvox's texture sample there equals ours.
    texture = np.random.default_rng(3).integers(0, 256, (5, 7, 3), dtype=np.uint8)
    uv = np.array([[0.37, 0.61]], np.float32)
    v = np.array([[0.4, 0.4, 0.5], [0.41, 0.4, 0.5], [0.4, 0.41, 0.5]], np.float32)
    grid = hyvox.voxelize(
        v,
        np.array([[0, 1, 2]], np.uint32),
        voxel_size=1.0,
        origin=(0, 0, 0),
        uvs=np.repeat(uv, 3, axis=0),
        texture=texture,
        attributes="color",
    )
    np.testing.assert_allclose(grid.attributes()["color"][0], sample_bilinear(texture, uv)[0, :3], atol=1e-6)
