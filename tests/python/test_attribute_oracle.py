# SPDX-License-Identifier: GPL-3.0-or-later
# The numpy oracle of the attribute definition (attribute_oracle.py) against answers worked
# out by hand, before any method is compared with it (test_attributes.py).
import numpy as np
import pytest

from attribute_oracle import sample_texture, srgb_to_linear, voxel_attributes

RED, BLUE = [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]


def test_two_triangles_meeting_inside_one_voxel_are_area_weighted():
    # Both lie inside voxel (0,0,0) (z = 0.5), no touch of a neighbour: red area 0.18, blue 0.3.
    v = [[0.1, 0.1, 0.5], [0.7, 0.1, 0.5], [0.1, 0.7, 0.5], [0.7, 0.1, 0.5], [0.9, 0.9, 0.5], [0.1, 0.7, 0.5]]
    t = [[0, 1, 2], [3, 4, 5]]
    colors = [RED, RED, RED, BLUE, BLUE, BLUE]
    ijk, values = voxel_attributes(v, t, (0, 0, 0), 1.0, (2, 2, 2), colors=colors)
    assert ijk.tolist() == [[0, 0, 0]]
    red, blue = 0.18 + 1e-6, 0.3 + 1e-6
    np.testing.assert_allclose(values["color"][0], [red / (red + blue), 0, blue / (red + blue)], atol=1e-12)
    np.testing.assert_allclose(values["normal"][0], [0, 0, 1], atol=1e-12)


def test_triangle_on_a_voxel_face_colours_both_sides_alike():
    # In the plane z = 1, the face between voxels (0,0,0) and (0,0,1): both hold the whole
    # triangle, so both get the colour at its centroid (the mean of its corners' colours).
    v = [[0.2, 0.2, 1.0], [0.8, 0.2, 1.0], [0.2, 0.8, 1.0]]
    colors = [[1, 0, 0], [0, 1, 0], [0, 0, 1]]
    ijk, values = voxel_attributes(v, [[0, 1, 2]], (0, 0, 0), 1.0, (2, 2, 2), colors=colors)
    assert ijk.tolist() == [[0, 0, 0], [0, 0, 1]]
    np.testing.assert_allclose(values["color"], np.full((2, 3), 1 / 3), atol=1e-12)


def test_touch_only_voxel_takes_the_touching_segment_midpoint():
    # A triangle with its edge x = 1 on the face of voxel (1,0,0): that voxel holds only the
    # segment (0.2..0.6 in y), whose midpoint's colour is the mean of the two corners.
    v = [[0.5, 0.2, 0.5], [1.0, 0.2, 0.5], [1.0, 0.6, 0.5]]
    colors = [[0, 0, 0], [1, 0, 0], [0, 1, 0]]
    ijk, values = voxel_attributes(v, [[0, 1, 2]], (0, 0, 0), 1.0, (2, 1, 1), colors=colors)
    assert ijk.tolist() == [[0, 0, 0], [1, 0, 0]]
    np.testing.assert_allclose(values["color"][1], [0.5, 0.5, 0], atol=1e-12)


def test_linear_colour_integrates_over_the_voxels():
    # Sum over voxels of (clipped area) x value = the triangle's area x its centroid colour,
    # for a colour linear over a triangle crossing many voxels.
    rng = np.random.default_rng(3)
    v = rng.uniform(0.3, 7.7, size=(3, 3))
    colors = rng.uniform(0, 1, size=(3, 3))
    ijk, values = voxel_attributes(v, [[0, 1, 2]], (0, 0, 0), 1.0, (8, 8, 8), colors=colors)
    from attribute_oracle import clipped_pairs

    _, voxels, weight, _ = clipped_pairs(np.asarray(v)[None], (8, 8, 8))
    key = {tuple(x): w for x, w in zip(voxels.tolist(), weight)}
    total = sum((key[tuple(x)] - 1e-6) * c for x, c in zip(ijk.tolist(), values["color"]))
    area = 0.5 * np.linalg.norm(np.cross(v[1] - v[0], v[2] - v[0]))
    assert len(ijk) > 10
    # Each pair's 1e-6 weight moves its voxel's mean by at most 1e-6 / its area.
    np.testing.assert_allclose(total, area * colors.mean(axis=0), rtol=0, atol=1e-6 * len(voxels))
    assert not np.allclose(total, area * colors[0])  # the colour does vary


def test_texture_sampling_is_bilinear_with_repeat_wrap():
    texels = np.arange(2 * 4 * 3, dtype=np.float64).reshape(2, 4, 3)
    # Texel (row 1, column 2)'s centre: u = 2.5/4, v = 1 - 1.5/2.
    np.testing.assert_allclose(sample_texture(texels, np.array([[2.5 / 4, 0.25]])), texels[1:2, 2])
    # Halfway between column 3 and column 0 (wrapped) on row 0.
    halfway = sample_texture(texels, np.array([[1.0, 0.75]]))
    np.testing.assert_allclose(halfway[0], 0.5 * (texels[0, 3] + texels[0, 0]))
    assert srgb_to_linear(1.0) == pytest.approx(1.0) and srgb_to_linear(0.5) == pytest.approx(0.21404, abs=1e-5)
